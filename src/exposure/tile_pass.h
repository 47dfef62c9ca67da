#pragma once

#include "exposure/exposure_interval.h"
#include "exposure/pixel_shading.h"
#include "exposure/sample_passes.h"
#include "exposure/sample_resolve.h"
#include "exposure/tile_budget.h"
#include "exposure/visible_pieces.h"
#include "image/image.h"
#include "raster/sample_pattern.h"
#include "raster/tile_grid.h"
#include "scene/flat_geometry.h"
#include "scene/scene.h"
#include "util/progress.h"
#include "util/stats.h"

#include <glm/vec3.hpp>
#include <tbb/enumerable_thread_specific.h>

#include <chrono>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace streak::exposure {

// The frame of the exact-time methods that work per tile: bins items by their pixel bounds
// ("bin"), measures what the memory budget leaves the tiles (budget.measure()), then runs
// renderTile(tile, scratch, image) on every tile in parallel with one Scratch per thread
// ("tiles"); each tile owns its pixels, colour and coverage. Returns the image, background (and
// coverage 0) where no tile wrote; the per-thread scratches stay in `scratch` for the method to
// sum its counters.
template <class Scratch, class RenderTile>
Image runTilePass(raster::TileGrid& grid, std::span<const raster::PixelBounds> bounds, const glm::vec3& background,
                                   int width, int height, RenderStats& stats, ProgressReporter* progress, TileBudget& budget,
                                   tbb::enumerable_thread_specific<Scratch>& scratch, RenderTile&& renderTile) {
    {
        PhaseTimer timer(stats, "bin");
        grid.bin(bounds.size(), [&](std::size_t i) { return bounds[i]; });
    }
    budget.measure();
    Image image(width, height, background);
    image.setUncovered();
    {
        PhaseTimer timer(stats, "tiles");
        PartsProgress tiles(progress, std::size_t(grid.numActiveTiles()));
        grid.forEachTile(
            [&](int tile) {
                renderTile(tile, scratch.local(), image);
                tiles.partDone();
            },
            /*includeEmpty=*/true);
    }
    if (progress) progress->update(1.0);
    return image;
}

// Sets each pixel of rect in `image` (which has alpha) to the mean of its samples, laid out
// pixel-major in rect: colour and coverage.
inline void setTilePixels(const raster::PixelBounds& rect, int spp, std::span<const glm::vec3> color, std::span<const float> coverage, Image& image) {
    for (int py = rect.y0; py <= rect.y1; ++py)
        for (int px = rect.x0; px <= rect.x1; ++px) {
            image.at(px, py) = glm::vec3(0.0f);
            image.alpha()[std::size_t(py) * std::size_t(image.width()) + std::size_t(px)] = 0.0f;
        }
    raster::addTileToImage(rect, spp, color, 1.0f, image.pixels(), image.width());
    raster::addTileToImage(rect, spp, coverage, 1.0f, image.alpha(), image.width());
}

// The second half of such a tile: every sample's intervals (records grouped by sample: runs[i]
// to runs[i + 1] of bySample, each with an `interval`) become its colour, pixel by pixel:
// resolve(ndc, pixel row, intervals) resolves a sample (exposure::resolveSample), returning the
// colour of all but its visible opaque pieces, which it leaves in `pieces`, and its coverage
// (ResolvedSample); the pixel's pieces
// are then shaded together as `shading` says (textured triangles, isTextured(triangle), in cells) by shade(triangle, t0, t1, ShadingSite, pixel row)
// (PixelShading), and the tile's pixels become the mean of their samples, colour and coverage.
// A sample with no intervals is the background. With `passes`, each pixel's passes are written
// from what resolve() adds to pixelPasses.
template <class Record, class IsTextured, class Resolve, class Shade>
void resolveTile(const raster::PixelBounds& rect, const raster::SamplePattern& pattern, int width, int height, const glm::vec3& background,
                 std::span<const Record> bySample, std::span<const std::uint32_t> runs, std::vector<ExposureInterval>& list,
                 const std::vector<VisiblePiece>& pieces, std::vector<glm::vec3>& color, std::vector<float>& coverage, Image& image,
                 const PixelShadingOptions& shading,
                 PixelShading& pixelShading, SampleResolveCounters& counters, PassFrame* passes, PixelPasses& pixelPasses, IsTextured&& isTextured,
                 Resolve&& resolve, Shade&& shade) {
    using Clock = std::chrono::steady_clock;
    const int tileWidth = rect.x1 - rect.x0 + 1, spp = pattern.count();
    const std::size_t numSamples = runs.size() - 1;
    color.resize(numSamples);
    coverage.resize(numSamples);
    for (std::size_t first = 0; first < numSamples; first += std::size_t(spp)) {
        const int pixel = int(first / std::size_t(spp));
        const int px = rect.x0 + pixel % tileWidth, row = rect.y0 + pixel / tileWidth;
        pixelShading.begin(pattern, glm::dvec2(2.0 / width, 2.0 / height), shading.cellsFor(pattern.samplesPerAxis()));
        if (passes) pixelPasses.begin(*passes);
        for (int s = 0; s < spp; ++s) {
            const std::size_t i = first + std::size_t(s);
            if (runs[i] == runs[i + 1]) {
                color[i] = background, coverage[i] = 0.0f;
                continue;
            }
            const glm::dvec2 ndc = pattern.ndcOf(px, row, s, width, height);
            list.clear();
            for (std::uint32_t k = runs[i]; k < runs[i + 1]; ++k) list.push_back(bySample[k].interval);
            const ResolvedSample resolved = resolve(ndc, row, list);
            color[i] = resolved.color, coverage[i] = resolved.coverage;
            pixelShading.add(s, ndc, std::span<const VisiblePiece>(pieces), isTextured);
        }
        const auto start = Clock::now();
        pixelShading.finish(
            shading, [&](std::uint32_t triangle, float t0, float t1, const ShadingSite& site) { return shade(triangle, t0, t1, site, row); },
            std::span<glm::vec3>(color).subspan(first, std::size_t(spp)), counters.shading,
            [&](std::uint32_t triangle, const glm::vec3& added) {
                if (passes) pixelPasses.addColor(triangle, added);
            });
        counters.shadeSeconds += std::chrono::duration<double>(Clock::now() - start).count();
        if (passes) pixelPasses.finish(*passes, px, row, 1.0f / float(spp));
    }
    setTilePixels(rect, spp, color, coverage, image);
}

// One exposure interval of an exact method waiting in its tile for its sample's list.
struct TileRecord {
    std::uint32_t sample = 0;  ///< within the tile
    ExposureInterval interval;
};

// How an exact method resolves and shades its samples: the options of sample_resolve and
// pixel_shading it offers (each method parses its own).
struct ExactResolveOptions {
    int maxIntervals = 0;  ///< the compression budget; 0: unlimited
    OracleWeights oracle;
    bool occlusionCull = true;  ///< drop wholly hidden intervals before the resolve
    PixelShadingOptions shading;
};

// What one thread of an exact method keeps from tile to tile: the tile's interval records, then
// grouped by sample, the buffers of the resolve and the pixel shading, the method's cache of
// its triangles' equations (Cache) and its counters (Counters, with a SampleResolveCounters
// `resolve` and the seconds spent finding intervals, `intervalSeconds`; and the budget's).
template <class Cache, class Counters>
struct ExactTileScratch {
    std::vector<TileRecord> records, bySample;
    std::vector<std::uint32_t> runs;
    std::vector<float> nearness;  ///< a cut pixel's keys (keepRecordsWithinShare)
    TileBudgetCounters budget;
    std::vector<ExposureInterval> list;
    SampleResolveScratch resolve;
    PixelShading pixelShading;
    std::vector<glm::vec3> color;
    std::vector<float> coverage;
    std::vector<glm::dvec2> sampleNdc;  ///< the tile's samples in NDC, indexed as TileRecord::sample
    PixelPasses passes;
    Cache cache;
    Counters counters;
};

// An exact method's tile: its cache emptied, then its pixels by renderRect(items, rect, isPixel)
// (the tile's items, and the tile or a piece of it), in pieces while a piece's records would pass
// the share (renderWithinShare). A piece given up was spent finding intervals, and is timed so.
template <class Cache, class Counters, class RenderRect>
void renderExactTile(const raster::TileGrid& grid, int tile, ExactTileScratch<Cache, Counters>& scratch, RenderRect&& renderRect) {
    scratch.cache.clear();
    renderWithinShare(grid.tileBounds(tile), scratch.budget, [&](const raster::PixelBounds& rect, bool isPixel) {
        const auto start = std::chrono::steady_clock::now();
        const bool fits = renderRect(grid.items(tile), rect, isPixel);
        if (!fits) scratch.counters.intervalSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return fits;
    });
}

// What a tile's interval record costs the thread's share: itself, and its copy grouped by sample.
inline constexpr std::size_t kBytesPerTileRecord = 2 * sizeof(TileRecord);
inline std::size_t maxTileRecords(const TileBudget& budget) { return budget.maxItems(kBytesPerTileRecord); }

// Called after each triangle segment of a rectangle's interval search (numSamples in it; `done`
// of its `total` segments searched): false once scratch.records pass maxRecords, and the
// rectangle is to be cut (renderWithinShare, told how many shares it would take). A single pixel
// instead keeps each sample's nearest records, down to half its share (so the cut is not
// repeated at every segment), and goes on.
template <class Cache, class Counters>
bool keepRecordsWithinShare(ExactTileScratch<Cache, Counters>& scratch, std::size_t maxRecords, bool isPixel, std::size_t numSamples,
                            std::size_t done, std::size_t total) {
    scratch.budget.see(scratch.records.size());
    if (scratch.records.size() <= maxRecords) return true;
    if (!isPixel) {
        scratch.budget.refuse(scratch.records.size(), maxRecords, done, total);
        return false;
    }
    const std::size_t dropped = keepNearestPerSample(
        scratch.records, numSamples, maxRecords / (2 * numSamples), scratch.runs, scratch.bySample, scratch.nearness,
        [](std::span<TileRecord> run) { return run.size(); },
        [](const TileRecord& r) { return -std::min(r.interval.depth0, r.interval.depth1); });
    scratch.budget.dropped += std::int64_t(dropped);
    return true;
}

// The NDC of every sample of the pixels in rect, in TileRecord::sample order (row by row, the
// pattern's samples per pixel): computed once per tile, not once per segment that covers it.
inline void tileSampleNdc(const raster::PixelBounds& rect, const raster::SamplePattern& pattern, int width, int height,
                          std::vector<glm::dvec2>& out) {
    const int spp = pattern.count();
    out.clear();
    for (int py = rect.y0; py <= rect.y1; ++py)
        for (int px = rect.x0; px <= rect.x1; ++px)
            for (int s = 0; s < spp; ++s) out.push_back(pattern.ndcOf(px, py, s, width, height));
}

// The exact depth of interval source `source` at shutter time t under the sample at ndc, for
// measuring the linear depths' misordering (--option check-depth-order).
using ExactDepthOfSource = std::function<double(std::uint32_t source, float t, const glm::dvec2& ndc)>;

// The shared second half of an exact method's tile, once its intervals are in scratch.records
// (their search began at intervalStart, and is timed up to their grouping): groups them by
// sample, resolves every sample exactly (resolveSample, compressing to the budget) and shades
// what shows (resolveTile: per sample, or per pixel as options.shading says). The method
// supplies triangleOf(source) and shade(triangle, t0, t1, ShadingSite, pixel row) ->
// ShadedColor; exactDepth, when given, measures misordering. The tile's pixels go to `image`,
// and their passes, when asked for, to `passes`.
template <class Cache, class Counters, class TriangleOf, class Shade>
void resolveExactTile(const raster::PixelBounds& rect, const raster::SamplePattern& pattern, const Scene& scene,
                      const std::vector<FlatTriangle>& triangles, int width, int height, const ExactResolveOptions& options,
                      std::chrono::steady_clock::time_point intervalStart, ExactTileScratch<Cache, Counters>& scratch,
                      Image& image, TriangleOf&& triangleOf, Shade&& shade, const ExactDepthOfSource* exactDepth = nullptr,
                      PassFrame* passes = nullptr) {
    const std::size_t numSamples = std::size_t(rect.x1 - rect.x0 + 1) * std::size_t(rect.y1 - rect.y0 + 1) * std::size_t(pattern.count());
    raster::groupBySample(std::span<const TileRecord>(scratch.records), numSamples, scratch.runs, scratch.bySample);
    scratch.counters.intervalSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - intervalStart).count();

    auto materialOf = [&](std::uint32_t triangle) -> const Material& { return scene.materials[triangles[triangle].material]; };
    resolveTile(rect, pattern, width, height, scene.background, std::span<const TileRecord>(scratch.bySample),
                std::span<const std::uint32_t>(scratch.runs), scratch.list, scratch.resolve.pieces, scratch.color, scratch.coverage, image,
                options.shading, scratch.pixelShading, scratch.counters.resolve, passes, scratch.passes,
                [&](std::uint32_t triangle) { return materialOf(triangle).baseColorTexture >= 0; },
                [&](const glm::dvec2& ndc, int row, std::vector<ExposureInterval>& list) {
        std::optional<ExactDepth> depth;
        if (exactDepth) depth = [&](std::size_t k, float t) { return (*exactDepth)(list[k].source, t, ndc); };
        const glm::vec3 color = resolveSample(
            list, options.maxIntervals, options.oracle, depth ? &*depth : nullptr, options.occlusionCull, scene.shutter.rowWindow(row, height),
            scene.background, triangleOf, [&](std::uint32_t triangle) { return materialOf(triangle).isTranslucent(); },
            [&](std::uint32_t triangle, float t0, float t1) { return shade(triangle, t0, t1, sampleSite(ndc, pattern.samplesPerAxis()), row); },
            scratch.resolve, scratch.counters.resolve);
        if (passes) {
            forEachShownSurface(list, scratch.resolve, [&](std::uint32_t source, float share, float depth, float nearest, float farthest) {
                const std::uint32_t triangle = triangleOf(source);
                const FlatTriangle& t = triangles[triangle];
                scratch.passes.add({triangle, t.mesh, t.material, share, depth, nearest, farthest});
            });
            if (scratch.passes.wantsColor())
                forEachResolvedColor(list, scratch.resolve, [&](std::uint32_t source, const glm::vec3& added) { scratch.passes.addColor(triangleOf(source), added); });
        }
        return ResolvedSample{color, scratch.resolve.coverage};
    }, shade);
}

}  // namespace streak::exposure
