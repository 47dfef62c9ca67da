#pragma once

#include "raster/bernstein.h"
#include "raster/edge_equation.h"
#include "raster/moving_triangle.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <optional>

namespace streak::raster {

// How the roots of the edge equations are found (Gribel et al. 2013 compare both).
enum class RootSolver : std::uint8_t { BezierClipping, ClosedForm };

// CurvedTriangle is a triangle whose clip-space corners (x, y, w) follow Bezier curves of order
// n <= 3 over one piece of the shutter, u in [0, 1] (Gribel et al. 2013). In homogeneous 2D the
// edge function of corners j, k is (c_j(u) x c_k(u)) . (x, y, 1), a Bernstein polynomial of
// degree 2n whose control vectors are
//   c_k = sum_{i + l = k} C(n, i) C(n, l) / C(2n, k) (p_i x q_l),
// so a sample may enter and leave an edge up to 2n times. For n = 1 it is MovingTriangle's
// quadratic. Projection is linear in homogeneous coordinates, so a corner whose world path is
// a Bezier curve under a static camera has the projected control points as its clip path.
// Order 1 is handed to MovingTriangle whole, so linear motion gives its spans bit for bit.
class CurvedTriangle {
public:
    static constexpr int kMaxOrder = 3;
    // At most 3 edges x 2n roots + the two ends between which the sample is inside or not.
    static constexpr int kMaxSpanBounds = 3 * 2 * kMaxOrder + 2;
    using Corner = std::array<glm::vec4, kMaxOrder + 1>;  ///< clip-space control points, order + 1 used

    CurvedTriangle(int order, const std::array<Corner, 3>& control);

    int order() const { return m_order; }
    // Edge e joins corners e and (e + 1) % 3; its value is the weight of the opposite corner.
    Bernstein edgeFunction(int e, const glm::dvec2& ndc) const;
    // Corner i's (x, y, w) at u (de Casteljau).
    glm::dvec3 corner(int i, double u) const;
    // Perspective-correct barycentrics, view depth and facing at time u and point ndc.
    HomogeneousSample sample(double u, const glm::dvec2& ndc) const {
        return m_linear ? m_linear->sample(u, ndc) : evaluateHomogeneousXyw(cornersAt(u), ndc);
    }
    std::array<glm::dvec3, 3> cornersAt(double u) const { return {corner(0, u), corner(1, u), corner(2, u)}; }

    // The exact spans of u in [0, 1] during which the sample at ndc lies inside the triangle:
    // between consecutive roots of the three edge equations (and the ends) it is inside where
    // the three edge functions share a sign (either orientation, isInsideByEdges) and, when
    // checkNearPlane is set, where it lies beyond the near plane at mid-span. Writes start/end
    // pairs to `bounds`; returns how many values it wrote (even).
    int insideSpans(const glm::dvec2& ndc, double zNear, bool checkNearPlane, RootSolver solver,
                    std::array<double, kMaxSpanBounds>& bounds, BernsteinRootCounts* counts = nullptr) const;

    // A bit per slefe piece of the shutter: bit i is piece [i, i + 1] / segments.
    using PieceMask = std::uint32_t;
    static PieceMask allPieces(int segments) { return (PieceMask(1) << segments) - 1; }

    // The Edge-Tile test of Gribel et al. 2013, for a rectangle (NDC centre and half extents):
    // each edge function over the rectangle lies between its value at the centre with every
    // control coefficient padded down or up by |c_k.x| hx + |c_k.y| hy (it is linear in the
    // point), and those two polynomials between their slefes. On a piece of the shutter where
    // one edge is provably positive and another provably negative, no point of the rectangle
    // is inside (inside means all three of one sign, either orientation). Returns the pieces
    // it proves missed.
    PieceMask piecesMissedByEdges(const glm::dvec2& centre, const glm::dvec2& half, int segments) const;

    // The Triangle-Tile test's setup (Gribel et al. 2013): slefes of each corner's signed
    // distance to the frustum planes x = -w, x = w, y = -w and y = w, i.e. of x + w, x - w,
    // y + w and y - w. A tile plane x = a w with a in [-1, 1] blends the first two,
    // x - a w = (1 - a) / 2 (x + w) + (1 + a) / 2 (x - w), and a blend with non-negative
    // weights of enclosures encloses the blend: the bounds for every tile come from these.
    struct FrustumSlefes {
        int segments = 0;
        std::array<std::array<Slefe, 4>, 3> corner;  ///< corner i: x + w, x - w, y + w, y - w
    };
    FrustumSlefes frustumSlefes(int segments) const;
    // The Triangle-Tile test: the pieces of the shutter on which all three corners lie outside
    // one plane of the frustum through the rectangle's sides. In homogeneous coordinates the
    // triangle is the convex hull of its corners, so it lies outside that plane too, and no
    // visible point of it (w > 0) projects into the rectangle. The rectangle lies within the
    // viewport (|ndc| <= 1); a side outside it proves nothing.
    static PieceMask piecesMissedByCorners(const FrustumSlefes& slefes, const glm::dvec2& centre, const glm::dvec2& half);

private:
    int m_order;
    std::array<std::array<glm::dvec3, kMaxOrder + 1>, 3> m_control;  ///< (x, y, w)
    std::optional<MovingTriangle> m_linear;  ///< order 1
    std::array<std::array<glm::dvec3, 2 * kMaxOrder + 1>, 3> m_edge;  ///< edge e's control vectors
};

}  // namespace streak::raster
