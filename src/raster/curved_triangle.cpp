#include "raster/curved_triangle.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>

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

bool CurvedTriangle::missesRectangle(const glm::dvec2& centre, const glm::dvec2& half, int slefeSegments, int* culledPieces) const {
    const glm::dvec3 p(centre, 1.0);
    const int degree = 2 * m_order;
    // Per edge and slefe piece: +1 provably positive, -1 provably negative, 0 unknown. A piece is
    // provably of one sign when both its ends are (the enclosures are linear between them).
    std::array<std::array<int, Slefe::kMaxSegments>, 3> sign{};
    for (std::size_t e = 0; e < 3; ++e) {
        Bernstein lower, upper;
        lower.degree = upper.degree = degree;
        for (int k = 0; k <= degree; ++k) {
            const glm::dvec3& c = m_edge[e][std::size_t(k)];
            const double value = glm::dot(c, p), pad = std::abs(c.x) * half.x + std::abs(c.y) * half.y;
            lower.coefficients[std::size_t(k)] = value - pad, upper.coefficients[std::size_t(k)] = value + pad;
        }
        const Slefe below = slefeOf(lower, slefeSegments), above = slefeOf(upper, slefeSegments);
        for (int i = 0; i < slefeSegments; ++i) {
            const std::size_t a = std::size_t(i), b = std::size_t(i + 1);
            if (below.lower[a] > 0.0 && below.lower[b] > 0.0) sign[e][a] = 1;
            else if (above.upper[a] < 0.0 && above.upper[b] < 0.0) sign[e][a] = -1;
        }
    }
    int culled = 0;
    for (std::size_t i = 0; i < std::size_t(slefeSegments); ++i) {
        const bool hasPositive = sign[0][i] > 0 || sign[1][i] > 0 || sign[2][i] > 0;
        const bool hasNegative = sign[0][i] < 0 || sign[1][i] < 0 || sign[2][i] < 0;
        culled += hasPositive && hasNegative;
    }
    if (culledPieces) *culledPieces += culled;
    return culled == slefeSegments;
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
