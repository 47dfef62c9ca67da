#include "methods/stochastic/stochastic_renderer.h"

#include "exposure/sample_passes.h"

#include "raster/clip.h"
#include "raster/tile_grid.h"
#include "raster/translucency.h"
#include "scene/flat_geometry.h"
#include "util/random.h"

#include <glm/common.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <vector>

namespace streak {

namespace {

constexpr int kTileSize = 16;

// Where a triangle is at one sample's time.
struct SampleHit {
    const raster::RasterTriangle* triangle = nullptr;  ///< the (sub-)triangle covering the sample
    raster::EdgeValues edges{};
    float invW = 0.0f;
};

// The nearest opaque hit of one sample.
struct NearestHit {
    float invW = 0.0f;  ///< 0: nothing
    std::uint32_t triangle = 0;
};

struct TileScratch {
    std::vector<float> time;                  ///< per sample of the tile
    std::vector<glm::mat4> clipFromWorld;     ///< per sample, when the camera moves
    std::vector<NearestHit> nearest;
    std::vector<float> opaqueInvW;
    std::vector<glm::vec3> color;
    std::vector<float> coverage;
    std::vector<raster::TranslucentFragment> translucent;  ///< `triangle`: a FlatTriangle
    raster::TriangleSetup setup;              ///< reused: large, and tests are many
    // With the passes: per sample, its opaque surface (~0u: none) and colour before the
    // translucent ones over it, and SampledPasses' scratch.
    std::vector<std::uint32_t> opaqueTriangle;
    std::vector<glm::vec3> opaqueColor;
    std::vector<float> transmittance;
};

class StochasticRenderer final : public Renderer {
public:
    explicit StochasticRenderer(int samples) : m_samples(samples) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        const Frame frame(scene, settings);
        raster::TileGrid grid(frame.viewport, kTileSize, settings.region);
        Image sum(settings.width, settings.height);
        sum.setUncovered();
        std::vector<raster::PixelBounds> bounds(frame.geometry.triangles().size());
        tbb::enumerable_thread_specific<TileScratch> scratch;
        std::atomic<std::int64_t> tests{0};
        // The passes, when asked for: what each sample shows at each of its times (SampledPasses).
        std::optional<exposure::SampledPasses> passes;
        if (settings.passes.any())
            passes.emplace(scene, frame.geometry.triangles(), settings.passes, settings.width, settings.height,
                           settings.region.value_or(raster::PixelBounds{0, 0, settings.width - 1, settings.height - 1}),
                           1.0f / float(m_samples * frame.pattern.count()));

        for (int j = 0; j < m_samples; ++j) {
            // Stratum j's times in every row: its share of the exposure, from the top row's
            // window (the earliest) to the bottom row's.
            const float t0 = scene.shutter.rowWindow(0, settings.height).timeAt(float(j) / float(m_samples));
            const float t1 = scene.shutter.rowWindow(settings.height - 1, settings.height).timeAt(float(j + 1) / float(m_samples));
            {
                PhaseTimer timer(context.stats, "bounds");
                tbb::parallel_for(std::size_t(0), bounds.size(), [&](std::size_t i) { bounds[i] = frame.spaceTimeBounds(i, t0, t1); });
                grid.bin(bounds.size(), [&](std::size_t i) { return bounds[i]; });
            }
            PhaseTimer timer(context.stats, "sample+shade");
            grid.forEachTile([&](int tile) {
                tests += renderTile(frame, grid, tile, j, bounds, scratch.local(), sum, passes ? &*passes : nullptr);
            }, /*includeEmpty=*/true);
            if (context.progress) context.progress->update(double(j + 1) / m_samples);
        }

        const float norm = 1.0f / float(m_samples);
        for (glm::vec3& p : sum.pixels()) p *= norm;
        for (float& a : sum.alpha()) a *= norm;
        if (passes) passes->writeTo(sum, context.stats);
        context.stats.setCounter("time_samples_per_position", m_samples);
        context.stats.setCounter("samples_per_pixel", double(m_samples) * frame.pattern.count());
        context.stats.setCounter("triangle_tests", double(tests.load()));
        return sum;
    }

private:
    // Everything about the scene that does not change over the render.
    struct Frame {
        Frame(const Scene& scene, const RenderSettings& settings)
            : scene(scene), settings(settings), geometry(scene), viewport{settings.width, settings.height},
              pattern(raster::samplePatternFor(settings.aa, settings.isGridPattern)), aspect(float(settings.width) / float(settings.height)),
              isCameraStatic(scene.camera.isStatic()) {
            if (!isCameraStatic) return;
            // A static camera makes clip space a fixed linear map of world space, so a vertex's
            // clip position at t is the same combination of its clip-space keys.
            const glm::mat4 m = scene.camera.clipFromWorld(0.0f, aspect);
            for (const Mesh& mesh : scene.meshes) {
                std::vector<glm::vec4>& keys = clipKeys.emplace_back();
                keys.reserve(mesh.positions.size());
                for (const glm::vec3& p : mesh.positions) keys.push_back(m * glm::vec4(p, 1.0f));
            }
        }

        glm::mat4 clipFromWorldAt(float t) const { return scene.camera.clipFromWorld(t, aspect); }

        // Clip-space corners of triangle i at time t; clipFromWorld is used when the camera moves.
        std::array<glm::vec4, 3> clipCorners(std::size_t i, float t, const glm::mat4& clipFromWorld) const {
            const FlatTriangle& tri = geometry.triangles()[i];
            if (isCameraStatic) {
                const Mesh& mesh = scene.meshes[tri.mesh];
                const MotionWeights w = mesh.weightsAt(t);
                const std::size_t n = mesh.numVertices();
                const glm::vec4* keys = clipKeys[tri.mesh].data();
                const std::uint32_t base = geometry.meshVertexOffset(tri.mesh);
                return {w.apply(keys + (tri.vertices.x - base), n), w.apply(keys + (tri.vertices.y - base), n),
                        w.apply(keys + (tri.vertices.z - base), n)};
            }
            const std::array<glm::vec3, 3> p = geometry.cornersAt(tri, t);
            return {clipFromWorld * glm::vec4(p[0], 1.0f), clipFromWorld * glm::vec4(p[1], 1.0f), clipFromWorld * glm::vec4(p[2], 1.0f)};
        }

        // Pixels triangle i may cover at some time in [t0, t1]. Exact for linear segments seen
        // by a static camera (a moving point's projection then moves on a line); for curved
        // screen paths (moving camera, Bezier keys) the bounds are padded by each corner's
        // deviation from its chord at mid-interval, and where joints of the path (keys, Bezier
        // pieces' ends) fall inside, at the middle of each stretch between them too: two pieces
        // can bend apart around a joint that sits on the whole interval's chord. Anything
        // reaching the near plane or the guard band gets the whole image.
        raster::PixelBounds spaceTimeBounds(std::size_t i, float t0, float t1) const {
            const Mesh& mesh = scene.meshes[geometry.triangles()[i].mesh];
            float times[MotionWeights::kMaxKeys + 3];
            int numTimes = 0;
            times[numTimes++] = t0;
            times[numTimes++] = t1;
            times[numTimes++] = 0.5f * (t0 + t1);
            // The joints where the path may turn: every key of linear keys, every order-th of
            // Bezier pieces.
            const int step = mesh.bezierOrder();
            for (int k = step; k + 1 < mesh.numKeys && numTimes < int(std::size(times)); k += step)
                if (keyTime(k, mesh.numKeys) > t0 && keyTime(k, mesh.numKeys) < t1) times[numTimes++] = keyTime(k, mesh.numKeys);
            // Each corner's raster position at time t; false where the triangle needs clipping.
            const auto rasterCorners = [&](float t, std::array<glm::dvec2, 3>& out) {
                const std::array<glm::vec4, 3> clip = clipCorners(i, t, isCameraStatic ? glm::mat4(1.0f) : clipFromWorldAt(t));
                if (raster::needsClipping(clip, scene.camera.zNear)) return false;
                for (int v = 0; v < 3; ++v) out[v] = raster::rasterFromClip(clip[v], viewport);
                return true;
            };
            const raster::PixelBounds everything{0, 0, viewport.width - 1, viewport.height - 1};
            glm::dvec2 lo(1e300), hi(-1e300);
            std::array<glm::dvec2, 3> at[std::size(times)];
            for (int k = 0; k < numTimes; ++k) {
                if (!rasterCorners(times[k], at[k])) return everything;
                for (int v = 0; v < 3; ++v) lo = glm::min(lo, at[k][v]), hi = glm::max(hi, at[k][v]);
            }
            double pad = 1.0;  // fixed-point snapping
            const bool isCurved = !isCameraStatic || mesh.isCurved();
            if (isCurved) {
                std::array<double, 3> deviation{};
                for (int v = 0; v < 3; ++v) deviation[v] = glm::length(at[2][v] - 0.5 * (at[0][v] + at[1][v]));
                // Joints inside: the stretches between t0, them (ascending, times[3] on) and t1.
                for (int k = 2; numTimes > 3 && k < numTimes; ++k) {
                    const int a = k == 2 ? 0 : k, b = k + 1 < numTimes ? k + 1 : 1;
                    std::array<glm::dvec2, 3> middle;
                    if (!rasterCorners(0.5f * (times[a] + times[b]), middle)) return everything;
                    for (int v = 0; v < 3; ++v) deviation[v] = std::max(deviation[v], glm::length(middle[v] - 0.5 * (at[a][v] + at[b][v])));
                }
                for (int v = 0; v < 3; ++v) pad += 2.0 * deviation[v];
            }
            raster::PixelBounds b{int(std::floor(lo.x - pad)), int(std::floor(lo.y - pad)), int(std::floor(hi.x + pad)),
                                  int(std::floor(hi.y + pad))};
            b.x0 = std::max(b.x0, 0), b.y0 = std::max(b.y0, 0);
            b.x1 = std::min(b.x1, viewport.width - 1), b.y1 = std::min(b.y1, viewport.height - 1);
            return b;
        }

        // Tests triangle i at time t against the sample at fixed-point (X, Y).
        bool hit(std::size_t i, float t, const glm::mat4& clipFromWorld, std::int64_t X, std::int64_t Y,
                 raster::TriangleSetup& setup, SampleHit& out) const {
            const FlatTriangle& tri = geometry.triangles()[i];
            raster::setupTriangle(clipCorners(i, t, clipFromWorld), std::uint32_t(i), scene.camera.zNear, viewport,
                                  tri.isDoubleSided ? raster::CullMode::None : raster::CullMode::Back, setup);
            for (int k = 0; k < setup.count; ++k) {
                const raster::RasterTriangle& rt = setup.triangles[k];
                const raster::EdgeValues e = rt.screen.edgesAt(X, Y);
                if (!rt.screen.isInside(e)) continue;
                out = {&rt, e, rt.screen.interpolate(e).invW};
                return true;
            }
            return false;
        }

        ShadedColor shade(const SampleHit& hit, float t) const {
            const raster::RasterTriangle& rt = *hit.triangle;
            const FlatTriangle& tri = geometry.triangles()[rt.source];
            const raster::SourceFootprint f = rt.sourceFootprint(hit.edges, pattern.footprintStep());
            const SurfacePoint point = geometry.surfacePoint(tri, geometry.cornersAt(tri, t), geometry.cornerNormalsAt(tri, t), f.bary,
                                                             f.right, f.down, rt.screen.isFrontFacing);
            return shadeSurface(scene, settings.shading, point, scene.camera.positionAt(t));
        }

        const Scene& scene;
        const RenderSettings& settings;
        FlatGeometry geometry;
        raster::Viewport viewport;
        raster::SamplePattern pattern;
        float aspect;
        bool isCameraStatic;
        std::vector<std::vector<glm::vec4>> clipKeys;  ///< per mesh, static camera only
    };

    // Depth, Cryptomatte and deep as sampled at its times (SampledPasses).
    bool writesPasses() const override { return true; }

    // All samples of stratum j in one tile: times, visibility, shading, translucency; adds the
    // tile's mean colour (weighted 1/S) to `sum`, and what each sample shows to `passes`.
    // Returns the number of triangle tests.
    std::int64_t renderTile(const Frame& frame, const raster::TileGrid& grid, int tile, int j,
                            const std::vector<raster::PixelBounds>& bounds, TileScratch& scratch, Image& sum,
                            exposure::SampledPasses* passes) const {
        const raster::PixelBounds rect = grid.tileBounds(tile);
        const int tileWidth = rect.x1 - rect.x0 + 1, tileHeight = rect.y1 - rect.y0 + 1;
        const int spp = frame.pattern.count();
        const std::size_t numSamples = std::size_t(tileWidth) * tileHeight * spp;
        auto sampleIndex = [&](int px, int py, int a) { return (std::size_t(py - rect.y0) * tileWidth + (px - rect.x0)) * spp + a; };

        scratch.time.resize(numSamples);
        scratch.clipFromWorld.resize(frame.isCameraStatic ? 0 : numSamples);
        for (int py = rect.y0; py <= rect.y1; ++py) {
            // Stratified in the row's exposure, so a curve or rolling window places the times.
            const ShutterWindow window = frame.scene.shutter.rowWindow(py, frame.viewport.height);
            for (int px = rect.x0; px <= rect.x1; ++px)
                for (int a = 0; a < spp; ++a) {
                    const std::size_t i = sampleIndex(px, py, a);
                    const std::uint64_t pixel = std::uint64_t(py) * std::uint64_t(frame.viewport.width) + std::uint64_t(px);
                    scratch.time[i] = window.timeAt(stratifiedSampleTime(frame.settings.seed, pixel, a, j, m_samples));
                    if (!frame.isCameraStatic) scratch.clipFromWorld[i] = frame.clipFromWorldAt(scratch.time[i]);
                }
        }
        scratch.nearest.assign(numSamples, NearestHit{});
        scratch.translucent.clear();

        std::int64_t tests = 0;
        const glm::mat4 identity(1.0f);
        for (const std::uint32_t index : grid.items(tile)) {
            const raster::PixelBounds& b = bounds[index];
            const bool isTranslucent = frame.scene.materials[frame.geometry.triangles()[index].material].isTranslucent();
            for (int py = std::max(b.y0, rect.y0); py <= std::min(b.y1, rect.y1); ++py)
                for (int px = std::max(b.x0, rect.x0); px <= std::min(b.x1, rect.x1); ++px)
                    for (int a = 0; a < spp; ++a) {
                        const std::size_t i = sampleIndex(px, py, a);
                        const float t = scratch.time[i];
                        const std::int64_t X = std::int64_t(px) * raster::kSubpixelScale + frame.pattern.offsets[a].x;
                        const std::int64_t Y = std::int64_t(py) * raster::kSubpixelScale + frame.pattern.offsets[a].y;
                        ++tests;
                        SampleHit hit;
                        if (!frame.hit(index, t, frame.isCameraStatic ? identity : scratch.clipFromWorld[i], X, Y, scratch.setup, hit))
                            continue;
                        if (isTranslucent) {
                            const ShadedColor c = frame.shade(hit, t);
                            scratch.translucent.push_back({std::uint32_t(i), hit.invW, c.color, c.alpha, index});
                        } else if (hit.invW > scratch.nearest[i].invW) {
                            scratch.nearest[i] = {hit.invW, index};
                        }
                    }
        }

        scratch.color.resize(numSamples);
        scratch.coverage.resize(numSamples);
        scratch.opaqueInvW.resize(numSamples);
        for (int py = rect.y0; py <= rect.y1; ++py)
            for (int px = rect.x0; px <= rect.x1; ++px)
                for (int a = 0; a < spp; ++a) {
                    const std::size_t i = sampleIndex(px, py, a);
                    const NearestHit& n = scratch.nearest[i];
                    scratch.opaqueInvW[i] = n.invW;
                    scratch.color[i] = frame.scene.background, scratch.coverage[i] = 0.0f;
                    if (n.invW <= 0.0f) continue;
                    const float t = scratch.time[i];
                    const std::int64_t X = std::int64_t(px) * raster::kSubpixelScale + frame.pattern.offsets[a].x;
                    const std::int64_t Y = std::int64_t(py) * raster::kSubpixelScale + frame.pattern.offsets[a].y;
                    SampleHit hit;
                    // The same test again, deterministic, to recover where the winner was hit.
                    if (frame.hit(n.triangle, t, frame.isCameraStatic ? identity : scratch.clipFromWorld[i], X, Y, scratch.setup, hit))
                        scratch.color[i] = frame.shade(hit, t).color, scratch.coverage[i] = 1.0f;
                }
        if (passes) {
            scratch.opaqueColor.assign(scratch.color.begin(), scratch.color.end());
            scratch.opaqueTriangle.resize(numSamples);
            for (std::size_t i = 0; i < numSamples; ++i) scratch.opaqueTriangle[i] = scratch.coverage[i] > 0.0f ? scratch.nearest[i].triangle : ~0u;
        }
        if (!scratch.translucent.empty()) raster::compositeTranslucent(scratch.translucent, scratch.opaqueInvW, scratch.color, scratch.coverage);
        if (passes)
            passes->addTile(rect, spp, scratch.opaqueTriangle, scratch.opaqueInvW, scratch.opaqueColor, scratch.translucent, scratch.transmittance,
                            [](int) { return 1.0f; });

        raster::addTileToImage(rect, spp, scratch.color, 1.0f, sum.pixels(), frame.settings.width);
        raster::addTileToImage(rect, spp, scratch.coverage, 1.0f, sum.alpha(), frame.settings.width);
        return tests;
    }

    int m_samples;  ///< time strata S per sub-pixel position
};

}  // namespace

std::unique_ptr<Renderer> createStochasticRenderer(OptionMap& options) {
    return std::make_unique<StochasticRenderer>(options.getInt("samples", 8, 1, 1 << 20));
}

}  // namespace streak
