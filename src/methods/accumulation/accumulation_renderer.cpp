#include "methods/accumulation/accumulation_renderer.h"

#include "exposure/instant_frame.h"
#include "exposure/instant_schedule.h"
#include "exposure/sample_passes.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <limits>
#include <optional>
#include <vector>

namespace streak {

namespace {

constexpr int kTileSize = 32;

class AccumulationRenderer final : public Renderer {
public:
    explicit AccumulationRenderer(int samples) : m_samples(samples) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        const FlatGeometry geometry(scene);
        const raster::Viewport viewport{settings.width, settings.height};
        const raster::SamplePattern pattern = raster::samplePatternFor(settings.aa, settings.isGridPattern);
        const float aspect = float(settings.width) / float(settings.height);
        raster::TileGrid grid(viewport, kTileSize, settings.region);
        std::vector<glm::vec3> sum(std::size_t(settings.width) * settings.height, glm::vec3(0.0f));
        std::vector<float> coverage(sum.size(), 0.0f);
        tbb::enumerable_thread_specific<exposure::InstantScratch> scratch;
        exposure::InstantFrame slice;
        // The passes, when asked for: what each sample shows at each instant (SampledPasses).
        std::optional<exposure::SampledPasses> passes;
        const exposure::InstantSchedule schedule(scene.shutter, m_samples, settings.height);
        // Each instant's weight in the frame (a non-uniform schedule weighs its own instants).
        const float norm = schedule.isUniform() ? 1.0f / float(m_samples) : 1.0f;
        if (settings.passes.any())
            passes.emplace(scene, geometry.triangles(), settings.passes, settings.width, settings.height,
                           settings.region.value_or(raster::PixelBounds{0, 0, settings.width - 1, settings.height - 1}),
                           norm / float(pattern.count()));
        const exposure::InstantDraw draw{settings.shading, std::numeric_limits<std::uint32_t>::max(), passes.has_value()};
        double numFragments = 0.0;

        const int numInstants = schedule.numInstants();
        for (int s = 0; s < numInstants; ++s) {
            const std::pair<int, int> rows = schedule.rows(s);
            const int firstRow = rows.first, lastRow = rows.second;
            if (firstRow > lastRow) continue;
            {
                PhaseTimer timer(context.stats, "setup");
                slice.setup(geometry, schedule.time(s), viewport, aspect);
                grid.bin(slice.triangles.size(), [&](std::size_t i) { return slice.triangles[i].screen.bounds; });
            }
            PhaseTimer timer(context.stats, "raster+shade");
            std::atomic<std::int64_t> fragments{0};
            grid.forEachTile([&](int tile) {
                const raster::PixelBounds rect = grid.tileBounds(tile);
                if (rect.y1 < firstRow || rect.y0 > lastRow) return;
                exposure::InstantScratch& local = scratch.local();
                fragments += exposure::drawInstantTile(geometry, slice, grid, tile, pattern, draw, local);
                if (passes)
                    passes->addTile(rect, pattern.count(), local.opaqueTriangle, local.opaqueInvW, local.opaqueColor, local.translucent, local.transmittance,
                                    [&](int y) { return schedule.isUniform() ? 1.0f : schedule.weight(s, y); });
                if (schedule.isUniform()) {
                    raster::addTileToImage(rect, pattern.count(), local.color, 1.0f, sum, settings.width);
                    raster::addTileToImage(rect, pattern.count(), local.coverage, 1.0f, coverage, settings.width);
                    return;
                }
                // A rolling shutter: each row weighs the instant by its own window.
                const std::size_t rowSamples = std::size_t(rect.x1 - rect.x0 + 1) * std::size_t(pattern.count());
                for (int y = rect.y0; y <= rect.y1; ++y) {
                    const std::size_t first = std::size_t(y - rect.y0) * rowSamples;
                    raster::addTileToImage({rect.x0, y, rect.x1, y}, pattern.count(), std::span<const glm::vec3>(local.color).subspan(first, rowSamples),
                                           schedule.weight(s, y), sum, settings.width);
                    raster::addTileToImage({rect.x0, y, rect.x1, y}, pattern.count(), std::span<const float>(local.coverage).subspan(first, rowSamples),
                                           schedule.weight(s, y), coverage, settings.width);
                }
            }, /*includeEmpty=*/true);
            numFragments += double(fragments.load());
            if (context.progress) context.progress->update(double(s + 1) / numInstants);
        }

        Image image(settings.width, settings.height);
        for (std::size_t i = 0; i < sum.size(); ++i) image.pixels()[i] = sum[i] * norm, coverage[i] *= norm;
        image.setAlpha(std::move(coverage));
        if (passes) passes->writeTo(image, context.stats);
        context.stats.setCounter("time_samples", m_samples);
        context.stats.setCounter("instants", numInstants);
        context.stats.setCounter("fragments", numFragments);
        return image;
    }

    // Depth, Cryptomatte and deep as sampled at its instants (SampledPasses).
    bool writesPasses() const override { return true; }

private:
    int m_samples;  ///< shutter times S
};

}  // namespace

std::unique_ptr<Renderer> createAccumulationRenderer(OptionMap& options) {
    return std::make_unique<AccumulationRenderer>(options.getInt("samples", 256, 1, 1 << 20));
}

}  // namespace streak
