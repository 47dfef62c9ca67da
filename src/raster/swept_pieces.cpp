#include "raster/swept_pieces.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace streak::raster {

bool SweptPieces::build(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close) {
    m_isBuilt = false, m_area = 0.0;
    for (int i = 0; i < 3; ++i)
        if (!(open[i].w > 0.0f) || !(close[i].w > 0.0f)) return false;
    // The corners at the pieces' ends: clip space is linear in u. In float, as SweptHull takes
    // them; a piece's hull is widened for that rounding below.
    std::array<std::array<glm::vec4, 3>, kPieces + 1> ends;
    for (int k = 0; k <= kPieces; ++k) {
        const double u = double(k) / kPieces;
        for (int i = 0; i < 3; ++i) {
            const glm::dvec4 a(open[i]), b(close[i]);
            ends[std::size_t(k)][std::size_t(i)] = glm::vec4(k == 0 ? a : k == kPieces ? b : a + u * (b - a));
        }
    }
    for (int k = 0; k < kPieces; ++k) {
        const auto& from = ends[std::size_t(k)];
        const auto& to = ends[std::size_t(k + 1)];
        glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
        for (const auto* corners : {&from, &to})
            for (const glm::vec4& c : *corners) {
                const glm::dvec2 p = glm::dvec2(c.x, c.y) / double(c.w);
                lo = glm::min(lo, p), hi = glm::max(hi, p);
            }
        if (!std::isfinite(lo.x) || !std::isfinite(lo.y) || !std::isfinite(hi.x) || !std::isfinite(hi.y)) return false;
        // An inner end rounded to float moves a corner's NDC by a few float epsilons of its size,
        // the end poses' hull by as much: the hull's margin takes eight of them.
        const double rounding = 8.0 * double(std::numeric_limits<float>::epsilon()) * std::max({std::abs(lo.x), std::abs(lo.y), std::abs(hi.x), std::abs(hi.y), 1.0});
        // A piece where the triangle turns over (or is too sharp for build's margin): the hull
        // of its six corners still holds it, widened as its box would be.
        m_turns[std::size_t(k)] = !m_hull[std::size_t(k)].build(from, to, rounding);
        m_hasHull[std::size_t(k)] = !m_turns[std::size_t(k)] || m_hull[std::size_t(k)].buildAround(from, to, kBoxMargin + rounding);
        if (m_hasHull[std::size_t(k)]) {
            m_area += m_hull[std::size_t(k)].area();
        } else {
            m_area += (hi.x - lo.x) * (hi.y - lo.y);
            m_boxLo[std::size_t(k)] = lo - kBoxMargin, m_boxHi[std::size_t(k)] = hi + kBoxMargin;
        }
    }
    m_isBuilt = true;
    return true;
}

bool SweptPieces::rowRange(double y, double& xLo, double& xHi) const {
    if (!m_isBuilt) return false;
    xLo = std::numeric_limits<double>::infinity(), xHi = -xLo;
    for (int k = 0; k < kPieces; ++k) {
        double lo, hi;
        if (m_hasHull[std::size_t(k)]) {
            if (!m_hull[std::size_t(k)].rowRange(y, lo, hi)) continue;
        } else {
            if (y < m_boxLo[std::size_t(k)].y || y > m_boxHi[std::size_t(k)].y) continue;
            lo = m_boxLo[std::size_t(k)].x, hi = m_boxHi[std::size_t(k)].x;
        }
        xLo = std::min(xLo, lo), xHi = std::max(xHi, hi);
    }
    return xLo <= xHi;
}

int SweptPieces::numTurning() const { return int(std::count(m_turns.begin(), m_turns.end(), true)); }

int SweptPieces::numHulls() const { return kPieces - numTurning(); }  // (a piece that keeps its orientation has build's hull)

}  // namespace streak::raster
