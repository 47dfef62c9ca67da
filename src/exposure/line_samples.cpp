#include "exposure/line_samples.h"

namespace streak::exposure {

bool lineSamplingAllowed(const Scene& scene, const SegmentedGeometry& segmented) {
    return segmented.hasWholeShutterSegments() && scene.shutter.isBox();
}

bool isLineTile(std::span<const std::uint32_t> items, std::span<const TriangleSegment> segments, double zNear) {
    return std::all_of(items.begin(), items.end(), [&](std::uint32_t index) {
        const TriangleSegment& s = segments[index];
        return s.t0 == 0.0f && s.t1 == 1.0f && s.clip0 == s.clip1 && s.isInFront() && double(s.nearness) <= 1.0 / zNear;
    });
}

bool lineStretchAt(const raster::MovingTriangle& still, int orientation, const glm::dvec2& ndc, int width, LineStretch& stretch) {
    const int px = int(std::floor((ndc.x + 1.0) * 0.5 * double(width)));
    bool found = false;
    forEachLineStretch(still, orientation, ndc.y, px, px, width, [&](int, const LineStretch& s) { stretch = s, found = true; });
    return found;
}

raster::SamplePattern linePatternFor(const raster::SamplePattern& points, int rows) {
    return rows > 0 && rows != points.count() ? raster::SamplePattern::rows(rows) : points;
}

ShadingSite lineSite(ShadingSite site, float t0, float t1, int width) {
    const double step = 2.0 / double(width);
    const double left = -1.0 + step * std::floor((site.ndc.x + 1.0) / step);
    site.ndc.x = left + step * 0.5 * (double(t0) + double(t1));
    site.footprintPixels.x = std::max(double(t1) - double(t0), 1.0 / 64.0);
    site.clampToTriangle = true, site.boxFootprint = true;
    site.boxBudget = Texture::kMaxSweptBoxTaps;  // a stretch's own box, still: the whole budget at its one time
    return site;
}

}  // namespace streak::exposure
