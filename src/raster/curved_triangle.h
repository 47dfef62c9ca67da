#pragma once

#include "raster/bernstein.h"
#include "raster/edge_equation.h"
#include "raster/moving_triangle.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
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

    // The Edge-Tile test of Gribel et al. 2013, for a rectangle (NDC centre and half extents):
    // each edge function over the rectangle lies between its value at the centre with every
    // control coefficient padded down or up by |c_k.x| hx + |c_k.y| hy (it is linear in the
    // point), and those two polynomials between their slefes. On a piece of the shutter where
    // one edge is provably positive and another provably negative, no point of the rectangle
    // is inside (inside means all three of one sign, either orientation). True when that
    // holds on every piece: the triangle misses the rectangle for the whole shutter. Adds the
    // pieces it proves missed (the culled time spans) to *culledPieces when given.
    bool missesRectangle(const glm::dvec2& centre, const glm::dvec2& half, int slefeSegments = 4, int* culledPieces = nullptr) const;

private:
    int m_order;
    std::array<std::array<glm::dvec3, kMaxOrder + 1>, 3> m_control;  ///< (x, y, w)
    std::optional<MovingTriangle> m_linear;  ///< order 1
    std::array<std::array<glm::dvec3, 2 * kMaxOrder + 1>, 3> m_edge;  ///< edge e's control vectors
};

}  // namespace streak::raster
