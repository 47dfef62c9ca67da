#pragma once

#include "exposure/early_cull.h"
#include "exposure/segmented_geometry.h"
#include "exposure/shading_site.h"
#include "raster/moving_triangle.h"
#include "raster/sample_pattern.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

namespace streak::exposure {

// Line samples (`--option line-samples=1` of analytic and motion-path; Gribel, Barringer and
// Akenine-Moller 2011 sample lines of the screen): where nothing in a tile moves, each sample is
// the horizontal line through it across its pixel, and the time of its records stands for x
// along that line, 0 at the pixel's left edge and 1 at its right. A still triangle covers the
// line over one stretch, its depth along it its plane's, so an exact resolve in time is the exact
// visibility along the line, and a piece's weight the share of the line it shows: an edge is
// integrated across the pixel, and sampled only where it crosses the pattern's N^2 rows.
//
// It needs a still frame's time to be free: every time weighed alike (a box shutter, no rolling)
// and segments that span the shutter, which lineSamplingAllowed says of a frame, and a tile whose
// every segment spans the shutter, still and wholly in front of the near plane, which isLineTile
// says of a tile. (A triangle still over several keys is one merged segment: SegmentedGeometry.)
// The early cull holds as it is: a line covered end to end hides what lies behind it there.
bool lineSamplingAllowed(const Scene& scene, const SegmentedGeometry& segmented);
bool isLineTile(std::span<const std::uint32_t> items, std::span<const TriangleSegment> segments, double zNear);

// The most lines a pixel of a line tile takes (`--option line-rows`): the fixed-point grid's rows.
inline constexpr int kMaxLineRows = int(raster::kSubpixelScale);

// A line tile's samples: `rows` lines down each pixel (SamplePattern::rows), or with rows = 0
// the point pattern `points` itself, whose rows at --aa n are rooks(n)'s n^2. A line resolves x
// exactly and y only at its rows, so fewer rows than n^2 trade the edges near horizontal for
// time (ToyCar at --aa 2 against Cycles: 2 rows 39.8 dB, 3 rows 45.7, 4 rows 47.8).
raster::SamplePattern linePatternFor(const raster::SamplePattern& points, int rows);

// The stretch [u0, u1] of a pixel's line that a triangle covers (shares of the pixel's width),
// and its view depths at both ends.
struct LineStretch {
    float u0 = 0.0f, u1 = 0.0f;
    float depth0 = 0.0f, depth1 = 0.0f;
};

// The pixels px in [x0, x1] of a width-pixel image whose line at NDC height y the still
// triangle `still` (of orientation +1 or -1) covers, each with its stretch:
// visit(px, LineStretch). A stretch whose ends' depths cannot be taken (seen edge-on) is left out.
template <class Visit>
void forEachLineStretch(const raster::MovingTriangle& still, int orientation, double y, int x0, int x1, int width, Visit&& visit) {
    double xLo, xHi;
    if (!still.stillRowSection(y, orientation, xLo, xHi)) return;
    const double step = 2.0 / double(width);
    xLo = std::clamp(xLo, -2.0, 2.0), xHi = std::clamp(xHi, -2.0, 2.0);
    const int first = std::max(x0, int(std::floor((xLo + 1.0) / step))), last = std::min(x1, int(std::ceil((xHi + 1.0) / step)) - 1);
    for (int px = first; px <= last; ++px) {
        const double left = -1.0 + step * double(px);
        const double u0 = std::max(0.0, (xLo - left) / step), u1 = std::min(1.0, (xHi - left) / step);
        if (!(u1 > u0)) continue;
        const raster::HomogeneousSample s0 = still.sample(0.0, {left + u0 * step, y}), s1 = still.sample(0.0, {left + u1 * step, y});
        if (!s0.isValid || !s1.isValid) continue;
        visit(px, LineStretch{float(u0), float(u1), float(s0.viewDepth), float(s1.viewDepth)});
    }
}

// A still segment's stretches in a line tile: over the pattern's rows of the pixels `region`
// of the tile `rect` (samples counted pixel-major, the pattern's minor, as TileRecord::sample),
// each stretch it covers as visit(sample, LineStretch). With `cull` (the tile's early cull, the
// segment's nearest depth `nearest`), the pixels and samples hidden from it are skipped and
// counted in `hidden`, and where `isOccluder` (opaque) its stretches cover (coverStretch).
// Returns false, visiting nothing, where a single-sided triangle is seen from behind (no
// interval anywhere, and above all no cover); an edge-on one (no area) visits nothing. `missed`
// counts the rows' pixels whose lines it does not cover.
template <class Visit>
bool forEachTileLineStretch(const raster::MovingTriangle& still, const TriangleSegment& segment, bool isDoubleSided,
                            const raster::PixelBounds& rect, const raster::PixelBounds& region, const raster::SamplePattern& pattern,
                            const raster::Viewport& viewport, EarlyCull* cull, float nearest, bool isOccluder, std::int64_t& hidden,
                            std::int64_t& missed, Visit&& visit) {
    if (segment.orientation == 0) return true;
    if (!isDoubleSided && !still.isFrontFacing(0.5)) return false;
    const int spp = pattern.count(), tileWidth = rect.x1 - rect.x0 + 1, boxWidth = region.x1 - region.x0 + 1;
    for (int py = region.y0; py <= region.y1; ++py) {
        int open0 = region.x0, open1 = region.x1;
        if (cull) {
            cull->openRow(py, rect.x0, rect.y0, nearest, open0, open1);
            hidden += std::int64_t(boxWidth - std::max(0, open1 - open0 + 1)) * spp;
            if (open0 > open1) continue;
        }
        for (int s = 0; s < spp; ++s) {
            const double y = pattern.ndcOf(region.x0, py, s, viewport.width, viewport.height).y;
            int covered = 0;
            forEachLineStretch(still, segment.orientation, y, open0, open1, viewport.width, [&](int px, const LineStretch& stretch) {
                ++covered;
                const auto sample = std::uint32_t((std::size_t(py - rect.y0) * std::size_t(tileWidth) + std::size_t(px - rect.x0)) * spp + s);
                if (cull && cull->isHidden(sample, nearest)) {
                    ++hidden;
                    return;
                }
                visit(sample, stretch);
                if (isOccluder) cull->coverStretch(sample, stretch.u0, stretch.u1, std::max(stretch.depth0, stretch.depth1));
            });
            missed += (open1 - open0 + 1) - covered;
        }
    }
    return true;
}

// The stretch of the line through the sample at `ndc` (its pixel's) that the still triangle
// covers; false where it covers none.
bool lineStretchAt(const raster::MovingTriangle& still, int orientation, const glm::dvec2& ndc, int width, LineStretch& stretch);

// Where a line sample's span [t0, t1] (a stretch of its pixel's width) is shaded: at the
// stretch's middle, on the rows of `site` (a sample's, or a shared shading's), its texture a box
// as wide as the stretch, clipped to the triangle: what the line sees, where a sample's bell
// would blur across it (the still ToyCar at --aa 2 against Cycles: 43.1 dB with the bell, 47.8
// with the box). The site's x only says which pixel. A still triangle is the same at every time,
// so the span is shaded over [0, 1].
ShadingSite lineSite(ShadingSite site, float t0, float t1, int width);

}  // namespace streak::exposure
