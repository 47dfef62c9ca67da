#include "raster/swept_hull.h"

#include "raster/edge_equation.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace streak::raster {

namespace {

double cross(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// sin(theta / 2) of the triangle's smallest corner angle theta; 0 when it is degenerate.
double smallestHalfAngleSine(const std::array<glm::dvec2, 3>& p) {
    double least = 1.0;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
        const double la = glm::length(a), lb = glm::length(b);
        if (!(la > 0.0 && lb > 0.0)) return 0.0;
        const double cosine = std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0);
        least = std::min(least, std::sqrt(0.5 * (1.0 - cosine)));
    }
    return least;
}

}  // namespace

bool SweptHull::build(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close) {
    m_count = 0;
    std::array<glm::dvec2, 6> points;
    double sine = 1.0;
    for (int end = 0; end < 2; ++end) {
        const std::array<glm::vec4, 3>& corners = end == 0 ? open : close;
        std::array<glm::dvec2, 3> pose;
        for (int i = 0; i < 3; ++i) {
            if (!(corners[i].w > 0.0f)) return false;
            pose[i] = glm::dvec2(double(corners[i].x), double(corners[i].y)) / double(corners[i].w);
            if (!std::isfinite(pose[i].x) || !std::isfinite(pose[i].y)) return false;
            points[std::size_t(end * 3 + i)] = pose[i];
        }
        sine = std::min(sine, smallestHalfAngleSine(pose));
    }
    // The on-edge tolerance's reach past a corner (see the header), and a little for rounding.
    const double reach = 4.0 * kOnEdgeTolerance;
    if (!(sine * kMaxMargin > reach)) return false;
    m_margin = reach / sine + 1e-12;

    // Andrew's monotone chain: the lower hull left to right, then the upper right to left.
    std::sort(points.begin(), points.end(), [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    std::array<glm::dvec2, 12> chain;
    int k = 0;
    for (int i = 0; i < 6; ++i) {
        while (k >= 2 && cross(chain[k - 2], chain[k - 1], points[i]) <= 0.0) --k;
        chain[k++] = points[i];
    }
    for (int i = 4, lower = k + 1; i >= 0; --i) {
        while (k >= lower && cross(chain[k - 2], chain[k - 1], points[i]) <= 0.0) --k;
        chain[k++] = points[i];
    }
    m_count = k - 1;  // the last point repeats the first
    if (m_count < 3) {  // not reached: both end poses have area
        m_count = 0;
        return false;
    }
    std::copy(chain.begin(), chain.begin() + m_count, m_vertex.begin());
    m_yLo = std::numeric_limits<double>::infinity(), m_yHi = -m_yLo;
    m_area = 0.0;
    for (int i = 0; i < m_count; ++i) {
        m_yLo = std::min(m_yLo, m_vertex[i].y), m_yHi = std::max(m_yHi, m_vertex[i].y);
        m_area += 0.5 * cross(m_vertex[0], m_vertex[i], m_vertex[(i + 1) % m_count]);
    }
    m_yLo -= m_margin, m_yHi += m_margin;
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
        glm::dvec2 a = m_vertex[i], b = m_vertex[(i + 1) % m_count];
        if (a.y > b.y) std::swap(a, b);
        if (b.y < bandLo || a.y > bandHi) continue;
        if (a.y == b.y) {
            xLo = std::min({xLo, a.x, b.x}), xHi = std::max({xHi, a.x, b.x});
            continue;
        }
        const double yA = std::max(a.y, bandLo), yB = std::min(b.y, bandHi);
        const double slope = (b.x - a.x) / (b.y - a.y);
        const double xA = a.x + (yA - a.y) * slope, xB = a.x + (yB - a.y) * slope;
        xLo = std::min({xLo, xA, xB}), xHi = std::max({xHi, xA, xB});
    }
    if (!(xLo <= xHi)) return false;
    xLo -= m_margin, xHi += m_margin;
    return true;
}

}  // namespace streak::raster
