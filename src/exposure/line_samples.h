#pragma once

#include "exposure/segmented_geometry.h"
#include "exposure/shading_site.h"
#include "raster/moving_triangle.h"

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
// It needs a still frame's time to be free: one segment a triangle and every time weighed alike
// (a box shutter, no rolling), which lineSamplingAllowed says of a frame, and a tile whose every
// segment is still and wholly in front of the near plane, which isLineTile says of a tile.
// The early cull holds as it is: a line covered end to end hides what lies behind it there.
bool lineSamplingAllowed(const Scene& scene, const SegmentedGeometry& segmented);
bool isLineTile(std::span<const std::uint32_t> items, std::span<const TriangleSegment> segments, double zNear);

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
