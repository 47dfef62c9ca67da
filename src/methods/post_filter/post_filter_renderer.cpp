#include "methods/post_filter/post_filter_renderer.h"

#include "exposure/instant_frame.h"
#include "exposure/reconstruction_filter.h"

#include <tbb/enumerable_thread_specific.h>

#include <cmath>
#include <limits>
#include <vector>

namespace streak {

namespace {

constexpr int kTileSize = 32;

class PostFilterRenderer final : public Renderer {
public:
    explicit PostFilterRenderer(const exposure::ReconstructionOptions& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        const int width = settings.width, height = settings.height;
        exposure::VelocityFrame frame;
        {
            PhaseTimer timer(context.stats, "centre frame");
            frame = centreFrame(scene, settings);
        }
        exposure::ReconstructionOptions options = m_options;
        options.seed = settings.seed;
        // The shutter only by its velocity scale: a rolling shutter's rows see D of the motion;
        // the curve's shape and the rows' offsets in time are not modelled (one instant, box filter).
        options.velocityScale = scene.shutter.rollingDuration;
        context.stats.setInfo("shutter_model", "velocity scale only");
        exposure::clampVelocities(frame, options);
        PhaseTimer timer(context.stats, "filter");
        Image image = exposure::reconstruct(frame, options);
        double moving = 0.0;
        for (const glm::vec2& v : frame.velocity) moving += glm::length(v) > 0.0f ? 1.0 : 0.0;
        context.stats.setCounter("moving_pixels", moving);
        context.stats.setCounter("tiles", double(((width + options.tile - 1) / options.tile) * ((height + options.tile - 1) / options.tile)));
        return image;
    }

private:
    // The scene at shutter centre: colour box-filtered over the --aa samples; depth and velocity
    // of the pixel's nearest opaque sample.
    static exposure::VelocityFrame centreFrame(const Scene& scene, const RenderSettings& settings) {
        const FlatGeometry geometry(scene);
        const raster::Viewport viewport{settings.width, settings.height};
        const raster::SamplePattern pattern = raster::samplePatternFor(settings.aa, settings.isGridPattern);
        const float aspect = float(settings.width) / float(settings.height);
        raster::TileGrid grid(viewport, kTileSize);
        exposure::InstantFrame instant;
        instant.setup(geometry, 0.5f, viewport, aspect);
        grid.bin(instant.triangles.size(), [&](std::size_t i) { return instant.triangles[i].screen.bounds; });
        const glm::mat4 openClip = scene.camera.clipFromWorld(0.0f, aspect), closeClip = scene.camera.clipFromWorld(1.0f, aspect);
        auto rasterOf = [&](const glm::mat4& clipFromWorld, const glm::vec3& p) {
            const glm::vec4 c = clipFromWorld * glm::vec4(p, 1.0f);
            if (!(c.w > 1e-6f)) return glm::vec2(std::numeric_limits<float>::quiet_NaN());  // behind the eye: no velocity
            return glm::vec2((c.x / c.w * 0.5f + 0.5f) * float(settings.width), (0.5f - 0.5f * c.y / c.w) * float(settings.height));
        };
        exposure::VelocityFrame frame;
        frame.width = settings.width, frame.height = settings.height;
        const std::size_t numPixels = std::size_t(settings.width) * std::size_t(settings.height);
        frame.color.assign(numPixels, glm::vec3(0.0f));
        frame.coverage.assign(numPixels, 0.0f);
        frame.depth.assign(numPixels, std::numeric_limits<float>::infinity());
        frame.velocity.assign(numPixels, glm::vec2(0.0f));
        const exposure::InstantDraw draw{settings.shading};
        tbb::enumerable_thread_specific<exposure::InstantScratch> scratch;
        const int spp = pattern.count();
        grid.forEachTile([&](int tile) {
            exposure::InstantScratch& local = scratch.local();
            exposure::drawInstantTile(geometry, instant, grid, tile, pattern, draw, local);
            const raster::PixelBounds rect = grid.tileBounds(tile);
            raster::addTileToImage(rect, spp, local.color, 1.0f, frame.color, settings.width);
            raster::addTileToImage(rect, spp, local.coverage, 1.0f, frame.coverage, settings.width);
            const int tileWidth = rect.x1 - rect.x0 + 1;
            for (int py = rect.y0; py <= rect.y1; ++py)
                for (int px = rect.x0; px <= rect.x1; ++px) {
                    const std::size_t first = (std::size_t(py - rect.y0) * std::size_t(tileWidth) + std::size_t(px - rect.x0)) * std::size_t(spp);
                    const exposure::InstantScratch::VisibleSample* nearest = nullptr;
                    for (int s = 0; s < spp; ++s) {
                        const auto& v = local.visible[first + std::size_t(s)];
                        if (v.invW > 0.0f && (!nearest || v.invW > nearest->invW)) nearest = &v;
                    }
                    if (!nearest) continue;
                    const raster::RasterTriangle& rt = instant.triangles[nearest->triangle];
                    const FlatTriangle& tri = geometry.triangles()[rt.source];
                    const glm::vec3 bary = rt.sourceBary(rt.screen.interpolate(nearest->edges).bary);
                    auto pointAt = [&](float t) {
                        const std::array<glm::vec3, 3> c = geometry.cornersAt(tri, t);
                        return bary.x * c[0] + bary.y * c[1] + bary.z * c[2];
                    };
                    const std::size_t i = std::size_t(py) * std::size_t(settings.width) + std::size_t(px);
                    frame.depth[i] = 1.0f / nearest->invW;
                    // McGuire's V: half the displacement over the shutter.
                    frame.velocity[i] = 0.5f * (rasterOf(closeClip, pointAt(1.0f)) - rasterOf(openClip, pointAt(0.0f)));
                    if (!std::isfinite(frame.velocity[i].x) || !std::isfinite(frame.velocity[i].y)) frame.velocity[i] = glm::vec2(0.0f);
                }
        }, /*includeEmpty=*/true);
        return frame;
    }

    exposure::ReconstructionOptions m_options;
};

}  // namespace

std::unique_ptr<Renderer> createPostFilterRenderer(OptionMap& options) {
    return std::make_unique<PostFilterRenderer>(exposure::ReconstructionOptions::read(options));
}

}  // namespace streak
