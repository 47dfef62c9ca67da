#pragma once

#include "exposure/adaptive_sampling.h"
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

#include <algorithm>
#include <chrono>
#include <cmath>
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

// Progress over one stretch [from, to] of a render's whole (a pass of several).
class ProgressStretch final : public ProgressReporter {
public:
    ProgressStretch(ProgressReporter* whole, double from, double to) : m_whole(whole), m_from(from), m_to(to) {}
    ProgressReporter* get() { return m_whole ? this : nullptr; }
    void update(double fraction) override { m_whole->update(m_from + (m_to - m_from) * fraction); }

private:
    ProgressReporter* m_whole;
    double m_from, m_to;
};

// An exact method's tile passes, one to three (AdaptiveSampling). firstPass(pattern, grid region,
// progress, geometry) renders the whole image with the sample pattern it is handed, in a grid of
// that region, and returns it; it tells `geometry` (when not null) what its samples showed and
// missed. Without a threshold (or with one sample a pixel) that is all, with fullPattern. With
// one, the first pass takes one sample per pixel, in the region grown by a pixel, and the pixels
// it marks go to refine(refinement, level, pattern, image, progress), level by level (the coarse
// one first, where fullPattern has one; fullContrast as AdaptiveSampling takes it), which
// renders the pixels of that level again with its pattern into the first pass's image.
// `refinement` keeps the marks (for the stats). The marking is timed as "mark"; the passes time
// their own tiles.
template <class FirstPass, class Refine>
Image renderAdaptively(const raster::SamplePattern& fullPattern, float threshold, float fullContrast, const std::optional<raster::PixelBounds>& region,
                       int width, int height, RenderStats& stats, ProgressReporter* progress, std::optional<AdaptiveSampling>& refinement,
                       FirstPass&& firstPass, Refine&& refine) {
    if (!(threshold > 0.0f) || fullPattern.count() == 1) return firstPass(fullPattern, region, progress, nullptr);
    // The first pass is about 1/N^2 of the work of a refined pixel: a fifth of the bar.
    ProgressStretch first(progress, 0.0, 0.2);
    std::optional<Image> image;
    const raster::SamplePattern coarsePattern = AdaptiveSampling::coarsePatternOf(fullPattern);
    const bool hasCoarse = coarsePattern.count() < fullPattern.count();  // (AdaptiveSampling::hasCoarseLevel)
    {
        // (What the first pass saw is freed before the second.)
        FirstPassGeometry geometry(width, height);
        image = firstPass(raster::samplePatternFor(1, false), AdaptiveSampling::firstPassRegion(region, width, height), first.get(), &geometry);
        PhaseTimer timer(stats, "mark");
        refinement.emplace(*image, threshold, region, &geometry, hasCoarse, fullContrast);
    }
    // The rest of the bar split between the levels by their samples.
    const double coarseSamples = double(refinement->numCoarse()) * double(coarsePattern.count());
    const double fullSamples = double(refinement->numMarked() - refinement->numCoarse()) * double(fullPattern.count());
    const double split = 0.2 + 0.8 * (coarseSamples + fullSamples > 0.0 ? coarseSamples / (coarseSamples + fullSamples) : 0.0);
    if (refinement->numCoarse() > 0) {
        ProgressStretch coarse(progress, 0.2, split);
        refine(*refinement, AdaptiveSampling::Level::Coarse, coarsePattern, *image, coarse.get());
    }
    {
        ProgressStretch full(progress, split, 1.0);
        refine(*refinement, AdaptiveSampling::Level::Full, fullPattern, *image, full.get());
    }
    if (progress) progress->update(1.0);
    return std::move(*image);
}

// A refining pass of AdaptiveSampling: every tile of the grid with pixels of `level`, in
// parallel, by renderTile(tile, scratch) (which renders their runs: renderExactTileRuns).
template <class Scratch, class RenderTile>
void runRefinementPass(const raster::TileGrid& grid, const AdaptiveSampling& refinement, AdaptiveSampling::Level level, ProgressReporter* progress,
                       tbb::enumerable_thread_specific<Scratch>& scratch, RenderTile&& renderTile) {
    PartsProgress tiles(progress, std::size_t(grid.numActiveTiles()));
    grid.forEachTile([&](int tile) {
        if (refinement.anyIn(grid.tileBounds(tile), level)) renderTile(tile, scratch.local());
        tiles.partDone();
    });
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
// are then shaded together as `shading` says (each triangle as sharingOf(triangle), a Sharing, says) by shade(triangle, t0, t1, ShadingSite, pixel row)
// (PixelShading), and the tile's pixels become the mean of their samples, colour and coverage.
// A sample with no intervals is the background. With `passes`, each pixel's passes are written
// from what resolve() adds to pixelPasses. sampleNdc holds the tile's samples in NDC
// (tileSampleNdc of rect and pattern), indexed as the runs.
template <class Record, class SharingOf, class Resolve, class Shade>
void resolveTile(const raster::PixelBounds& rect, const raster::SamplePattern& pattern, int width, int height, const glm::vec3& background,
                 std::span<const glm::dvec2> sampleNdc, std::span<const Record> bySample, std::span<const std::uint32_t> runs, std::vector<ExposureInterval>& list,
                 const std::vector<VisiblePiece>& pieces, std::vector<glm::vec3>& color, std::vector<float>& coverage, Image& image,
                 const PixelShadingOptions& shading,
                 PixelShading& pixelShading, SampleResolveCounters& counters, PassFrame* passes, PixelPasses& pixelPasses, SharingOf&& sharingOf,
                 Resolve&& resolve, Shade&& shade) {
    const int tileWidth = rect.x1 - rect.x0 + 1, spp = pattern.count();
    const std::size_t numSamples = runs.size() - 1;
    color.resize(numSamples);
    coverage.resize(numSamples);
    // The tile's time is split into resolve and shade by timing the two halves of every
    // kTimedEvery-th pixel: a clock read costs about as much as resolving a sample (36 ns through
    // the vDSO on the development machine), and two reads a sample were a fifth of an --aa 1
    // frame (one pixel in 8 still cost 4%). The resolve's share holds its samples' lists and
    // pieces.
    using Clock = std::chrono::steady_clock;
    constexpr int kTimedEvery = 32;
    const auto tileStart = Clock::now();
    Clock::duration timedResolve{}, timedShade{};
    for (std::size_t first = 0; first < numSamples; first += std::size_t(spp)) {
        const int pixel = int(first / std::size_t(spp));
        const int px = rect.x0 + pixel % tileWidth, row = rect.y0 + pixel / tileWidth;
        const bool isTimed = pixel % kTimedEvery == 0;
        const auto pixelStart = isTimed ? Clock::now() : Clock::time_point{};
        pixelShading.begin(pattern, glm::dvec2(2.0 / width, 2.0 / height), shading.cellsFor(pattern.samplesPerAxis()));
        if (passes) pixelPasses.begin(*passes);
        for (int s = 0; s < spp; ++s) {
            const std::size_t i = first + std::size_t(s);
            if (runs[i] == runs[i + 1]) {
                color[i] = background, coverage[i] = 0.0f;
                continue;
            }
            const glm::dvec2 ndc = sampleNdc[i];
            list.clear();
            for (std::uint32_t k = runs[i]; k < runs[i + 1]; ++k) list.push_back(bySample[k].interval);
            const ResolvedSample resolved = resolve(ndc, row, list);
            color[i] = resolved.color, coverage[i] = resolved.coverage;
            pixelShading.add(s, ndc, std::span<const VisiblePiece>(pieces), sharingOf);
        }
        const auto resolved = isTimed ? Clock::now() : Clock::time_point{};
        pixelShading.finish(
            shading, [&](std::uint32_t triangle, float t0, float t1, const ShadingSite& site) { return shade(triangle, t0, t1, site, row); },
            std::span<glm::vec3>(color).subspan(first, std::size_t(spp)), counters.shading,
            [&](std::uint32_t triangle, const glm::vec3& added) {
                if (passes) pixelPasses.addColor(triangle, added);
            });
        if (passes) pixelPasses.finish(*passes, px, row, 1.0f / float(spp));
        if (isTimed) {
            const auto shaded = Clock::now();
            timedResolve += resolved - pixelStart, timedShade += shaded - resolved;
        }
    }
    const double tileSeconds = std::chrono::duration<double>(Clock::now() - tileStart).count();
    const double timed = std::chrono::duration<double>(timedResolve + timedShade).count();
    const double shadeShare = timed > 0.0 ? std::chrono::duration<double>(timedShade).count() / timed : 0.0;
    counters.resolveSeconds += tileSeconds * (1.0 - shadeShare);
    counters.shadeSeconds += tileSeconds * shadeShare;
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
    std::vector<std::uint32_t> seenSources;  ///< a first pass's items with records in the tile (noteUnseenItems)
    bool sortRunsBySource = false;  ///< the method found the records out of its items' order: each sample's go back to it
    PixelPasses passes;
    Cache cache;
    Counters counters;
};

// The pixels `bounds` of a tile whose items are `items`, by renderRect(items, rect, isPixel), in
// pieces while a piece's records would pass the share (renderWithinShare). A piece given up was
// spent finding intervals, and is timed so.
template <class Cache, class Counters, class RenderRect>
void renderExactRect(const raster::PixelBounds& bounds, std::span<const std::uint32_t> items, ExactTileScratch<Cache, Counters>& scratch,
                     RenderRect&& renderRect) {
    renderWithinShare(bounds, scratch.budget, [&](const raster::PixelBounds& rect, bool isPixel) {
        const auto start = std::chrono::steady_clock::now();
        const bool fits = renderRect(items, rect, isPixel);
        if (!fits) scratch.counters.intervalSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return fits;
    });
}

// An exact method's tile: its cache emptied, then its pixels by renderRect(items, rect, isPixel)
// (the tile's items, and the tile or a piece of it: renderExactRect).
template <class Cache, class Counters, class RenderRect>
void renderExactTile(const raster::TileGrid& grid, int tile, ExactTileScratch<Cache, Counters>& scratch, RenderRect&& renderRect) {
    scratch.cache.clear();
    renderExactRect(grid.tileBounds(tile), grid.items(tile), scratch, renderRect);
}

// A refining pass's tile (AdaptiveSampling): its cache emptied, then each run of its pixels of
// `level` as renderExactTile renders its whole rectangle.
template <class Cache, class Counters, class RenderRect>
void renderExactTileRuns(const raster::TileGrid& grid, int tile, const AdaptiveSampling& refinement, AdaptiveSampling::Level level,
                         ExactTileScratch<Cache, Counters>& scratch, RenderRect&& renderRect) {
    scratch.cache.clear();
    refinement.forEachRun(grid.tileBounds(tile), level,
                          [&](const raster::PixelBounds& run) { renderExactRect(run, grid.items(tile), scratch, renderRect); });
}

// The tile passes of an exact method on ExactTileScratch, one to three (renderAdaptively over a
// grid of tileSize tiles): `frame` is the method's, with its viewport, its items' pixel `bounds`,
// its full sample `pattern`, and usePass(pattern, firstPass), which sets the pass's pattern
// (and what the method derives from it) and what a first pass tells FirstPassGeometry (else
// null); renderRect(items, rect, isPixel, scratch, image) renders
// a piece of a tile (renderExactTile, renderExactTileRuns), and frame.unseenSurfaceOf(item) is
// an item's surface for noteUnseenItems (unseenSurface). `refinement` keeps the marks; the
// frame's pattern is its full one again after.
template <class Frame, class Scratch, class RenderRect>
Image runExactTilePasses(Frame& frame, int tileSize, const glm::vec3& background, float adaptiveThreshold, float adaptiveFullContrast,
                         const std::optional<raster::PixelBounds>& region, RenderStats& stats, ProgressReporter* progress, TileBudget& budget,
                         tbb::enumerable_thread_specific<Scratch>& scratch, std::optional<AdaptiveSampling>& refinement, RenderRect&& renderRect) {
    const raster::Viewport viewport = frame.viewport;
    const raster::SamplePattern fullPattern = frame.pattern;
    const std::span<const raster::PixelBounds> bounds(frame.bounds);
    std::optional<raster::TileGrid> grid;
    return renderAdaptively(
        fullPattern, adaptiveThreshold, adaptiveFullContrast, region, viewport.width, viewport.height, stats, progress, refinement,
        [&](const raster::SamplePattern& pattern, const std::optional<raster::PixelBounds>& passRegion, ProgressReporter* passProgress,
            FirstPassGeometry* geometry) {
            frame.usePass(pattern, geometry);
            grid.emplace(viewport, tileSize, passRegion);
            return runTilePass(*grid, bounds, background, viewport.width, viewport.height, stats, passProgress, budget, scratch,
                               [&](int tile, Scratch& local, Image& image) {
                local.seenSources.clear();
                renderExactTile(*grid, tile, local, [&](std::span<const std::uint32_t> items, const raster::PixelBounds& rect, bool isPixel) {
                    const bool fits = renderRect(items, rect, isPixel, local, image);
                    if (geometry)
                        for (const TileRecord& r : local.records) local.seenSources.push_back(r.interval.source);
                    return fits;
                });
                if (geometry)
                    noteUnseenItems(grid->items(tile), bounds, grid->tileBounds(tile), local.seenSources, *geometry,
                                    [&](std::uint32_t item) { return frame.unseenSurfaceOf(item); });
            });
        },
        [&](const AdaptiveSampling& marks, AdaptiveSampling::Level level, const raster::SamplePattern& pattern, Image& image,
            ProgressReporter* passProgress) {
            frame.usePass(pattern, nullptr);
            PhaseTimer timer(stats, "tiles");
            runRefinementPass(*grid, marks, level, passProgress, scratch, [&](int tile, Scratch& local) {
                renderExactTileRuns(*grid, tile, marks, level, local,
                                    [&](std::span<const std::uint32_t> items, const raster::PixelBounds& rect, bool isPixel) {
                    return renderRect(items, rect, isPixel, local, image);
                });
            });
            frame.usePass(fullPattern, nullptr);
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

// Tells a first pass of adaptive sampling which of a tile's items (triangle segments, `bounds`
// their pixels) covered none of its samples: those whose bounds meet the tile's pixels `rect`
// and that are not in `seen` (the sources of all the tile's records or intervals, over every
// piece the memory budget cut it into; sorted and made unique here), each with its surface and
// nearest view depth, surfaceOf(item) -> {FirstPassGeometry::keyBit, depth (0: unknown)}, over
// those pixels.
template <class SurfaceOf>
void noteUnseenItems(std::span<const std::uint32_t> items, std::span<const raster::PixelBounds> bounds, const raster::PixelBounds& rect,
                     std::vector<std::uint32_t>& seen, FirstPassGeometry& firstPass, SurfaceOf&& surfaceOf) {
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    for (const std::uint32_t item : items) {
        const raster::PixelBounds& box = bounds[item];
        const raster::PixelBounds pixels{std::max(box.x0, rect.x0), std::max(box.y0, rect.y0), std::min(box.x1, rect.x1), std::min(box.y1, rect.y1)};
        if (pixels.empty() || std::binary_search(seen.begin(), seen.end(), item)) continue;
        const auto [key, nearest] = surfaceOf(item);
        firstPass.addUnseen({key, pixels, nearest});
    }
}

// Tells a first pass of adaptive sampling what pixel (x, y)'s one sample showed: the surfaces of
// its opaque pieces, and, where opaque surfaces covered it all the shutter (isOpaque), the
// farthest depth it saw there.
inline void tellFirstPass(FirstPassGeometry& firstPass, int x, int y, std::span<const VisiblePiece> pieces, const FlatTriangles& triangles,
                          bool isOpaque, float farthest) {
    for (const VisiblePiece& piece : pieces) firstPass.show(x, y, triangles[piece.triangle].mesh, triangles[piece.triangle].material);
    if (isOpaque) firstPass.setReach(x, y, farthest);
}

// The key and nearest view depth of a segment for noteUnseenItems, from its triangle and its
// nearness (1 / its nearest view depth, 0 where unknown).
inline std::pair<std::uint64_t, float> unseenSurface(const FlatTriangle& triangle, float nearness) {
    return {FirstPassGeometry::keyBit(triangle.mesh, triangle.material), nearness > 0.0f ? 1.0f / nearness : 0.0f};
}

// Puts each sample's records (runs[i] to runs[i + 1] of bySample) in the order of their sources,
// keeping the order of one source's: the order of a method that visits its items in ascending
// order, for a method that visited them in another (analytic's nearest first). Both sorts are
// stable, so either gives that one order. A run is mostly short (the intervals a sample sees),
// and insertion sort suits it; a dense mesh under fast motion leaves a hundred or more, whose
// insertion sort moved each record across half the run (5% of such a frame).
inline void sortRunsBySource(std::span<const std::uint32_t> runs, std::vector<TileRecord>& bySample) {
    constexpr std::uint32_t kInsertionRun = 16;
    for (std::size_t i = 0; i + 1 < runs.size(); ++i) {
        if (runs[i + 1] - runs[i] > kInsertionRun) {
            std::stable_sort(bySample.begin() + runs[i], bySample.begin() + runs[i + 1],
                             [](const TileRecord& a, const TileRecord& b) { return a.interval.source < b.interval.source; });
            continue;
        }
        for (std::uint32_t k = runs[i] + 1; k < runs[i + 1]; ++k) {
            const TileRecord r = bySample[k];
            std::uint32_t j = k;
            for (; j > runs[i] && bySample[j - 1].interval.source > r.interval.source; --j) bySample[j] = bySample[j - 1];
            bySample[j] = r;
        }
    }
}

// The shared second half of an exact method's tile, once its intervals are in scratch.records
// (their search began at intervalStart, and is timed up to their grouping): groups them by
// sample, resolves every sample exactly (resolveSample, compressing to the budget) and shades
// what shows (resolveTile: per sample, or per pixel as options.shading says). The method
// supplies triangleOf(source), shade(triangle, t0, t1, ShadingSite, pixel row) ->
// ShadedColor, and isStill(triangle): true where the triangle is still all the shutter under a
// still camera and shade() looks up a still point's texture at its site's samples
// (ShadingSite::samples), so that its textured pieces share a pixel's shading
// (Sharing::StillTextured); exactDepth, when given, measures misordering. The tile's pixels go to `image`,
// and their passes, when asked for, to `passes`; a first pass of adaptive sampling tells
// `firstPass` the surfaces each pixel showed. scratch.sampleNdc holds the tile's samples
// (tileSampleNdc of rect and pattern), as the search for intervals took them.
template <class Cache, class Counters, class TriangleOf, class Shade, class IsStill>
void resolveExactTile(const raster::PixelBounds& rect, const raster::SamplePattern& pattern, const Scene& scene,
                      const FlatTriangles& triangles, int width, int height, const ExactResolveOptions& options,
                      std::chrono::steady_clock::time_point intervalStart, ExactTileScratch<Cache, Counters>& scratch,
                      Image& image, TriangleOf&& triangleOf, Shade&& shade, IsStill&& isStill, const ExactDepthOfSource* exactDepth = nullptr,
                      PassFrame* passes = nullptr, FirstPassGeometry* firstPass = nullptr) {
    const std::size_t numSamples = std::size_t(rect.x1 - rect.x0 + 1) * std::size_t(rect.y1 - rect.y0 + 1) * std::size_t(pattern.count());
    raster::groupBySample(std::span<const TileRecord>(scratch.records), numSamples, scratch.runs, scratch.bySample);
    if (scratch.sortRunsBySource) sortRunsBySource(scratch.runs, scratch.bySample);
    scratch.counters.intervalSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - intervalStart).count();

    auto materialOf = [&](std::uint32_t triangle) -> const Material& { return scene.materials[triangles[triangle].material]; };
    resolveTile(rect, pattern, width, height, scene.background, std::span<const glm::dvec2>(scratch.sampleNdc), std::span<const TileRecord>(scratch.bySample),
                std::span<const std::uint32_t>(scratch.runs), scratch.list, scratch.resolve.pieces, scratch.color, scratch.coverage, image,
                options.shading, scratch.pixelShading, scratch.counters.resolve, passes, scratch.passes,
                [&](std::uint32_t triangle) { return sharingOf(materialOf(triangle), triangles[triangle], options.shading.isUnlit, isStill(triangle)); },
                [&](const glm::dvec2& ndc, int row, std::vector<ExposureInterval>& list) {
        std::optional<ExactDepth> depth;
        if (exactDepth) depth = [&](std::size_t k, float t) { return (*exactDepth)(list[k].source, t, ndc); };
        const glm::vec3 color = resolveSample(
            list, options.maxIntervals, options.oracle, depth ? &*depth : nullptr, options.occlusionCull, scene.shutter.rowWindow(row, height),
            scene.background, triangleOf, [&](std::uint32_t triangle) { return materialOf(triangle).isTranslucent(); },
            [&](std::uint32_t triangle, float t0, float t1) { return shade(triangle, t0, t1, sampleSite(ndc, pattern.samplesPerAxis()), row); },
            scratch.resolve, scratch.counters.resolve);
        if (firstPass) {
            // One sample per pixel, at its centre.
            const int px = std::clamp(int(std::floor((ndc.x + 1.0) * 0.5 * width)), 0, width - 1);
            bool isOpaque = scratch.resolve.coverage >= 1.0f - 1e-5f;
            for (const ExposureInterval& interval : list) isOpaque = isOpaque && !materialOf(triangleOf(interval.source)).isTranslucent();
            float farthest = 0.0f;
            if (isOpaque)
                forEachShownSurface(list, scratch.resolve, [&](std::uint32_t, float, float, float, float far) { farthest = std::max(farthest, far); });
            tellFirstPass(*firstPass, px, row, scratch.resolve.pieces, triangles, isOpaque, farthest);
        }
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
