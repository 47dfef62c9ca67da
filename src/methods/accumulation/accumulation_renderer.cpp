#include "methods/accumulation/accumulation_renderer.h"

#include "exposure/instant_frame.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>

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
        raster::TileGrid grid(viewport, kTileSize);
        std::vector<glm::vec3> sum(std::size_t(settings.width) * settings.height, glm::vec3(0.0f));
        tbb::enumerable_thread_specific<exposure::InstantScratch> scratch;
        exposure::InstantFrame slice;
        const exposure::InstantDraw draw{settings.shading};
        double numFragments = 0.0;

        for (int s = 0; s < m_samples; ++s) {
            {
                PhaseTimer timer(context.stats, "setup");
                slice.setup(geometry, (float(s) + 0.5f) / float(m_samples), viewport, aspect);
                grid.bin(slice.triangles.size(), [&](std::size_t i) { return slice.triangles[i].screen.bounds; });
            }
            PhaseTimer timer(context.stats, "raster+shade");
            std::atomic<std::int64_t> fragments{0};
            grid.forEachTile([&](int tile) {
                exposure::InstantScratch& local = scratch.local();
                fragments += exposure::drawInstantTile(geometry, slice, grid, tile, pattern, draw, local);
                raster::addTileToImage(grid.tileBounds(tile), pattern.count(), local.color, 1.0f, sum, settings.width);
            }, /*includeEmpty=*/true);
            numFragments += double(fragments.load());
            if (context.progress) context.progress->update(double(s + 1) / m_samples);
        }

        Image image(settings.width, settings.height);
        const float norm = 1.0f / float(m_samples);
        for (std::size_t i = 0; i < sum.size(); ++i) image.pixels()[i] = sum[i] * norm;
        context.stats.setCounter("time_samples", m_samples);
        context.stats.setCounter("fragments", numFragments);
        return image;
    }

private:
    int m_samples;  ///< shutter times S
};

}  // namespace

std::unique_ptr<Renderer> createAccumulationRenderer(OptionMap& options) {
    return std::make_unique<AccumulationRenderer>(options.getInt("samples", 256, 1, 1 << 20));
}

}  // namespace streak
