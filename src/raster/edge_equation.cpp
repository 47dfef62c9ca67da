#include "raster/edge_equation.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace streak::raster {

namespace {

glm::dvec3 xyw(const glm::vec4& c) { return {double(c.x), double(c.y), double(c.w)}; }

}  // namespace

HomogeneousSample evaluateHomogeneous(const std::array<glm::vec4, 3>& clip, const glm::dvec2& ndc) {
    return evaluateHomogeneousXyw({xyw(clip[0]), xyw(clip[1]), xyw(clip[2])}, ndc);
}

HomogeneousSample evaluateHomogeneousXyw(const std::array<glm::dvec3, 3>& corners, const glm::dvec2& ndc) {
    const glm::dvec3 p(ndc, 1.0);
    const glm::dvec3 c0 = corners[0], c1 = corners[1], c2 = corners[2];
    const glm::dvec3 e(glm::dot(glm::cross(c1, c2), p), glm::dot(glm::cross(c2, c0), p), glm::dot(glm::cross(c0, c1), p));
    const double sum = e.x + e.y + e.z;
    HomogeneousSample s;
    // det(c0, c1, c2) = w0 w1 w2 * (twice the NDC area): its sign is the orientation.
    s.isFrontFacing = glm::dot(c0, glm::cross(c1, c2)) > 0.0;
    if (sum == 0.0 || !std::isfinite(sum)) return s;
    s.bary = e / sum;
    s.viewDepth = s.bary.x * c0.z + s.bary.y * c1.z + s.bary.z * c2.z;
    s.isValid = true;
    return s;
}

MovingEdge movingEdge(const glm::dvec3& p0, const glm::dvec3& dp, const glm::dvec3& q0, const glm::dvec3& dq) {
    // (p0 + u dp) x (q0 + u dq) = p0 x q0 + u (p0 x dq + dp x q0) + u^2 (dp x dq)
    return {glm::cross(dp, dq), glm::cross(p0, dq) + glm::cross(dp, q0), glm::cross(p0, q0)};
}

Quadratic movingEdgeFunction(const glm::vec4& a0, const glm::vec4& a1, const glm::vec4& b0, const glm::vec4& b1,
                             const glm::dvec2& ndc) {
    const glm::dvec3 p(ndc, 1.0);
    const MovingEdge e = movingEdge(xyw(a0), xyw(a1) - xyw(a0), xyw(b0), xyw(b1) - xyw(b0));
    return {glm::dot(e.a, p), glm::dot(e.b, p), glm::dot(e.c, p)};
}

int solveQuadratic(const Quadratic& q, double roots[2], RootCaseCounts* counts) {
    RootCaseCounts ignored;
    RootCaseCounts& count = counts ? *counts : ignored;
    const double scale = std::max({std::abs(q.a), std::abs(q.b), std::abs(q.c)});
    if (scale == 0.0) {
        ++count.constant;
        return 0;
    }
    // Treat a as zero when it is negligible next to b and c: the linear root is then the exact
    // one, where the quadratic formula would lose it to cancellation.
    if (std::abs(q.a) <= 1e-12 * scale) {
        if (q.b == 0.0) {
            ++count.constant;
            return 0;
        }
        ++count.linear;
        roots[0] = -q.c / q.b;
        return 1;
    }
    const double discriminant = q.b * q.b - 4.0 * q.a * q.c;
    if (discriminant < 0.0) {
        ++count.noRealRoot;
        return 0;
    }
    if (discriminant == 0.0) {
        ++count.doubleRoot;
        roots[0] = -q.b / (2.0 * q.a);
        return 1;
    }
    ++count.twoRoots;
    const double s = -0.5 * (q.b + std::copysign(std::sqrt(discriminant), q.b));
    double r0 = s / q.a;
    double r1 = s != 0.0 ? q.c / s : -r0;
    if (r0 > r1) std::swap(r0, r1);
    roots[0] = r0;
    roots[1] = r1;
    return 2;
}

// An edge within float precision of zero between two breaks passes through the sample all that
// span (a static edge on a sample: the input corners are floats, so "on" cannot mean exactly
// zero in double). Such a sample goes by the rasterizer's top-left rule (screen_triangle.cpp):
// to one of two triangles sharing the edge, and to a lone triangle only along its top or left
// side (inside right of the edge in raster x, or below a horizontal one).
bool isInsideByEdges(const std::array<glm::dvec3, 3>& edges, const glm::dvec2& ndc, const std::array<double, 3>& values) {
    std::array<bool, 3> isOn{};
    double orientation = 0.0;
    for (std::size_t e = 0; e < 3; ++e) {
        const glm::dvec3& v = edges[e];
        const double scale = std::abs(v.x * ndc.x) + std::abs(v.y * ndc.y) + std::abs(v.z);
        isOn[e] = std::abs(values[e]) <= kOnEdgeTolerance * scale;
        if (!isOn[e]) {
            if (orientation != 0.0 && (orientation > 0.0) != (values[e] > 0.0)) return false;
            orientation = values[e];
        }
    }
    if (orientation == 0.0) return true;  // every edge through the sample: a degenerate instant
    for (std::size_t e = 0; e < 3; ++e) {
        if (!isOn[e]) continue;
        // Inward gradient in NDC (y up); raster y points down.
        const glm::dvec3 v = edges[e] * (orientation > 0.0 ? 1.0 : -1.0);
        if (!(v.x > 0.0 || (v.x == 0.0 && v.y < 0.0))) return false;
    }
    return true;
}

glm::dvec2 ndcFromRaster(double rasterX, double rasterY, int width, int height) {
    return {2.0 * rasterX / width - 1.0, 1.0 - 2.0 * rasterY / height};
}

}  // namespace streak::raster
