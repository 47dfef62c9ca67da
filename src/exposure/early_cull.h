#pragma once

#include "exposure/segmented_geometry.h"
#include "raster/tile_grid.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace streak::exposure {

// A tile's segments `items` in `out`, nearest first (by their nearest corner; at equal
// nearness in their order), so that what hides others is mostly drawn before them.
// The order is sorted as 64-bit keys, the nearness's bits inverted over the index: a
// nearness is a float >= 0, whose bits order as the numbers do, so the keys order by
// nearness, largest first, then by index, without reading a segment at every step (a dense
// tile sorts many thousands).
inline void nearestFirst(std::span<const std::uint32_t> items, std::span<const TriangleSegment> segments, std::vector<std::uint32_t>& out,
                         std::vector<std::uint64_t>& keys) {
    keys.resize(items.size());
    for (std::size_t i = 0; i < items.size(); ++i) {
        const float nearness = segments[items[i]].nearness + 0.0f;  // (-0 becomes +0)
        assert(nearness >= 0.0f);  // and not NaN
        keys[i] = (std::uint64_t(~std::bit_cast<std::uint32_t>(nearness)) << 32) | items[i];
    }
    std::sort(keys.begin(), keys.end());
    out.resize(items.size());
    for (std::size_t i = 0; i < items.size(); ++i) out[i] = std::uint32_t(keys[i]);
}

// The early cull of an exact method's tile: what its samples are known to be hidden behind
// before the segments reaching them are solved. A sample that an opaque triangle covers over the
// whole shutter keeps the farthest depth of that triangle there (the nearest such), and a
// segment whose nearest corner lies beyond it has no share there: the resolve's occlusion cull
// (cullHiddenIntervals) would drop each of its intervals, an opaque interval over [0, 1] wholly
// nearer hiding it. So a method may skip such a sample, and a pixel whose every sample is so
// covered, without changing any image. It pays where segments come nearest first
// (nearestFirst), and only where a segment can cover the whole shutter (one segment a triangle,
// or a merged run of them: SegmentedGeometry::hasWholeShutterSegments).
//
// Samples are a tile's (or a piece of it), pixel-major with the pattern's samples minor, as
// TileRecord::sample counts them.
class EarlyCull {
public:
    // Every sample of a rectangle `tileWidth` pixels wide, `spp` samples a pixel, uncovered.
    // Returns the tile's segments `items` nearest first (nearestFirst), the order to visit them
    // in; the pieces of one tile (its runs, its budget's halves) share the items, so it is
    // ordered once for them all.
    std::span<const std::uint32_t> begin(std::size_t numSamples, int spp, int tileWidth, std::span<const std::uint32_t> items,
                                         std::span<const TriangleSegment> segments) {
        m_spp = spp, m_tileWidth = tileWidth;
        m_farthest.assign(numSamples, std::numeric_limits<float>::infinity());
        m_pixelFarthest.assign(numSamples / std::size_t(spp), std::numeric_limits<float>::infinity());
        m_runCount.clear();
        if (m_orderOf.data() != items.data() || m_orderOf.size() != items.size()) {
            nearestFirst(items, segments, m_order, m_keys);
            m_orderOf = items;
        }
        return m_order;
    }

    // The depth a segment of `nearness` (1 / its nearest corner's view depth; 0: unknown, never
    // culled) cannot come nearer than: below its nearest by more than the rounding of an
    // interval's float depths.
    static float nearestOf(float nearness) {
        return nearness > 0.0f ? (1.0f - 1e-5f) / nearness : -std::numeric_limits<float>::infinity();
    }

    bool isHidden(std::uint32_t sample, float nearest) const { return m_farthest[sample] < nearest; }
    // Pixel (x, y) of the rectangle, counted from its corner.
    bool isPixelHidden(int x, int y, float nearest) const {
        return m_pixelFarthest[std::size_t(y) * std::size_t(m_tileWidth) + std::size_t(x)] < nearest;
    }
    // True when every pixel of `region` (pixels, within the rectangle whose corner is `origin`)
    // is hidden from a segment whose nearest is `nearest`.
    bool isRegionHidden(const raster::PixelBounds& region, int originX, int originY, float nearest) const {
        for (int py = region.y0; py <= region.y1; ++py)
            for (int px = region.x0; px <= region.x1; ++px)
                if (!isPixelHidden(px - originX, py - originY, nearest)) return false;
        return true;
    }
    // Narrows [x0, x1] (pixels of row py, within the rectangle whose corner is `origin`) to the
    // pixels not hidden from the segment; x0 > x1 where none is left.
    void openRow(int py, int originX, int originY, float nearest, int& x0, int& x1) const {
        while (x0 <= x1 && isPixelHidden(x0 - originX, py - originY, nearest)) ++x0;
        while (x1 >= x0 && isPixelHidden(x1 - originX, py - originY, nearest)) --x1;
    }

    // An opaque stretch [u0, u1] of a line sample (exposure/line_samples.h), or an opaque
    // interval of a point sample over part of the shutter, lies no farther than `farthest`. A
    // line is seldom covered end to end by one small triangle, nor a shutter by one moving
    // triangle, but often by a mesh's several in turn: each sample keeps the union of what opaque stretches covered it, up to
    // kStretchRuns disjoint runs (past that a stretch that meets none is let go: covering less is
    // only culling less), and once a run spans the line, the sample is covered no farther than
    // the farthest of the stretches that made it. The resolve's occlusion cull takes the same
    // union (cullHiddenIntervals), so what this skips it would drop.
    void coverStretch(std::uint32_t sample, float u0, float u1, float farthest) {
        if (m_runCount.empty()) m_runCount.assign(m_farthest.size(), 0), m_runs.resize(m_farthest.size() * kStretchRuns);
        Run merged{u0, u1, farthest};
        Run* runs = m_runs.data() + std::size_t(sample) * kStretchRuns;
        std::uint8_t& count = m_runCount[sample];
        int kept = 0;
        for (int i = 0; i < count; ++i) {
            if (runs[i].u0 <= merged.u1 && runs[i].u1 >= merged.u0)
                merged = {std::min(merged.u0, runs[i].u0), std::max(merged.u1, runs[i].u1), std::max(merged.farthest, runs[i].farthest)};
            else
                runs[kept++] = runs[i];
        }
        count = std::uint8_t(kept);
        if (kept < kStretchRuns) runs[count++] = merged;
        if (merged.u0 <= 0.0f && merged.u1 >= 1.0f) cover(sample, merged.farthest);
    }

    // The shortest part of the shutter a moving surface's interval may cover a sample over to
    // be kept in its union (coverStretch): a surface that sweeps the sample in many short pieces
    // (a dense mesh under a camera move) scatters the union past its runs, and keeping them
    // would cost more than the cull saves.
    static constexpr float kShortestStretch = 1.0f / 16.0f;

    // Whether a segment may cover a point sample over kShortestStretch of the shutter or more,
    // and so give the cull something to keep (cover, coverStretch). Not where every point of
    // its surface travels across the screen more than 1 / kShortestStretch times the
    // triangle's size over the segment's share of the shutter: a sample then stays inside it
    // for less than that share (a dense mesh's tiny triangles under a camera move). An estimate
    // of the motion (exact for a translation), which only ever turns the cull off where it
    // would keep nothing: images do not depend on the cull. Segments behind the eye, still ones,
    // and ones that turn about a point of themselves (their corners' displacements surround
    // none) may.
    static bool mayCoverAStretch(const TriangleSegment& segment, const raster::Viewport& viewport);
    // Per segment of `geometry`: the farthest view depth it may hide others from (its farthest
    // corner's), where it may cover a stretch and is opaque; infinity elsewhere.
    static LargeBuffer<float> occluderDepths(const SegmentedGeometry& geometry, const raster::Viewport& viewport);
    // Whether the cull may hide anything among a tile's segments `items`: some segment lies
    // wholly beyond what another may hide it from. Where none does (a tile of a dense mesh
    // under a camera move, whose triangles sweep its samples in slivers), the tile is not
    // ordered nearest first for the cull, nor its samples' records put back in order.
    static bool mayHideAny(std::span<const std::uint32_t> items, std::span<const TriangleSegment> segments, std::span<const float> occluderDepths);

    // An opaque interval covers `sample` over the whole shutter, no farther than `farthest`.
    void cover(std::uint32_t sample, float farthest) {
        float& covered = m_farthest[sample];
        if (!(farthest < covered)) return;
        covered = farthest;
        const std::size_t pixel = sample / std::uint32_t(m_spp);
        const float* first = m_farthest.data() + pixel * std::size_t(m_spp);
        m_pixelFarthest[pixel] = *std::max_element(first, first + m_spp);
    }

private:
    static constexpr int kStretchRuns = 4;
    struct Run {
        float u0, u1, farthest;
    };

    int m_spp = 1, m_tileWidth = 1;
    std::vector<Run> m_runs;                 ///< per sample, kStretchRuns (coverStretch)
    std::vector<std::uint8_t> m_runCount;    ///< per sample; empty until a stretch comes
    std::vector<float> m_farthest;       ///< per sample
    std::vector<float> m_pixelFarthest;  ///< per pixel: the farthest of its samples'
    std::vector<std::uint32_t> m_order;       ///< m_orderOf nearest first
    std::vector<std::uint64_t> m_keys;        ///< nearestFirst's scratch
    std::span<const std::uint32_t> m_orderOf;  ///< the items m_order orders
};


}  // namespace streak::exposure
