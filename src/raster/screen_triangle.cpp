#include "raster/screen_triangle.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace streak::raster {

PixelBounds pixelBoundsOfRaster(const glm::dvec2& lo, const glm::dvec2& hi, const Viewport& viewport) {
    PixelBounds b;
    b.x0 = int(std::clamp(std::floor(lo.x), 0.0, double(viewport.width)));
    b.y0 = int(std::clamp(std::floor(lo.y), 0.0, double(viewport.height)));
    b.x1 = int(std::clamp(std::floor(hi.x), -1.0, double(viewport.width - 1)));
    b.y1 = int(std::clamp(std::floor(hi.y), -1.0, double(viewport.height - 1)));
    return b;
}

glm::dvec2 rasterFromClip(const glm::vec4& clip, const Viewport& viewport) {
    const double invW = 1.0 / double(clip.w);
    return {(double(clip.x) * invW * 0.5 + 0.5) * viewport.width, (0.5 - double(clip.y) * invW * 0.5) * viewport.height};
}

PerspectiveSample ScreenTriangle::interpolate(const EdgeValues& e) const {
    // Screen-space barycentrics l_i = E_i / sum E; perspective correction divides by w per
    // vertex and renormalizes (attributes / w are affine in screen space).
    const double q0 = double(e[0]) * invEdgeSum * invW[0];
    const double q1 = double(e[1]) * invEdgeSum * invW[1];
    const double q2 = double(e[2]) * invEdgeSum * invW[2];
    const double sum = q0 + q1 + q2;
    PerspectiveSample s;
    s.invW = float(sum);
    if (sum > 0.0) s.bary = glm::vec3(float(q0 / sum), float(q1 / sum), float(q2 / sum));
    return s;
}

namespace {

// A raster point on the fixed-point grid.
std::int64_t snapped(double raster) { return std::llround(raster * double(kSubpixelScale)); }

// Twice the signed area of a triangle of snapped corners.
std::int64_t snappedArea2(const std::array<std::int64_t, 3>& x, const std::array<std::int64_t, 3>& y) {
    return (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
}

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

}  // namespace

bool setupScreenTriangle(const std::array<glm::vec4, 3>& clip, const Viewport& viewport, ScreenTriangle& out) {
    std::array<std::int64_t, 3> x{}, y{};
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 p = rasterFromClip(clip[i], viewport);
        x[i] = snapped(p.x);
        y[i] = snapped(p.y);
        out.invW[i] = 1.0f / clip[i].w;
    }
    const std::int64_t area2 = snappedArea2(x, y);
    if (area2 == 0) return false;
    // y points down in raster space, so counter-clockwise in NDC has negative area here.
    out.isFrontFacing = area2 < 0;
    const std::int64_t sign = area2 > 0 ? 1 : -1;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        // E_i(p) = cross(v_k - v_j, p - v_j): equals area2 at v_i, zero on edge jk.
        out.a[i] = -(y[k] - y[j]) * sign;
        out.b[i] = (x[k] - x[j]) * sign;
        out.c[i] = ((y[k] - y[j]) * x[j] - (x[k] - x[j]) * y[j]) * sign;
        // Top-left rule: the inside lies right of a left edge (a > 0) or below a top edge.
        const bool isTopLeft = out.a[i] > 0 || (out.a[i] == 0 && out.b[i] > 0);
        out.bias[i] = isTopLeft ? 0 : -1;
    }
    out.invEdgeSum = 1.0 / double(area2 * sign);
    const std::int64_t minX = std::min({x[0], x[1], x[2]}), maxX = std::max({x[0], x[1], x[2]});
    const std::int64_t minY = std::min({y[0], y[1], y[2]}), maxY = std::max({y[0], y[1], y[2]});
    // A sample of pixel p lies in [p, p+1) * scale, so these pixels may hold covered samples.
    out.bounds.x0 = int(std::max<std::int64_t>(0, minX >> kSubpixelBits));
    out.bounds.y0 = int(std::max<std::int64_t>(0, minY >> kSubpixelBits));
    out.bounds.x1 = int(std::min<std::int64_t>(viewport.width - 1, maxX >> kSubpixelBits));
    out.bounds.y1 = int(std::min<std::int64_t>(viewport.height - 1, maxY >> kSubpixelBits));
    return true;
}

void makeConservative(ScreenTriangle& tri, const Viewport& viewport) {
    // Snapping moves each corner by at most half a fixed-point unit per axis, so each edge line
    // by at most sqrt(2)/2 units; a margin of |a| + |b| moves it out by at least one unit.
    for (int i = 0; i < 3; ++i) tri.bias[i] = std::abs(tri.a[i]) + std::abs(tri.b[i]);
    tri.bounds.x0 = std::max(0, tri.bounds.x0 - 1), tri.bounds.y0 = std::max(0, tri.bounds.y0 - 1);
    tri.bounds.x1 = std::min(viewport.width - 1, tri.bounds.x1 + 1), tri.bounds.y1 = std::min(viewport.height - 1, tri.bounds.y1 + 1);
}

bool SnappedAwayTriangle::setup(const std::array<glm::vec4, 3>& clip, const Viewport& viewport) {
    std::array<std::int64_t, 3> x{}, y{};
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 p = rasterFromClip(clip[std::size_t(i)], viewport);
        if (!(std::abs(p.x) <= 1e9 && std::abs(p.y) <= 1e9)) return false;  // (and not NaN)
        m_corners[std::size_t(i)] = p;
        x[std::size_t(i)] = snapped(p.x), y[std::size_t(i)] = snapped(p.y);
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    if (snappedArea2(x, y) != 0) return false;
    m_area = cross(m_corners[1] - m_corners[0], m_corners[2] - m_corners[0]);
    m_bounds = pixelBoundsOfRaster(lo - kReach, hi + kReach, viewport);
    return true;
}

bool SnappedAwayTriangle::covers(const glm::dvec2& q) const {
    bool isInside = m_area != 0.0;
    for (int i = 0; i < 3 && isInside; ++i)
        isInside = cross(m_corners[std::size_t((i + 1) % 3)] - m_corners[std::size_t(i)], q - m_corners[std::size_t(i)]) * m_area >= 0.0;
    if (isInside) return true;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 a = m_corners[std::size_t(i)], d = m_corners[std::size_t((i + 1) % 3)] - a;
        const double length2 = glm::dot(d, d);
        const double t = length2 > 0.0 ? std::clamp(glm::dot(q - a, d) / length2, 0.0, 1.0) : 0.0;
        if (glm::distance(q, a + t * d) <= kReach) return true;
    }
    return false;
}

}  // namespace streak::raster
