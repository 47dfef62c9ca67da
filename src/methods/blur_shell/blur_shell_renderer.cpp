#include "methods/blur_shell/blur_shell_renderer.h"

#include "exposure/instant_frame.h"
#include "scene/blur_shell.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <limits>
#include <vector>

namespace streak {

namespace {

constexpr int kTileSize = 32;

class BlurShellRenderer final : public Renderer {
public:
    BlurShellRenderer(const BlurShellOptions& options, bool isSorted) : m_options(options), m_isSorted(isSorted) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        const ShellScene shellScene = buildShellScene(scene, m_options, context.stats);
        const Scene& drawn = shellScene.scene;

        PhaseTimer timer(context.stats, "draw");
        const FlatGeometry geometry(drawn);
        const raster::Viewport viewport{settings.width, settings.height};
        const raster::SamplePattern pattern = raster::samplePatternFor(settings.aa, settings.isGridPattern);
        raster::TileGrid grid(viewport, kTileSize, settings.region);
        exposure::InstantFrame frame;
        frame.setup(geometry, 1.0f, viewport, float(settings.width) / float(settings.height));
        grid.bin(frame.triangles.size(), [&](std::size_t i) { return frame.triangles[i].screen.bounds; });
        exposure::InstantDraw draw{settings.shading};
        if (!m_isSorted) draw.firstInOrderMesh = std::uint32_t(shellScene.firstShellMesh);
        Image image(settings.width, settings.height);
        image.setUncovered();
        tbb::enumerable_thread_specific<exposure::InstantScratch> scratch;
        std::atomic<std::int64_t> fragments{0};
        grid.forEachTile([&](int tile) {
            exposure::InstantScratch& local = scratch.local();
            fragments += exposure::drawInstantTile(geometry, frame, grid, tile, pattern, draw, local);
            raster::addTileToImage(grid.tileBounds(tile), pattern.count(), local.color, 1.0f, image.pixels(), settings.width);
            raster::addTileToImage(grid.tileBounds(tile), pattern.count(), local.coverage, 1.0f, image.alpha(), settings.width);
        }, /*includeEmpty=*/true);

        context.stats.setCounter("fragments", double(fragments.load()));
        return image;
    }

    std::optional<AnimationTrail> animationTrail() const override {
        return AnimationTrail{m_options.lengthSeconds, m_options.subdivisions + 1};
    }

private:
    BlurShellOptions m_options;
    bool m_isSorted;
};

}  // namespace

std::unique_ptr<Renderer> createBlurShellRenderer(OptionMap& options) {
    const BlurShellOptions shell = BlurShellOptions::read(options);
    return std::make_unique<BlurShellRenderer>(shell, BlurShellOptions::readIsSorted(options));
}

}  // namespace streak
