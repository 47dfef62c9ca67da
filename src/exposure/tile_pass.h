#pragma once

#include "exposure/exposure_interval.h"
#include "exposure/pixel_shading.h"
#include "exposure/sample_resolve.h"
#include "exposure/visible_pieces.h"
#include "raster/sample_pattern.h"
#include "raster/tile_grid.h"
#include "util/progress.h"
#include "util/stats.h"

#include <glm/vec3.hpp>
#include <tbb/enumerable_thread_specific.h>

#include <chrono>
#include <span>
#include <vector>

namespace streak::exposure {

// The frame of the exact-time methods that work per tile: bins items by their pixel bounds
// ("bin"), then runs renderTile(tile, scratch, image) on every tile in parallel with one Scratch
// per thread ("tiles"); each tile owns its pixels. Returns the image, background where no tile
// wrote; the per-thread scratches stay in `scratch` for the method to sum its counters.
template <class Scratch, class RenderTile>
std::vector<glm::vec3> runTilePass(raster::TileGrid& grid, std::span<const raster::PixelBounds> bounds, const glm::vec3& background,
                                   int width, int height, RenderStats& stats, ProgressReporter* progress,
                                   tbb::enumerable_thread_specific<Scratch>& scratch, RenderTile&& renderTile) {
    {
        PhaseTimer timer(stats, "bin");
        grid.bin(bounds.size(), [&](std::size_t i) { return bounds[i]; });
    }
    std::vector<glm::vec3> image(std::size_t(width) * std::size_t(height), background);
    {
        PhaseTimer timer(stats, "tiles");
        grid.forEachTile([&](int tile) { renderTile(tile, scratch.local(), image); }, /*includeEmpty=*/true);
    }
    if (progress) progress->update(1.0);
    return image;
}

// The second half of such a tile: every sample's intervals (records grouped by sample: runs[i]
// to runs[i + 1] of bySample, each with an `interval`) become its colour, pixel by pixel:
// resolve(ndc, pixel row, intervals) resolves a sample (exposure::resolveSample), returning the
// colour of all but its visible opaque pieces, which it leaves in `pieces`; the pixel's pieces
// are then shaded together as `shading` says (textured triangles, isTextured(triangle), in cells) by shade(triangle, t0, t1, ShadingSite, pixel row)
// (PixelShading), and the tile's pixels become the mean of their samples. A sample with no
// intervals is the background.
template <class Record, class IsTextured, class Resolve, class Shade>
void resolveTile(const raster::PixelBounds& rect, const raster::SamplePattern& pattern, int width, int height, const glm::vec3& background,
                 std::span<const Record> bySample, std::span<const std::uint32_t> runs, std::vector<ExposureInterval>& list,
                 const std::vector<VisiblePiece>& pieces, std::vector<glm::vec3>& color, std::vector<glm::vec3>& image, const PixelShadingOptions& shading,
                 PixelShading& pixelShading, SampleResolveCounters& counters, IsTextured&& isTextured, Resolve&& resolve, Shade&& shade) {
    using Clock = std::chrono::steady_clock;
    const int tileWidth = rect.x1 - rect.x0 + 1, spp = pattern.count();
    const std::size_t numSamples = runs.size() - 1;
    color.resize(numSamples);
    for (std::size_t first = 0; first < numSamples; first += std::size_t(spp)) {
        const int pixel = int(first / std::size_t(spp));
        const int px = rect.x0 + pixel % tileWidth, row = rect.y0 + pixel / tileWidth;
        pixelShading.begin(pattern, glm::dvec2(2.0 / width, 2.0 / height), shading.cellsFor(pattern.samplesPerAxis()));
        for (int s = 0; s < spp; ++s) {
            const std::size_t i = first + std::size_t(s);
            if (runs[i] == runs[i + 1]) {
                color[i] = background;
                continue;
            }
            const glm::dvec2 ndc = pattern.ndcOf(px, row, s, width, height);
            list.clear();
            for (std::uint32_t k = runs[i]; k < runs[i + 1]; ++k) list.push_back(bySample[k].interval);
            color[i] = resolve(ndc, row, list);
            pixelShading.add(s, ndc, std::span<const VisiblePiece>(pieces), isTextured);
        }
        const auto start = Clock::now();
        pixelShading.finish(shading, [&](std::uint32_t triangle, float t0, float t1, const ShadingSite& site) { return shade(triangle, t0, t1, site, row); },
                            std::span<glm::vec3>(color).subspan(first, std::size_t(spp)), counters.shading);
        counters.shadeSeconds += std::chrono::duration<double>(Clock::now() - start).count();
    }
    for (int py = rect.y0; py <= rect.y1; ++py)
        for (int px = rect.x0; px <= rect.x1; ++px) image[std::size_t(py) * std::size_t(width) + std::size_t(px)] = glm::vec3(0.0f);
    raster::addTileToImage(rect, spp, color, 1.0f, image, width);
}

}  // namespace streak::exposure
