#include "methods/accumulation/accumulation_renderer.h"

#include "raster/clip.h"
#include "raster/tile_grid.h"
#include "raster/translucency.h"
#include "scene/flat_geometry.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>

#include <vector>

namespace streak {

namespace {

constexpr int kTileSize = 32;

// The nearest opaque surface at one sample: which raster triangle, and where on it.
struct VisibleSample {
    float invW = 0.0f;                ///< 0: nothing (every visible point has 1/w > 0)
    std::uint32_t triangle = 0;       ///< index into this time's raster triangles
    raster::EdgeValues edges{};       ///< edge values at the sample, for barycentrics and footprint
};

// Scratch memory of one thread for one tile.
struct TileScratch {
    std::vector<VisibleSample> visible;
    std::vector<float> opaqueInvW;
    std::vector<glm::vec3> color;
    std::vector<raster::TranslucentFragment> translucent;
};

// The geometry of the scene at one shutter time, set up for rasterization.
struct TimeSlice {
    float t = 0.0f;
    glm::vec3 eye{0.0f};
    std::vector<glm::vec3> positions;  ///< world, per global vertex
    std::vector<glm::vec3> normals;
    std::vector<raster::RasterTriangle> triangles;
};

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
        tbb::enumerable_thread_specific<TileScratch> scratch;
        TimeSlice slice;
        double numFragments = 0.0;

        for (int s = 0; s < m_samples; ++s) {
            slice.t = (float(s) + 0.5f) / float(m_samples);
            {
                PhaseTimer timer(context.stats, "setup");
                setupTimeSlice(geometry, slice, viewport, aspect);
                grid.bin(slice.triangles.size(), [&](std::size_t i) { return slice.triangles[i].screen.bounds; });
            }
            PhaseTimer timer(context.stats, "raster+shade");
            std::atomic<std::int64_t> fragments{0};
            grid.forEachTile([&](int tile) {
                fragments += renderTile(geometry, slice, grid, tile, pattern, settings, scratch.local(), sum);
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
    static void setupTimeSlice(const FlatGeometry& geometry, TimeSlice& slice, const raster::Viewport& viewport, float aspect) {
        const Scene& scene = geometry.scene();
        geometry.positionsAt(slice.t, slice.positions);
        geometry.normalsAt(slice.t, slice.normals);
        slice.eye = scene.camera.positionAt(slice.t);
        const glm::mat4 clipFromWorld = scene.camera.clipFromWorld(slice.t, aspect);
        const auto& triangles = geometry.triangles();
        // Fixed chunks set up in parallel and concatenated in order: the triangle order, and so
        // which of two equally deep surfaces wins, does not depend on the thread count.
        constexpr std::size_t kChunk = 4096;
        const std::size_t numChunks = (triangles.size() + kChunk - 1) / kChunk;
        std::vector<std::vector<raster::RasterTriangle>> chunks(numChunks);
        tbb::parallel_for(std::size_t(0), numChunks, [&](std::size_t c) {
            raster::TriangleSetup setup;
            for (std::size_t i = c * kChunk; i < std::min(triangles.size(), (c + 1) * kChunk); ++i) {
                const FlatTriangle& tri = triangles[i];
                const std::array<glm::vec4, 3> clip{clipFromWorld * glm::vec4(slice.positions[tri.vertices.x], 1.0f),
                                                    clipFromWorld * glm::vec4(slice.positions[tri.vertices.y], 1.0f),
                                                    clipFromWorld * glm::vec4(slice.positions[tri.vertices.z], 1.0f)};
                raster::setupTriangle(clip, std::uint32_t(i), scene.camera.zNear, viewport,
                                      tri.isDoubleSided ? raster::CullMode::None : raster::CullMode::Back, setup);
                chunks[c].insert(chunks[c].end(), setup.triangles.begin(), setup.triangles.begin() + setup.count);
            }
        });
        slice.triangles.clear();
        for (auto& chunk : chunks) slice.triangles.insert(slice.triangles.end(), chunk.begin(), chunk.end());
    }

    // Rasterizes, shades and resolves one tile at one time; adds the result to `sum`.
    static std::int64_t renderTile(const FlatGeometry& geometry, const TimeSlice& slice, const raster::TileGrid& grid, int tile,
                                   const raster::SamplePattern& pattern, const RenderSettings& settings, TileScratch& scratch,
                                   std::vector<glm::vec3>& sum) {
        const Scene& scene = geometry.scene();
        const raster::PixelBounds rect = grid.tileBounds(tile);
        const int tileWidth = rect.x1 - rect.x0 + 1, tileHeight = rect.y1 - rect.y0 + 1;
        const int spp = pattern.count();
        const std::size_t numSamples = std::size_t(tileWidth) * tileHeight * spp;
        scratch.visible.assign(numSamples, VisibleSample{});
        scratch.translucent.clear();
        auto sampleIndex = [&](int px, int py, int s) {
            return (std::size_t(py - rect.y0) * tileWidth + (px - rect.x0)) * spp + s;
        };
        auto shade = [&](const raster::RasterTriangle& rt, const raster::EdgeValues& e) {
            const FlatTriangle& tri = geometry.triangles()[rt.source];
            const raster::SourceFootprint f = rt.sourceFootprint(e, pattern.footprintStep());
            const std::array<glm::vec3, 3> corners{slice.positions[tri.vertices.x], slice.positions[tri.vertices.y],
                                                   slice.positions[tri.vertices.z]};
            const std::array<glm::vec3, 3> normals{slice.normals[tri.vertices.x], slice.normals[tri.vertices.y],
                                                   slice.normals[tri.vertices.z]};
            const SurfacePoint point =
                geometry.surfacePoint(tri, corners, normals, f.bary, f.right, f.down, rt.screen.isFrontFacing);
            return shadeSurface(scene, settings.shading, point, slice.eye);
        };

        std::int64_t fragments = 0;
        for (const std::uint32_t index : grid.items(tile)) {
            const raster::RasterTriangle& rt = slice.triangles[index];
            const bool isTranslucent = scene.materials[geometry.triangles()[rt.source].material].isTranslucent();
            raster::scanTriangle(rt.screen, rect, pattern, [&](int px, int py, int s, const raster::EdgeValues& e) {
                ++fragments;
                const std::size_t i = sampleIndex(px, py, s);
                const float invW = rt.screen.interpolate(e).invW;
                if (isTranslucent) {
                    const ShadedColor c = shade(rt, e);
                    scratch.translucent.push_back({std::uint32_t(i), invW, c.color, c.alpha});
                } else if (invW > scratch.visible[i].invW) {
                    scratch.visible[i] = {invW, index, e};
                }
            });
        }

        scratch.color.resize(numSamples);
        scratch.opaqueInvW.resize(numSamples);
        for (std::size_t i = 0; i < numSamples; ++i) {
            const VisibleSample& v = scratch.visible[i];
            scratch.opaqueInvW[i] = v.invW;
            scratch.color[i] = v.invW > 0.0f ? shade(slice.triangles[v.triangle], v.edges).color : scene.background;
        }
        if (!scratch.translucent.empty()) raster::compositeTranslucent(scratch.translucent, scratch.opaqueInvW, scratch.color);

        raster::addTileToImage(rect, spp, scratch.color, 1.0f, sum, settings.width);
        return fragments;
    }

    int m_samples;  ///< shutter times S
};

}  // namespace

std::unique_ptr<Renderer> createAccumulationRenderer(OptionMap& options) {
    return std::make_unique<AccumulationRenderer>(options.getInt("samples", 256, 1, 1 << 20));
}

}  // namespace streak
