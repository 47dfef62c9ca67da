#pragma once

#include "raster/edge_equation.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>

namespace streak::raster {

// MovingTriangle is a triangle whose clip-space corners move linearly over one motion segment,
// c(u) = c_open + u (c_close - c_open), u in [0, 1]. In homogeneous 2D (Olano & Greer) the edge
// function of corners j, k is (c_j(u) x c_k(u)) . p with p = (x, y, 1): a quadratic in u whose
// coefficients are fixed vectors (Gribel et al. 2010). Keeping those vectors makes the edge
// equations at any sample, and barycentrics, depth and facing at any (u, p), a few dot products
// each, with no per-time triangle setup.
class MovingTriangle {
public:
    MovingTriangle(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close);

    // Edge e joins corners e and (e + 1) % 3; its value is the weight of the opposite corner.
    Quadratic edgeFunction(int e, const glm::dvec2& ndc) const {
        const glm::dvec3 p(ndc, 1.0);
        return {glm::dot(m_a[e], p), glm::dot(m_b[e], p), glm::dot(m_c[e], p)};
    }
    std::array<Quadratic, 3> edgeFunctions(const glm::dvec2& ndc) const { return {edgeFunction(0, ndc), edgeFunction(1, ndc), edgeFunction(2, ndc)}; }
    // The vectors the edge quadratics are made of, and their term bounds (|a| + |b| + |c|):
    // what a batch kernel (EdgeBatch) evaluates at many samples at once.
    struct EdgeTerms {
        const std::array<glm::dvec3, 3>&a, &b, &c, &bound;
    };
    EdgeTerms edgeTerms() const { return {m_a, m_b, m_c, m_termBound}; }
    // True when the triangle keeps the orientation `orientation` (+1: counter-clockwise, -1)
    // over u in [0, 1] and ndc stays outside one of its edges throughout, by more than the
    // inside test's on-edge tolerance: insideSpans would find no span there. It costs a third
    // of insideSpans, so methods ask it first where most samples of a box are empty.
    bool staysOutside(const glm::dvec2& ndc, int orientation) const { return staysOutside(edgeFunctions(ndc), ndc, orientation); }
    // The same from edgeFunctions(ndc), found already.
    bool staysOutside(const std::array<Quadratic, 3>& edges, const glm::dvec2& ndc, int orientation) const;
    // For a still triangle of orientation +1 or -1: the NDC x range [xLo, xHi] of the sample
    // row at height y outside which staysOutside(ndc, orientation) holds at every |ndc.x| <= 1
    // (each edge, a line, bounds x on one side; its on-edge tolerance is taken at |x| = 1, so the
    // range is a little wider than the exact one). Returns false when the whole row stays
    // outside. A box loop then visits only the row's samples in range, a rasterizer's span.
    bool stillRowRange(double y, int orientation, double& xLo, double& xHi) const;
    // For a still triangle of orientation +1 or -1: its exact cross-section [xLo, xHi] (NDC x)
    // of the horizontal line at height y, where every edge function has the orientation's sign.
    // Returns false when the line misses it. A line sample's covered length, with no on-edge
    // rule: an edge meets a line in one point, which has no length.
    bool stillRowSection(double y, int orientation, double& xLo, double& xHi) const;
    // Perspective-correct barycentrics, view depth and facing at time u and point ndc: equal to
    // evaluateHomogeneous() of the corners at u.
    HomogeneousSample sample(double u, const glm::dvec2& ndc) const;
    // A still triangle's sample() at the point whose edge functions are `edges`
    // (edgeFunctions(ndc), or an EdgeBatch's): the same values, without evaluating them again.
    HomogeneousSample stillSample(const std::array<Quadratic, 3>& edges) const {
        return fromEdgeValues({edges[1].c, edges[2].c, edges[0].c}, {m_corner[0].z, m_corner[1].z, m_corner[2].z},
                              glm::dot(m_corner[0], m_c[1]) > 0.0);
    }
    // sample() at ndc and at ndc + offsets[i] (the neighbours a texture footprint needs), at
    // the cost of little more than one: the edge vectors at u are shared.
    template <std::size_t N>
    void sampleWithNeighbours(double u, const glm::dvec2& ndc, const std::array<glm::dvec2, N>& offsets, HomogeneousSample& centre,
                              std::array<HomogeneousSample, N>& neighbours) const {
        const std::array<glm::dvec3, 3> edges{edgeVector(1, u), edgeVector(2, u), edgeVector(0, u)};
        const glm::dvec3 w(corner(0, u).z, corner(1, u).z, corner(2, u).z);
        const bool isFront = glm::dot(corner(0, u), edges[0]) > 0.0;
        centre = fromEdges(edges, w, ndc, isFront);
        for (std::size_t i = 0; i < N; ++i) neighbours[i] = fromEdges(edges, w, ndc + offsets[i], isFront);
    }
    // The exact spans of u in [0, 1] during which the sample at ndc lies inside the triangle
    // (Gribel et al. 2010): between consecutive roots of the three edge equations and the ends
    // the sample is inside where all three edge functions share a sign (either orientation, so
    // a triangle turning over is handled) and the triangle lies beyond the near plane
    // (view depth >= zNear; checked only when checkNearPlane is set, since depth on the
    // triangle is a convex combination of its corners'). Writes start/end pairs to `bounds`,
    // returns how many values it wrote (even, at most 8).
    int insideSpans(const glm::dvec2& ndc, double zNear, bool checkNearPlane, std::array<double, 8>& bounds,
                    RootCaseCounts* rootCases = nullptr) const {
        return insideSpans(edgeFunctions(ndc), ndc, zNear, checkNearPlane, bounds, rootCases);
    }
    // The same from the edge functions at ndc, edgeFunctions(ndc), found already (by a batch
    // that also asked staysOutside): the same spans, without evaluating them again.
    int insideSpans(const std::array<Quadratic, 3>& edges, const glm::dvec2& ndc, double zNear, bool checkNearPlane,
                    std::array<double, 8>& bounds, RootCaseCounts* rootCases = nullptr) const {
        return m_isStill ? stillSpans(edges, ndc, zNear, checkNearPlane, bounds, rootCases)
                         : solvedSpans(edges, ndc, zNear, checkNearPlane, bounds, rootCases);
    }
    // A still triangle's spans when whether the sample is inside by its edges (isInsideByEdges
    // of the constant edge vectors and values) is known already (EdgeBatch finds it in lanes).
    int stillSpansOf(bool isInsideByItsEdges, const glm::dvec2& ndc, double zNear, bool checkNearPlane, std::array<double, 8>& bounds,
                     RootCaseCounts* rootCases = nullptr) const;
    // insideSpans by solving the edge equations, whether or not the triangle moves: the general
    // path, which a still triangle's shortcut must equal (tested bit for bit).
    int solvedSpans(const glm::dvec2& ndc, double zNear, bool checkNearPlane, std::array<double, 8>& bounds,
                    RootCaseCounts* rootCases = nullptr) const {
        return solvedSpans(edgeFunctions(ndc), ndc, zNear, checkNearPlane, bounds, rootCases);
    }

    // No corner moves over the segment: the edge functions are constants, and the sample is
    // inside for all of [0, 1] or none of it. insideSpans and staysOutside then take a plain
    // rasterizer's path (three dot products and the same on-edge rule), with the same results:
    // the moving arithmetic with zero motion terms is exactly the constant term.
    bool isStill() const { return m_isStill; }

    // Counter-clockwise (front facing) at time u, for corners in front of the eye.
    bool isFrontFacing(double u) const { return glm::dot(corner(0, u), edgeVector(1, u)) > 0.0; }

private:
    int stillSpans(const std::array<Quadratic, 3>& edges, const glm::dvec2& ndc, double zNear, bool checkNearPlane, std::array<double, 8>& bounds,
                   RootCaseCounts* rootCases) const;
    int solvedSpans(const std::array<Quadratic, 3>& edges, const glm::dvec2& ndc, double zNear, bool checkNearPlane, std::array<double, 8>& bounds,
                    RootCaseCounts* rootCases) const;
    bool isInsideAt(double u, const glm::dvec2& ndc, const std::array<double, 3>& values) const;
    static HomogeneousSample fromEdges(const std::array<glm::dvec3, 3>& edges, const glm::dvec3& w, const glm::dvec2& ndc, bool isFront);
    // From the values e of the edges opposite each corner (edges 1, 2, 0).
    static HomogeneousSample fromEdgeValues(const glm::dvec3& e, const glm::dvec3& w, bool isFront);
    // (A still triangle's are its constants: with zero motion terms the sums below are exactly
    // them, and the shading of a still frame asks for them at every sample.)
    glm::dvec3 corner(int i, double u) const { return m_isStill ? m_corner[i] : m_corner[i] + u * m_delta[i]; }
    glm::dvec3 edgeVector(int e, double u) const { return m_isStill ? m_c[e] : (m_a[e] * u + m_b[e]) * u + m_c[e]; }

    std::array<glm::dvec3, 3> m_a, m_b, m_c;        ///< edge e: (a u^2 + b u + c) . p
    std::array<glm::dvec3, 3> m_termBound;          ///< |a| + |b| + |c|: edge e's terms over u in [0, 1] are at most this
    std::array<glm::dvec3, 3> m_corner, m_delta;    ///< (x, y, w) at u = 0 and its change to u = 1
    bool m_isStill = false;                         ///< every m_delta zero
};

// The orientation of a moving triangle is det(c0, c1, c2)(u) of its corners (x, y, w), a cubic
// in u; the corners are linear in u, so the determinant is multilinear in them and its
// Bernstein coefficients (returned, k = 0..3) are the means of the determinants that take k
// corners from the end and 3 - k from the start. The cubic lies between the least and the
// greatest of them on [0, 1] (convex hull property).
std::array<double, 4> orientationBernstein(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close);

// True when the triangle (all corners in front of the eye) is seen from its back at every u in
// [0, 1]: every Bernstein coefficient of its orientation is negative.
bool isBackFacingThroughout(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close);

}  // namespace streak::raster
