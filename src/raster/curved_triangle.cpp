#include "raster/curved_triangle.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace streak::raster {

namespace {

double binomial(int n, int k) {
    double b = 1.0;
    for (int i = 1; i <= k; ++i) b = b * double(n - k + i) / double(i);
    return b;
}

}  // namespace

CurvedTriangle::CurvedTriangle(int order, const std::array<Corner, 3>& control) : m_order(order) {
    assert(order >= 1 && order <= kMaxOrder);
    const int n = order;
    for (std::size_t i = 0; i < 3; ++i)
        for (int j = 0; j <= n; ++j) {
            const glm::vec4& c = control[i][std::size_t(j)];
            m_control[i][std::size_t(j)] = glm::dvec3(c.x, c.y, c.w);
        }
    if (order == 1) m_linear.emplace(std::array{control[0][0], control[1][0], control[2][0]}, std::array{control[0][1], control[1][1], control[2][1]});
    for (int e = 0; e < 3; ++e) {
        const auto& p = m_control[std::size_t(e)];
        const auto& q = m_control[std::size_t((e + 1) % 3)];
        for (int k = 0; k <= 2 * n; ++k) {
            glm::dvec3 sum(0.0);
            for (int i = std::max(0, k - n); i <= std::min(k, n); ++i)
                sum += (binomial(n, i) * binomial(n, k - i) / binomial(2 * n, k)) * glm::cross(p[std::size_t(i)], q[std::size_t(k - i)]);
            m_edge[std::size_t(e)][std::size_t(k)] = sum;
        }
    }
}

Bernstein CurvedTriangle::edgeFunction(int e, const glm::dvec2& ndc) const {
    const glm::dvec3 p(ndc, 1.0);
    Bernstein b;
    b.degree = 2 * m_order;
    for (int k = 0; k <= b.degree; ++k) b.coefficients[std::size_t(k)] = glm::dot(m_edge[std::size_t(e)][std::size_t(k)], p);
    return b;
}

glm::dvec3 CurvedTriangle::corner(int i, double u) const {
    auto c = m_control[std::size_t(i)];
    for (int level = m_order; level > 0; --level)
        for (int j = 0; j < level; ++j) c[std::size_t(j)] = c[std::size_t(j)] + u * (c[std::size_t(j + 1)] - c[std::size_t(j)]);
    return c[0];
}

CurvedTriangle::PieceMask CurvedTriangle::piecesMissedByEdges(const glm::dvec2& centre, const glm::dvec2& half, int segments) const {
    const glm::dvec3 p(centre, 1.0);
    const int degree = 2 * m_order;
    // Per piece: whether some edge is provably positive on it, and whether some edge is
    // provably negative. A piece is provably of one sign when both its ends are (the
    // enclosures are linear between them).
    PieceMask positive = 0, negative = 0;
    for (std::size_t e = 0; e < 3; ++e) {
        Bernstein lower, upper;
        lower.degree = upper.degree = degree;
        for (int k = 0; k <= degree; ++k) {
            const glm::dvec3& c = m_edge[e][std::size_t(k)];
            const double value = glm::dot(c, p), pad = std::abs(c.x) * half.x + std::abs(c.y) * half.y;
            lower.coefficients[std::size_t(k)] = value - pad, upper.coefficients[std::size_t(k)] = value + pad;
        }
        const Slefe below = slefeOf(lower, segments), above = slefeOf(upper, segments);
        for (int i = 0; i < segments; ++i) {
            const std::size_t a = std::size_t(i), b = std::size_t(i + 1);
            if (below.lower[a] > 0.0 && below.lower[b] > 0.0) positive |= PieceMask(1) << i;
            else if (above.upper[a] < 0.0 && above.upper[b] < 0.0) negative |= PieceMask(1) << i;
        }
    }
    return positive & negative;
}

CurvedTriangle::FrustumSlefes CurvedTriangle::frustumSlefes(int segments) const {
    FrustumSlefes s;
    s.segments = segments;
    for (std::size_t i = 0; i < 3; ++i) {
        std::array<Bernstein, 4> distance;
        for (Bernstein& d : distance) d.degree = m_order;
        for (int k = 0; k <= m_order; ++k) {
            const glm::dvec3& c = m_control[i][std::size_t(k)];
            const std::size_t j = std::size_t(k);
            distance[0].coefficients[j] = c.x + c.z, distance[1].coefficients[j] = c.x - c.z;
            distance[2].coefficients[j] = c.y + c.z, distance[3].coefficients[j] = c.y - c.z;
        }
        for (std::size_t plane = 0; plane < 4; ++plane) s.corner[i][plane] = slefeOf(distance[plane], segments);
    }
    return s;
}

CurvedTriangle::PieceMask CurvedTriangle::piecesMissedByCorners(const FrustumSlefes& slefes, const glm::dvec2& centre, const glm::dvec2& half) {
    const int segments = slefes.segments;
    PieceMask missed = 0;
    for (int axis = 0; axis < 2; ++axis) {
        const std::size_t plus = std::size_t(2 * axis), minus = plus + 1;  // x + w, x - w (or y)
        for (const bool isHighSide : {false, true}) {
            const double a = centre[axis] + (isHighSide ? half[axis] : -half[axis]);
            if (!(a >= -1.0 && a <= 1.0)) continue;
            const double toPlus = 0.5 * (1.0 - a), toMinus = 0.5 * (1.0 + a);
            // Outside the low side: x - a w < 0, an upper bound below zero; outside the high
            // side: x - a w > 0, a lower bound above zero. Bit e: all three corners are outside
            // at breakpoint e; a piece is outside where both its ends are.
            PieceMask outside = 0;
            for (int e = 0; e <= segments; ++e) {
                bool allOutside = true;
                for (std::size_t i = 0; i < 3 && allOutside; ++i) {
                    const Slefe& p = slefes.corner[i][plus];
                    const Slefe& m = slefes.corner[i][minus];
                    const std::size_t k = std::size_t(e);
                    allOutside = isHighSide ? toPlus * p.lower[k] + toMinus * m.lower[k] > 0.0 : toPlus * p.upper[k] + toMinus * m.upper[k] < 0.0;
                }
                if (allOutside) outside |= PieceMask(1) << e;
            }
            missed |= outside & (outside >> 1) & allPieces(segments);
        }
    }
    return missed;
}

int CurvedTriangle::insideSpans(const glm::dvec2& ndc, double zNear, bool checkNearPlane, RootSolver solver,
                                std::array<double, kMaxSpanBounds>& bounds, BernsteinRootCounts* counts) const {
    if (m_linear) {
        std::array<double, 8> linear;
        const int count = m_linear->insideSpans(ndc, zNear, checkNearPlane, linear);
        std::copy(linear.begin(), linear.begin() + count, bounds.begin());
        return count;
    }
    std::array<double, kMaxSpanBounds> breaks;
    int n = 0;
    breaks[std::size_t(n++)] = 0.0;
    std::array<Bernstein, 3> edges;
    for (int e = 0; e < 3; ++e) {
        edges[std::size_t(e)] = edgeFunction(e, ndc);
        std::array<double, kMaxBernsteinDegree> roots;
        const int m = solver == RootSolver::ClosedForm ? rootsInClosedForm(edges[std::size_t(e)], roots, counts)
                                                       : rootsByBezierClipping(edges[std::size_t(e)], roots, counts);
        for (int i = 0; i < m; ++i)
            if (roots[std::size_t(i)] > 0.0 && roots[std::size_t(i)] < 1.0) breaks[std::size_t(n++)] = roots[std::size_t(i)];
    }
    breaks[std::size_t(n++)] = 1.0;
    std::sort(breaks.begin(), breaks.begin() + n);
    int count = 0;
    bool wasInside = false;
    for (int i = 0; i + 1 < n; ++i) {
        if (!(breaks[std::size_t(i + 1)] > breaks[std::size_t(i)])) continue;
        const double u = 0.5 * (breaks[std::size_t(i)] + breaks[std::size_t(i + 1)]);
        const std::array<glm::dvec3, 3> c = cornersAt(u);
        const std::array<glm::dvec3, 3> edgeVectors{glm::cross(c[0], c[1]), glm::cross(c[1], c[2]), glm::cross(c[2], c[0])};
        const glm::dvec3 p(ndc, 1.0);
        bool inside = isInsideByEdges(edgeVectors, ndc, {glm::dot(edgeVectors[0], p), glm::dot(edgeVectors[1], p), glm::dot(edgeVectors[2], p)});
        if (inside && checkNearPlane) inside = sample(u, ndc).viewDepth >= zNear;
        if (inside != wasInside) bounds[std::size_t(count++)] = breaks[std::size_t(i)];
        wasInside = inside;
    }
    if (wasInside) bounds[std::size_t(count++)] = 1.0;
    return count;
}

}  // namespace streak::raster
