#pragma once

#include "raster/screen_triangle.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/vec3.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace streak::raster {

// TileGrid splits the image into square tiles and bins items (triangles) by their pixel bounds,
// keeping submission order within each tile. Tiles are then processed in parallel: each owns its
// pixels, so per-pixel state needs no locks, and the result does not depend on thread count.
// Given a region (a border render), only the tiles holding its pixels are active: the others get
// no items and are never visited. The tiles stay where the whole image puts them, with the same
// items in the same order, so the region's pixels are the whole render's to the bit.
class TileGrid {
public:
    TileGrid(const Viewport& viewport, int tileSize, const std::optional<PixelBounds>& region = std::nullopt);

    int tileSize() const { return m_tileSize; }
    int numTiles() const { return m_tilesX * m_tilesY; }
    // Pixel bounds of tile i, clipped to the image.
    PixelBounds tileBounds(int tile) const;

    // Bins items 0..count-1 with bounds(i) -> PixelBounds. Replaces the previous binning.
    template <class BoundsOf>
    void bin(std::size_t count, BoundsOf&& bounds);
    std::span<const std::uint32_t> items(int tile) const {
        return {m_items.data() + m_offsets[tile], m_offsets[tile + 1] - m_offsets[tile]};
    }

    // Calls f(tile) for every active tile with at least one item (or every active tile if
    // includeEmpty), in parallel.
    template <class F>
    void forEachTile(F&& f, bool includeEmpty = false) const {
        tbb::parallel_for(tbb::blocked_range<int>(0, numTiles(), 1), [&](const tbb::blocked_range<int>& r) {
            for (int tile = r.begin(); tile != r.end(); ++tile)
                if (isActive(tile) && (includeEmpty || !items(tile).empty())) f(tile);
        });
    }
    // Whether the tile holds pixels of the region (every tile without one).
    bool isActive(int tile) const;
    int numActiveTiles() const { return m_active.empty() ? 0 : (m_active.x1 - m_active.x0 + 1) * (m_active.y1 - m_active.y0 + 1); }

private:
    PixelBounds tileRange(const PixelBounds& pixels) const;
    PixelBounds activeTileRange(const PixelBounds& pixels) const;  ///< tileRange within the active tiles

    Viewport m_viewport;
    int m_tileSize;
    int m_tilesX;
    int m_tilesY;
    PixelBounds m_active;               ///< the active tiles (tile coordinates)
    std::vector<std::size_t> m_offsets;  ///< numTiles + 1, into m_items (CSR layout)
    std::vector<std::uint32_t> m_items;
};

template <class BoundsOf>
void TileGrid::bin(std::size_t count, BoundsOf&& bounds) {
    std::vector<std::size_t>& offsets = m_offsets;
    offsets.assign(std::size_t(numTiles()) + 1, 0);
    for (std::size_t i = 0; i < count; ++i) {
        const PixelBounds t = activeTileRange(bounds(i));
        for (int ty = t.y0; ty <= t.y1; ++ty)
            for (int tx = t.x0; tx <= t.x1; ++tx) ++offsets[std::size_t(ty) * m_tilesX + tx + 1];
    }
    for (std::size_t i = 1; i < offsets.size(); ++i) offsets[i] += offsets[i - 1];
    m_items.resize(offsets.back());
    std::vector<std::size_t> cursor(offsets.begin(), offsets.end() - 1);
    for (std::size_t i = 0; i < count; ++i) {
        const PixelBounds t = activeTileRange(bounds(i));
        for (int ty = t.y0; ty <= t.y1; ++ty)
            for (int tx = t.x0; tx <= t.x1; ++tx) m_items[cursor[std::size_t(ty) * m_tilesX + tx]++] = std::uint32_t(i);
    }
}

// The pixels k = 0 .. last of a sample row where one edge holds, value + step k >= 0 (value:
// the edge function plus its bias at the row's first pixel; step: its change a pixel), as
// [first, last] narrowed in place; false when none is left. Exact in integers: a quotient of
// doubles (the values are below 2^53) estimates each end, and the edge itself settles it.
inline bool narrowToEdge(std::int64_t value, std::int64_t step, std::int64_t& first, std::int64_t& last) {
    if (step == 0) return value >= 0;
    if (step > 0) {
        if (value >= 0) return true;  // from the first pixel on
        const double estimate = std::ceil(double(-value) / double(step));
        if (!(estimate <= double(last) + 1.0)) return false;  // beyond the row (the estimate is off by at most one)
        std::int64_t k = std::int64_t(estimate);
        while (k > 0 && value + step * (k - 1) >= 0) --k;
        while (value + step * k < 0) ++k;
        first = std::max(first, k);
    } else {
        if (value < 0) return false;  // and only falls from there
        const double estimate = std::floor(double(value) / double(-step));
        if (estimate <= double(last)) {  // (beyond: the true end is at least estimate - 1 >= last)
            std::int64_t k = std::int64_t(estimate);
            while (value + step * (k + 1) >= 0) ++k;
            while (k >= 0 && value + step * k < 0) --k;
            last = std::min(last, k);
        }
    }
    return first <= last;
}

// Calls onSample(px, py, sampleIndex, edgeValues) for every sample of `pattern` inside `tri`
// within the pixel rectangle `region` (a tile). The one scan loop of streak: every CPU method
// rasterizes through it, so the fill rule and edge setup exist once. A row kScanSpanMinWidth
// pixels wide or more finds its covered pixels from the edges first (narrowToEdge), as a
// rasterizer's span walk does, and visits only those: the same samples and edge values as
// testing every pixel, without the test at each. (A thin diagonal face across a tile tested
// 0.45% of its box's samples inside: motion-path's dense camera move scanned 10.7 G samples for
// 48 M fragments.) Narrower rows test each pixel, which costs less than finding their span.
inline constexpr int kScanSpanMinWidth = 8;

template <class OnSample>
void scanTriangle(const ScreenTriangle& tri, const PixelBounds& region, const SamplePattern& pattern, OnSample&& onSample) {
    const int x0 = std::max(region.x0, tri.bounds.x0), x1 = std::min(region.x1, tri.bounds.x1);
    const int y0 = std::max(region.y0, tri.bounds.y0), y1 = std::min(region.y1, tri.bounds.y1);
    if (x0 > x1 || y0 > y1) return;
    const std::int64_t stepX[3] = {tri.a[0] * kSubpixelScale, tri.a[1] * kSubpixelScale, tri.a[2] * kSubpixelScale};
    const bool isWide = x1 - x0 + 1 >= kScanSpanMinWidth;
    for (int py = y0; py <= y1; ++py) {
        for (int s = 0; s < pattern.count(); ++s) {
            const glm::i64vec2 offset = pattern.offsets[s];
            EdgeValues e = tri.edgesAt(std::int64_t(x0) * kSubpixelScale + offset.x, std::int64_t(py) * kSubpixelScale + offset.y);
            if (isWide) {
                std::int64_t first = 0, last = x1 - x0;
                bool isAny = true;
                for (int i = 0; i < 3 && isAny; ++i) isAny = narrowToEdge(e[i] + tri.bias[i], stepX[i], first, last);
                if (!isAny) continue;
                for (int i = 0; i < 3; ++i) e[i] += stepX[i] * first;
                for (std::int64_t k = first; k <= last; ++k) {
                    assert(tri.isInside(e));
                    onSample(x0 + int(k), py, s, e);
                    e[0] += stepX[0], e[1] += stepX[1], e[2] += stepX[2];
                }
                continue;
            }
            for (int px = x0; px <= x1; ++px) {
                if (tri.isInside(e)) onSample(px, py, s, e);
                e[0] += stepX[0], e[1] += stepX[1], e[2] += stepX[2];
            }
        }
    }
}

// Counting sort of a tile's records by their sample (record.sample in [0, numSamples)): each
// sample's records become one run, bySample[runs[i] .. runs[i + 1]), in their original order.
template <class Record>
void groupBySample(std::span<const Record> records, std::size_t numSamples, std::vector<std::uint32_t>& runs, std::vector<Record>& bySample) {
    runs.assign(numSamples + 1, 0);
    for (const Record& r : records) ++runs[r.sample + 1];
    for (std::size_t i = 1; i <= numSamples; ++i) runs[i] += runs[i - 1];
    bySample.resize(records.size());
    std::vector<std::uint32_t> cursor(runs.begin(), runs.end() - 1);
    for (const Record& r : records) bySample[cursor[r.sample]++] = r;
}

// Adds weight times the box-filtered mean of each pixel's samples in `region` to its pixel in
// `image` (row-major, imageWidth wide). Samples are laid out pixel-major within the region.
// Value: a colour (glm::vec3) or a coverage (float).
template <class Value>
void addTileToImage(const PixelBounds& region, int samplesPerPixel, std::span<const Value> samples, float weight, std::span<Value> image,
                    int imageWidth) {
    const float sampleWeight = weight / float(samplesPerPixel);
    std::size_t i = 0;
    for (int py = region.y0; py <= region.y1; ++py)
        for (int px = region.x0; px <= region.x1; ++px) {
            Value pixel(0.0f);
            for (int s = 0; s < samplesPerPixel; ++s) pixel += samples[i++];
            image[std::size_t(py) * std::size_t(imageWidth) + std::size_t(px)] += pixel * sampleWeight;
        }
}
inline void addTileToImage(const PixelBounds& region, int samplesPerPixel, std::span<const glm::vec3> samples, float weight,
                           std::span<glm::vec3> image, int imageWidth) {
    addTileToImage<glm::vec3>(region, samplesPerPixel, samples, weight, image, imageWidth);
}
inline void addTileToImage(const PixelBounds& region, int samplesPerPixel, std::span<const float> samples, float weight,
                           std::span<float> image, int imageWidth) {
    addTileToImage<float>(region, samplesPerPixel, samples, weight, image, imageWidth);
}

}  // namespace streak::raster
