#include "exposure/adaptive_sampling.h"

#include "image/color.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace streak::exposure {

std::optional<raster::PixelBounds> AdaptiveSampling::firstPassRegion(const std::optional<raster::PixelBounds>& region, int width, int height) {
    if (!region) return std::nullopt;
    return raster::PixelBounds{std::max(region->x0 - 1, 0), std::max(region->y0 - 1, 0), std::min(region->x1 + 1, width - 1),
                               std::min(region->y1 + 1, height - 1)};
}

raster::SamplePattern AdaptiveSampling::coarsePatternOf(const raster::SamplePattern& full) {
    return raster::samplePatternFor(std::max(2, full.samplesPerAxis() / 2), full.isGrid());
}

AdaptiveSampling::AdaptiveSampling(const Image& firstPass, float threshold, const std::optional<raster::PixelBounds>& within,
                                   const FirstPassGeometry* geometry, bool hasCoarse, float fullContrast)
    : m_width(firstPass.width()), m_fullContrast(hasCoarse ? fullContrastFor(threshold, fullContrast) : 0.0f) {
    const int width = firstPass.width(), height = firstPass.height();
    m_marks.assign(std::size_t(width) * std::size_t(height), 0);
    const raster::PixelBounds area = within.value_or(raster::PixelBounds{0, 0, width - 1, height - 1});
    // Each pixel's display values, once: sRGB colour and coverage, over the area and its border.
    const int x0 = std::max(area.x0 - 1, 0), y0 = std::max(area.y0 - 1, 0);
    const int x1 = std::min(area.x1 + 1, width - 1), y1 = std::min(area.y1 + 1, height - 1);
    const int w = x1 - x0 + 1;
    std::vector<float> display(std::size_t(w) * std::size_t(y1 - y0 + 1) * 4);
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            float* d = &display[(std::size_t(y - y0) * std::size_t(w) + std::size_t(x - x0)) * 4];
            const glm::vec3 c = linearToSrgb(firstPass.at(x, y));
            d[0] = c.x, d[1] = c.y, d[2] = c.z, d[3] = firstPass.alphaAt(x, y);
        }
    // The largest difference of two pixels' display values; a NaN colour (never written by a
    // method) is infinitely far, so it refines rather than hides.
    auto contrast = [&](int xa, int ya, int xb, int yb) {
        const float* a = &display[(std::size_t(ya - y0) * std::size_t(w) + std::size_t(xa - x0)) * 4];
        const float* b = &display[(std::size_t(yb - y0) * std::size_t(w) + std::size_t(xb - x0)) * 4];
        float most = 0.0f;
        for (int c = 0; c < 4; ++c) {
            const float d = std::fabs(a[c] - b[c]);
            most = d == d ? std::max(most, d) : std::numeric_limits<float>::infinity();
        }
        return most;
    };
    // (Past fullContrast nothing changes the level: the search stops there.)
    const float enough = std::max(m_fullContrast, threshold);
    for (int y = area.y0; y <= area.y1; ++y)
        for (int x = area.x0; x <= area.x1; ++x) {
            float most = 0.0f;
            for (int dy = -1; dy <= 1 && !(most > enough); ++dy)
                for (int dx = -1; dx <= 1 && !(most > enough); ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if ((dx == 0 && dy == 0) || nx < x0 || nx > x1 || ny < y0 || ny > y1) continue;
                    most = std::max(most, contrast(x, y, nx, ny));
                }
            const Level level = !(most > threshold)                         ? Level::None
                                : m_fullContrast > 0.0f && most <= m_fullContrast ? Level::Coarse
                                                                             : Level::Full;
            m_marks[std::size_t(y) * std::size_t(width) + std::size_t(x)] = std::uint8_t(level);
            m_numMarked += level != Level::None, m_numCoarse += level == Level::Coarse;
        }
    m_numAsked = std::int64_t(area.x1 - area.x0 + 1) * std::int64_t(area.y1 - area.y0 + 1);
    if (!geometry) return;
    geometry->forEachUnseen([&](const FirstPassGeometry::Unseen& unseen) {
        const raster::PixelBounds& p = unseen.pixels;
        for (int y = std::max(p.y0, area.y0); y <= std::min(p.y1, area.y1); ++y)
            for (int x = std::max(p.x0, area.x0); x <= std::min(p.x1, area.x1); ++x) {
                std::uint8_t& mark = m_marks[std::size_t(y) * std::size_t(width) + std::size_t(x)];
                if (mark == std::uint8_t(Level::Full)) continue;
                std::uint64_t around = 0;
                float reach = 0.0f;
                for (int ny = std::max(y - 1, y0); ny <= std::min(y + 1, y1); ++ny)
                    for (int nx = std::max(x - 1, x0); nx <= std::min(x + 1, x1); ++nx)
                        around |= geometry->shownAt(nx, ny), reach = std::max(reach, geometry->reachAt(nx, ny));
                if ((around & unseen.key) || unseen.nearest > reach) continue;
                // A sliver its sample missed takes the full pattern, as one no centre saw does.
                if (mark == std::uint8_t(Level::Coarse))
                    --m_numCoarse;
                else
                    ++m_numMarked, ++m_numMissed;
                mark = std::uint8_t(Level::Full);
            }
    });
}

bool AdaptiveSampling::anyIn(const raster::PixelBounds& rect, Level level) const {
    for (int y = rect.y0; y <= rect.y1; ++y)
        for (int x = rect.x0; x <= rect.x1; ++x)
            if (levelAt(x, y) == level) return true;
    return false;
}

void AdaptiveSampling::record(RenderStats& stats, float threshold) const {
    stats.setCounter("adaptive_threshold", threshold);
    stats.setCounter("adaptive_full_contrast", m_fullContrast);
    stats.setCounter("adaptive_pixels_refined", double(m_numMarked));
    stats.setCounter("adaptive_pixels_refined_coarse", double(m_numCoarse));
    stats.setCounter("adaptive_pixels_unseen_geometry", double(m_numMissed));
    stats.setCounter("adaptive_refined_fraction", m_numAsked > 0 ? double(m_numMarked) / double(m_numAsked) : 0.0);
}

}  // namespace streak::exposure
