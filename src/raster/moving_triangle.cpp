#include "raster/moving_triangle.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <limits>
#include <cmath>
#include <utility>

namespace streak::raster {

MovingTriangle::MovingTriangle(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close) {
    for (int i = 0; i < 3; ++i) {
        m_corner[i] = {double(open[i].x), double(open[i].y), double(open[i].w)};
        m_delta[i] = glm::dvec3(double(close[i].x), double(close[i].y), double(close[i].w)) - m_corner[i];
    }
    for (int e = 0; e < 3; ++e) {
        const int f = (e + 1) % 3;
        const MovingEdge edge = movingEdge(m_corner[e], m_delta[e], m_corner[f], m_delta[f]);
        m_a[e] = edge.a, m_b[e] = edge.b, m_c[e] = edge.c;
        m_termBound[e] = glm::abs(edge.a) + glm::abs(edge.b) + glm::abs(edge.c);
    }
    m_isStill = m_delta[0] == glm::dvec3(0.0) && m_delta[1] == glm::dvec3(0.0) && m_delta[2] == glm::dvec3(0.0);
}

HomogeneousSample MovingTriangle::fromEdges(const std::array<glm::dvec3, 3>& edges, const glm::dvec3& w, const glm::dvec2& ndc,
                                             bool isFront) {
    const glm::dvec3 p(ndc, 1.0);
    return fromEdgeValues({glm::dot(edges[0], p), glm::dot(edges[1], p), glm::dot(edges[2], p)}, w, isFront);
}

HomogeneousSample MovingTriangle::fromEdgeValues(const glm::dvec3& e, const glm::dvec3& w, bool isFront) {
    const double sum = e.x + e.y + e.z;
    HomogeneousSample s;
    s.isFrontFacing = isFront;
    if (sum == 0.0 || !std::isfinite(sum)) return s;
    s.bary = e / sum;
    s.viewDepth = glm::dot(s.bary, w);
    s.isValid = true;
    return s;
}

HomogeneousSample MovingTriangle::sample(double u, const glm::dvec2& ndc) const {
    const std::array<glm::dvec3, 3> edges{edgeVector(1, u), edgeVector(2, u), edgeVector(0, u)};
    const glm::dvec3 w(corner(0, u).z, corner(1, u).z, corner(2, u).z);
    return fromEdges(edges, w, ndc, glm::dot(corner(0, u), edges[0]) > 0.0);
}

bool MovingTriangle::isInsideAt(double u, const glm::dvec2& ndc, const std::array<double, 3>& values) const {
    return isInsideByEdges({edgeVector(0, u), edgeVector(1, u), edgeVector(2, u)}, ndc, values);
}

bool MovingTriangle::staysOutside(const std::array<Quadratic, 3>& edges, const glm::dvec2& ndc, int orientation) const {
    if (orientation == 0) return false;
    const glm::dvec3 size(std::abs(ndc.x), std::abs(ndc.y), 1.0);
    for (int e = 0; e < 3; ++e) {
        // The edge's largest value over the segment (a still triangle's a and b vanish, so it is
        // c), past twice the on-edge tolerance at its term bound: twice leaves room for rounding.
        Quadratic q = edges[std::size_t(e)];
        q.a *= orientation, q.b *= orientation, q.c *= orientation;
        const double most = q.maxOnUnitInterval();
        if (most < 0.0 && most < -2.0 * kOnEdgeTolerance * glm::dot(m_termBound[e], size)) return true;
    }
    return false;
}

bool MovingTriangle::stillRowRange(double y, int orientation, double& xLo, double& xHi) const {
    xLo = -std::numeric_limits<double>::infinity(), xHi = std::numeric_limits<double>::infinity();
    for (int e = 0; e < 3; ++e) {
        // staysOutside fails only where o (cx x + cy y + cz) >= -2 tol (|cx| |x| + |cy| |y| + |cz|),
        // so where o cx x >= r with the tolerance at |x| = 1.
        const glm::dvec3 c = m_c[e] * double(orientation);
        const double tolerance = 2.0 * kOnEdgeTolerance * (m_termBound[e].x + m_termBound[e].y * std::abs(y) + m_termBound[e].z);
        const double r = -tolerance - c.y * y - c.z;
        if (c.x > 0.0) xLo = std::max(xLo, r / c.x);
        else if (c.x < 0.0) xHi = std::min(xHi, r / c.x);
        else if (r > 0.0) return false;
    }
    return xLo <= xHi;
}

bool MovingTriangle::stillRowSection(double y, int orientation, double& xLo, double& xHi) const {
    xLo = -std::numeric_limits<double>::infinity(), xHi = std::numeric_limits<double>::infinity();
    for (int e = 0; e < 3; ++e) {
        // o (cx x + cy y + cz) >= 0, so o cx x >= -o (cy y + cz).
        const glm::dvec3 c = m_c[e] * double(orientation);
        const double r = -c.y * y - c.z;
        if (c.x > 0.0) xLo = std::max(xLo, r / c.x);
        else if (c.x < 0.0) xHi = std::min(xHi, r / c.x);
        else if (r > 0.0) return false;
    }
    return xLo < xHi;
}

int MovingTriangle::stillSpans(const std::array<Quadratic, 3>& edges, const glm::dvec2& ndc, double zNear, bool checkNearPlane,
                               std::array<double, 8>& bounds, RootCaseCounts* rootCases) const {
    // What solvedSpans computes when no corner moves: three constant quadratics (no roots, one
    // piece [0, 1]), their values and edge vectors at u = 1/2 the constant terms themselves.
    return stillSpansOf(isInsideByEdges(m_c, ndc, {edges[0].c, edges[1].c, edges[2].c}), ndc, zNear, checkNearPlane, bounds, rootCases);
}

int MovingTriangle::stillSpansOf(bool isInsideByItsEdges, const glm::dvec2& ndc, double zNear, bool checkNearPlane,
                                 std::array<double, 8>& bounds, RootCaseCounts* rootCases) const {
    if (rootCases) rootCases->constant += 3;
    bool inside = isInsideByItsEdges;
    if (inside && checkNearPlane) inside = sample(0.5, ndc).viewDepth >= zNear;
    if (!inside) return 0;
    bounds[0] = 0.0, bounds[1] = 1.0;
    return 2;
}

int MovingTriangle::solvedSpans(const std::array<Quadratic, 3>& q, const glm::dvec2& ndc, double zNear, bool checkNearPlane,
                                std::array<double, 8>& bounds, RootCaseCounts* rootCases) const {
    std::array<double, 8> breaks;
    int n = 0;
    breaks[n++] = 0.0;
    for (int e = 0; e < 3; ++e) {
        double roots[2];
        const int m = solveQuadratic(q[e], roots, rootCases);
        for (int i = 0; i < m; ++i)
            if (roots[i] > 0.0 && roots[i] < 1.0) breaks[n++] = roots[i];
    }
    breaks[n++] = 1.0;
    // At most 8 breaks: insertion sort.
    for (int i = 1; i < n; ++i)
        for (int j = i; j > 0 && breaks[j] < breaks[j - 1]; --j) std::swap(breaks[j], breaks[j - 1]);
    // An edge's on-edge tolerance at any u is at most kOnEdgeTolerance times its term bound's
    // scale (|edgeVector(e, u)| <= |a| + |b| + |c| componentwise); twice that leaves room for
    // rounding. Two edges beyond it with opposite signs put the sample outside, as
    // isInsideByEdges would find, without building the edge vectors at u.
    const glm::dvec3 size(std::abs(ndc.x), std::abs(ndc.y), 1.0);
    std::array<double, 3> clear;
    for (int e = 0; e < 3; ++e) clear[std::size_t(e)] = 2.0 * kOnEdgeTolerance * glm::dot(m_termBound[e], size);
    int count = 0;
    bool wasInside = false;
    for (int i = 0; i + 1 < n; ++i) {
        if (!(breaks[i + 1] > breaks[i])) continue;
        const double u = 0.5 * (breaks[i] + breaks[i + 1]);
        const double e0 = q[0](u), e1 = q[1](u), e2 = q[2](u);
        const bool isClearlyOutside = (e0 > clear[0] || e1 > clear[1] || e2 > clear[2]) && (e0 < -clear[0] || e1 < -clear[1] || e2 < -clear[2]);
        bool inside = !isClearlyOutside && isInsideAt(u, ndc, {e0, e1, e2});
        if (inside && checkNearPlane) inside = sample(u, ndc).viewDepth >= zNear;
        if (inside != wasInside) bounds[count++] = breaks[i];
        wasInside = inside;
    }
    if (wasInside) bounds[count++] = 1.0;
    return count;
}

namespace {

glm::dvec3 xywOf(const glm::vec4& c) { return {c.x, c.y, c.w}; }

}  // namespace

std::array<double, 4> orientationBernstein(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close) {
    std::array<double, 4> coefficients{};
    for (int k = 0; k <= 3; ++k) {
        double sum = 0.0;
        int count = 0;
        for (int mask = 0; mask < 8; ++mask) {
            if (std::popcount(unsigned(mask)) != k) continue;
            const glm::dvec3 r0 = xywOf(mask & 1 ? close[0] : open[0]);
            const glm::dvec3 r1 = xywOf(mask & 2 ? close[1] : open[1]);
            const glm::dvec3 r2 = xywOf(mask & 4 ? close[2] : open[2]);
            sum += glm::dot(r0, glm::cross(r1, r2));
            ++count;
        }
        coefficients[std::size_t(k)] = sum / count;
    }
    return coefficients;
}

bool isBackFacingThroughout(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close) {
    // A still triangle's eight determinants are one: its coefficients are it (a mean of equal
    // terms keeps their sign), so one determinant says what all four say, at an eighth of the
    // cost on a still dense mesh's million segments.
    if (open == close) return glm::dot(xywOf(open[0]), glm::cross(xywOf(open[1]), xywOf(open[2]))) < 0.0;
    for (const double c : orientationBernstein(open, close))
        if (!(c < 0.0)) return false;
    return true;
}

}  // namespace streak::raster
