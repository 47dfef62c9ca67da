#include "raster/swept_hull.h"

#include "raster/convex_hull.h"
#include "raster/edge_equation.h"
#include "raster/moving_triangle.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace streak::raster {

namespace {

double cross(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

}  // namespace

bool SweptHull::projectCorners(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, std::array<glm::dvec2, 6>& points) {
    for (int i = 0; i < 3; ++i)
        for (int end = 0; end < 2; ++end) {
            const glm::vec4& c = end == 0 ? open[i] : close[i];
            if (!(c.w > 0.0f)) return false;
            glm::dvec2& point = points[std::size_t(end * 3 + i)];
            point = glm::dvec2(double(c.x), double(c.y)) / double(c.w);
            if (!std::isfinite(point.x) || !std::isfinite(point.y)) return false;
        }
    return true;
}

bool SweptHull::buildAround(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, double margin) {
    m_count = 0;
    std::array<glm::dvec2, 6> points;
    if (!projectCorners(open, close, points)) return false;
    m_margin = margin;
    return setHull(points);
}

bool SweptHull::build(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, double extraMargin) {
    m_count = 0;
    std::array<glm::dvec2, 6> points;
    if (!projectCorners(open, close, points)) return false;
    double wProduct = 1.0;
    for (int i = 0; i < 3; ++i) wProduct *= double(std::max(open[i].w, close[i].w));
    // The margin needs the sharpest corner the triangle has at any u, not only at its ends: a
    // corner can pass close to the opposite edge in between. At corner i, sin(theta) =
    // 2 A / (|a| |b|). Twice the NDC area is det(u) / (w0 w1 w2)(u): at least the least
    // Bernstein coefficient's magnitude over the product of each w's greater end (w is linear in
    // u), when all coefficients share a sign. And sin(theta / 2) >= sin(theta) / 2.
    const std::array<double, 4> orientation = orientationBernstein(open, close);
    double least = std::numeric_limits<double>::infinity();
    for (const double c : orientation) {
        if (!(c * orientation[0] > 0.0)) return false;
        least = std::min(least, std::abs(c));
    }
    const double twiceArea = least / wProduct;
    // Side i-j at u is (x_i w_j - x_j w_i, y_i w_j - y_j w_i)(u) / (w_i w_j)(u): quadratics over
    // the product, each at most its largest Bernstein coefficient's magnitude.
    auto longestSide = [&](int i, int j) {
        auto most = [&](int axis) {
            auto cross2 = [axis](const glm::vec4& a, const glm::vec4& b) { return double(a[axis]) * double(b.w) - double(b[axis]) * double(a.w); };
            const double middle = 0.5 * (cross2(open[i], close[j]) + cross2(close[i], open[j]));
            return std::max({std::abs(cross2(open[i], open[j])), std::abs(middle), std::abs(cross2(close[i], close[j]))});
        };
        const double wLeast = double(std::min(open[i].w, close[i].w)) * double(std::min(open[j].w, close[j].w));
        return std::hypot(most(0), most(1)) / wLeast;
    };
    const std::array<double, 3> side{longestSide(1, 2), longestSide(2, 0), longestSide(0, 1)};  // opposite corner 0, 1, 2
    double sine = 1.0;
    for (int i = 0; i < 3; ++i) sine = std::min(sine, 0.5 * twiceArea / (side[std::size_t((i + 1) % 3)] * side[std::size_t((i + 2) % 3)]));
    // The on-edge tolerance's reach past a corner (see the header), and a little for rounding.
    const double reach = 4.0 * kOnEdgeTolerance;
    if (!(sine * kMaxMargin > reach)) return false;
    m_margin = reach / sine + 1e-12 + extraMargin;
    return setHull(points);
}

bool SweptHull::setHull(const std::array<glm::dvec2, 6>& points) {
    const ConvexHull hull = convexHull(points);
    m_count = hull.count;
    if (m_count < 3) {  // six points on a line (build's have area: only buildAround's can)
        m_count = 0;
        return false;
    }
    for (int i = 0; i < m_count; ++i) m_vertex[std::size_t(i)] = points[std::size_t(hull.index[std::size_t(i)])];
    m_yLo = std::numeric_limits<double>::infinity(), m_yHi = -m_yLo;
    m_area = 0.0;
    for (int i = 0; i < m_count; ++i) {
        m_yLo = std::min(m_yLo, m_vertex[i].y), m_yHi = std::max(m_yHi, m_vertex[i].y);
        m_area += 0.5 * cross(m_vertex[0], m_vertex[i], m_vertex[(i + 1) % m_count]);
    }
    m_yLo -= m_margin, m_yHi += m_margin;
    // Each edge from its lower end, with its slope (rowRange runs a few times per sample row).
    for (int i = 0; i < m_count; ++i) {
        Edge& e = m_edges[std::size_t(i)];
        e.lo = m_vertex[std::size_t(i)], e.hi = m_vertex[std::size_t((i + 1) % m_count)];
        if (e.lo.y > e.hi.y) std::swap(e.lo, e.hi);
        e.isLevel = e.lo.y == e.hi.y;
        e.slope = e.isLevel ? 0.0 : (e.hi.x - e.lo.x) / (e.hi.y - e.lo.y);
    }
    return true;
}

bool SweptHull::rowRange(double y, double& xLo, double& xHi) const {
    if (m_count == 0 || y < m_yLo || y > m_yHi) return false;
    // The hull within margin of the row: every edge clipped to the band |y' - y| <= margin
    // gives its x extremes at the clipped ends (a vertex in the band is an edge's end). The
    // widened hull lies within the band's x range widened by the margin.
    const double bandLo = y - m_margin, bandHi = y + m_margin;
    xLo = std::numeric_limits<double>::infinity(), xHi = -xLo;
    for (int i = 0; i < m_count; ++i) {
        const Edge& e = m_edges[std::size_t(i)];
        const glm::dvec2 &a = e.lo, &b = e.hi;
        if (b.y < bandLo || a.y > bandHi) continue;
        if (e.isLevel) {
            xLo = std::min({xLo, a.x, b.x}), xHi = std::max({xHi, a.x, b.x});
            continue;
        }
        const double yA = std::max(a.y, bandLo), yB = std::min(b.y, bandHi);
        const double xA = a.x + (yA - a.y) * e.slope, xB = a.x + (yB - a.y) * e.slope;
        xLo = std::min({xLo, xA, xB}), xHi = std::max({xHi, xA, xB});
    }
    if (!(xLo <= xHi)) return false;
    xLo -= m_margin, xHi += m_margin;
    return true;
}

}  // namespace streak::raster
