#pragma once

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <array>

namespace streak::raster {

// SweptHull bounds where a moving triangle can cover a sample over its whole segment. With every
// corner in front of the eye at both ends (clip w > 0, so > 0 in between: w is linear in u), each
// corner's NDC path is the straight segment between its projected ends, and the triangle at any
// u lies in the convex hull of its six projected end corners. A box loop over a moving
// triangle's motion box then visits per sample row only the hull's x range: for a small triangle
// moving diagonally (a dense mesh under a camera pan) that is a thin band of the box, where
// MovingTriangle::staysOutside, which asks one edge at a time, culls little.
//
// The hull is widened by `margin()` so that it holds every sample MovingTriangle::insideSpans
// can find inside, on-edge tolerance included: that tolerance accepts a sample within
// d = 4 kOnEdgeTolerance (NDC, for |x|, |y| <= 1) of an edge's line, so at most
// d / sin(theta / 2) from a corner of angle theta. The margin takes a lower bound of that sine
// over the whole segment (from the orientation cubic's Bernstein bound and the longest sides),
// since a corner can be sharper in between than at either end; a triangle sharper than
// kMaxMargin allows gets no hull.
class SweptHull {
public:
    static constexpr double kMaxMargin = 1e-2;  ///< NDC: beyond this a hull is no tighter than the box

    // Builds the hull of the segment (corners open -> close). Returns false, leaving no hull,
    // when a corner is not in front of the eye at an end, the orientation cubic's Bernstein
    // coefficients do not share a sign (it may vanish: the triangle may turn over or degenerate)
    // or the margin would exceed kMaxMargin. extraMargin (NDC) widens it further: by how far
    // the given corners may be from the true ones (SweptPieces rounds a piece's ends to float).
    bool build(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, double extraMargin = 0.0);
    // The hull of the six projected end corners widened by `margin` (NDC), whatever the triangle
    // does in between: it holds the triangle at every u even where it turns over, though not the
    // on-edge tolerance's reach along the line it collapses onto (SweptPieces). Returns false,
    // leaving no hull, when a corner is not in front of the eye at an end or the six lie on a
    // line.
    bool buildAround(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, double margin);

    // The NDC x range [xLo, xHi] of the widened hull on the sample row at height y. Returns
    // false when the row misses it.
    bool rowRange(double y, double& xLo, double& xHi) const;

    double margin() const { return m_margin; }
    double area() const { return m_area; }  ///< NDC, unwidened
    int numVertices() const { return m_count; }

private:
    // The six projected end corners (open's, then close's); false where one is not in front of
    // the eye or not finite.
    static bool projectCorners(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, std::array<glm::dvec2, 6>& points);
    // The hull of `points` widened by m_margin, set already; false (no hull) where they lie on a line.
    bool setHull(const std::array<glm::dvec2, 6>& points);

    struct Edge {
        glm::dvec2 lo{0.0}, hi{0.0};  ///< its ends, the lower first
        double slope = 0.0;           ///< dx / dy (0 when level)
        bool isLevel = false;
    };
    std::array<glm::dvec2, 6> m_vertex{};  ///< counter-clockwise
    std::array<Edge, 6> m_edges{};         ///< m_vertex[i] to m_vertex[i + 1]
    int m_count = 0;
    double m_margin = 0.0;
    double m_area = 0.0;
    double m_yLo = 0.0, m_yHi = 0.0;  ///< the widened hull's height range
};

}  // namespace streak::raster
