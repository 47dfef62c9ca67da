#include "methods/motion_path/motion_path_renderer.h"

#include "methods/motion_path/interval.h"
#include "methods/motion_path/motion_path.h"
#include "methods/motion_path/resolve.h"
#include "raster/clip.h"
#include "raster/edge_equation.h"
#include "raster/tile_grid.h"
#include "scene/flat_geometry.h"
#include "util/error.h"

#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace streak {

namespace {

using motion_path::Interval;
using motion_path::MotionPath;

constexpr int kTileSize = 32;

struct Options {
    int maxFragments = 150;
    int maxIntervals = 90;
    int maskBits = 128;
    int textureSamples = 16;
    bool sortIntervals = true;
};

// One triangle over one linear segment of the shutter: its corners at both ends. Everything
// about an interval is evaluated from this, at exact times.
struct SegmentPath {
    std::uint32_t triangle = 0;
    float t0 = 0.0f, t1 = 0.0f;
    std::array<glm::vec4, 3> clip0{}, clip1{};
    std::array<glm::vec3, 3> world0{}, world1{};
    std::array<glm::vec3, 3> normal0{}, normal1{};
    float nearness = 0.0f;  ///< 1 / smallest corner view depth (0 if some corner is behind the eye)
};

// A sample a motion path may cover. Paths are conservative and overlap themselves, so a sample
// can hold several fragments of one path; it counts once.
struct Fragment {
    std::uint32_t sample = 0;  ///< within the tile
    std::uint32_t path = 0;    ///< index into the segment paths
    float nearness = 0.0f;     ///< 1 / the path's smallest view depth: which to keep on overflow
};

// Counters of one thread, summed at the end.
struct Counters {
    std::int64_t fragments = 0, fragmentOverflowSamples = 0, intervals = 0, maxIntervals = 0,
                 intervalOverflowSamples = 0, splits = 0, cycles = 0, culledIntervals = 0;
    double rasterSeconds = 0, buildSeconds = 0, sortSeconds = 0, resolveSeconds = 0;
};

struct TileScratch {
    std::vector<Fragment> fragments;
    std::vector<Fragment> bySample;
    std::vector<std::uint32_t> offsets;
    std::vector<Interval> intervals;
    std::vector<float> events;
    std::vector<glm::vec3> color;
    Counters counters;
};

// True when the triangle (all corners in front of the eye) is seen from its back at every time
// of the segment. Its orientation is det(c0, c1, c2)(u), a cubic in u; the corners are linear in
// u, so the determinant is multilinear in them and its Bernstein coefficients are the means of
// the determinants that take k corners from the end and 3 - k from the start. All negative: the
// cubic is negative on [0, 1] (convex hull property).
bool isBackFacingThroughout(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close) {
    auto xyw = [](const glm::vec4& c) { return glm::dvec3(c.x, c.y, c.w); };
    for (int k = 0; k <= 3; ++k) {
        double sum = 0.0;
        int count = 0;
        for (int mask = 0; mask < 8; ++mask) {
            if (std::popcount(unsigned(mask)) != k) continue;
            const glm::dvec3 r0 = xyw(mask & 1 ? close[0] : open[0]);
            const glm::dvec3 r1 = xyw(mask & 2 ? close[1] : open[1]);
            const glm::dvec3 r2 = xyw(mask & 4 ? close[2] : open[2]);
            sum += glm::dot(r0, glm::cross(r1, r2));
            ++count;
        }
        if (!(sum / count < 0.0)) return false;
    }
    return true;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class MotionPathRenderer final : public Renderer {
public:
    explicit MotionPathRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        Frame frame(scene, settings, m_options);
        {
            PhaseTimer timer(context.stats, "generate");
            frame.generate();
        }
        raster::TileGrid grid(frame.viewport, kTileSize);
        {
            PhaseTimer timer(context.stats, "bin");
            grid.bin(frame.faces.size(), [&](std::size_t i) { return frame.faces[i].screen.bounds; });
        }
        std::vector<glm::vec3> image(std::size_t(settings.width) * settings.height, scene.background);
        tbb::enumerable_thread_specific<TileScratch> scratch;
        {
            PhaseTimer timer(context.stats, "tiles");
            grid.forEachTile([&](int tile) {
                renderTile(frame, grid, tile, scratch.local(), image);
            }, /*includeEmpty=*/true);
        }
        if (context.progress) context.progress->update(1.0);

        Counters total;
        for (const TileScratch& s : scratch) {
            const Counters& c = s.counters;
            total.fragments += c.fragments, total.fragmentOverflowSamples += c.fragmentOverflowSamples;
            total.intervals += c.intervals, total.maxIntervals = std::max(total.maxIntervals, c.maxIntervals);
            total.intervalOverflowSamples += c.intervalOverflowSamples, total.splits += c.splits, total.cycles += c.cycles;
            total.culledIntervals += c.culledIntervals;
            total.rasterSeconds += c.rasterSeconds, total.buildSeconds += c.buildSeconds;
            total.sortSeconds += c.sortSeconds, total.resolveSeconds += c.resolveSeconds;
        }
        // Tile work runs on all threads at once: split the tiles' wall time by thread time.
        const double tileWall = context.stats.time("tiles");
        const double threadTime = total.rasterSeconds + total.buildSeconds + total.sortSeconds + total.resolveSeconds;
        const double scale = threadTime > 0.0 ? tileWall / threadTime : 0.0;
        context.stats.addTime("rasterize", total.rasterSeconds * scale);
        context.stats.addTime("build intervals", total.buildSeconds * scale);
        context.stats.addTime("sort", total.sortSeconds * scale);
        context.stats.addTime("resolve", total.resolveSeconds * scale);

        const double numSamples = double(settings.width) * settings.height * frame.pattern.count();
        RenderStats& stats = context.stats;
        stats.setCounter("segments_per_triangle", frame.numSegments);
        stats.setCounter("motion_paths", double(frame.paths.size()));
        stats.setCounter("path_faces", double(frame.faces.size()));
        stats.setCounter("backfacing_paths_skipped", double(frame.numBackFacingPaths));
        stats.setCounter("fragments", double(total.fragments));
        stats.setCounter("fragments_per_sample_mean", double(total.fragments) / numSamples);
        stats.setCounter("fragment_overflow_samples", double(total.fragmentOverflowSamples));
        stats.setCounter("intervals", double(total.intervals));
        stats.setCounter("intervals_per_sample_mean", double(total.intervals) / numSamples);
        stats.setCounter("intervals_per_sample_max", double(total.maxIntervals));
        stats.setCounter("interval_overflow_samples", double(total.intervalOverflowSamples));
        stats.setCounter("interval_splits", double(total.splits));
        stats.setCounter("sort_cycles", double(total.cycles));
        stats.setCounter("backface_intervals_culled", double(total.culledIntervals));
        stats.setCounter("max_fragments", m_options.maxFragments);
        stats.setCounter("max_intervals", m_options.maxIntervals);
        stats.setCounter("mask_bits", m_options.maskBits);
        stats.setCounter("texture_samples", m_options.textureSamples);

        Image result(settings.width, settings.height);
        std::copy(image.begin(), image.end(), result.pixels().begin());
        return result;
    }

private:
    // The scene's motion paths, set up for rasterization.
    struct Frame {
        Frame(const Scene& scene, const RenderSettings& settings, const Options& options)
            : scene(scene), settings(settings), options(options), geometry(scene), viewport{settings.width, settings.height},
              pattern(raster::SamplePattern::stratified(settings.aa)), aspect(float(settings.width) / float(settings.height)) {
            // Linear keys under a static camera are linear in clip space: one path per key
            // segment is exact. Curved screen motion (Bezier keys, a moving camera) is followed
            // by four linear segments per key segment.
            int maxKeys = 2;
            bool isCurved = !scene.camera.isStatic();
            for (const Mesh& mesh : scene.meshes) {
                maxKeys = std::max(maxKeys, mesh.numKeys);
                isCurved = isCurved || (mesh.interpolation == MotionInterpolation::Bezier && mesh.numKeys > 2);
            }
            numSegments = (maxKeys - 1) * (isCurved ? 4 : 1);
        }

        void generate() {
            const auto& triangles = geometry.triangles();
            std::vector<std::vector<glm::vec3>> positions(numSegments + 1), normals(numSegments + 1);
            std::vector<glm::mat4> clipFromWorld(numSegments + 1);
            tbb::parallel_for(0, numSegments + 1, [&](int k) {
                const float t = float(k) / float(numSegments);
                geometry.positionsAt(t, positions[k]);
                geometry.normalsAt(t, normals[k]);
                clipFromWorld[k] = scene.camera.clipFromWorld(t, aspect);
            });
            paths.resize(triangles.size() * numSegments);
            constexpr std::size_t kChunk = 1024;
            const std::size_t numChunks = (paths.size() + kChunk - 1) / kChunk;
            std::vector<std::vector<raster::RasterTriangle>> chunkFaces(numChunks);
            std::atomic<std::int64_t> culledPaths{0};
            tbb::parallel_for(std::size_t(0), numChunks, [&](std::size_t c) {
                MotionPath path;
                raster::TriangleSetup setup;
                std::int64_t localCulled = 0;
                for (std::size_t p = c * kChunk; p < std::min(paths.size(), (c + 1) * kChunk); ++p) {
                    const std::uint32_t tri = std::uint32_t(p / numSegments);
                    const int segment = int(p % numSegments);
                    SegmentPath& sp = paths[p];
                    sp.triangle = tri;
                    sp.t0 = float(segment) / float(numSegments);
                    sp.t1 = float(segment + 1) / float(numSegments);
                    const glm::uvec3 v = triangles[tri].vertices;
                    for (int i = 0; i < 3; ++i) {
                        sp.world0[i] = positions[segment][v[i]], sp.world1[i] = positions[segment + 1][v[i]];
                        sp.normal0[i] = normals[segment][v[i]], sp.normal1[i] = normals[segment + 1][v[i]];
                        sp.clip0[i] = clipFromWorld[segment] * glm::vec4(sp.world0[i], 1.0f);
                        sp.clip1[i] = clipFromWorld[segment + 1] * glm::vec4(sp.world1[i], 1.0f);
                    }
                    float minW = std::numeric_limits<float>::max();
                    for (int i = 0; i < 3; ++i) minW = std::min({minW, sp.clip0[i].w, sp.clip1[i].w});
                    sp.nearness = minW > 0.0f ? 1.0f / minW : 0.0f;
                    // A single-sided triangle that shows its back all through the segment is never
                    // seen: skip its path.
                    if (!triangles[tri].isDoubleSided && sp.nearness > 0.0f && isBackFacingThroughout(sp.clip0, sp.clip1)) {
                        ++localCulled;
                        continue;
                    }
                    motion_path::buildMotionPath(sp.clip0, sp.clip1, path);
                    for (int f = 0; f < path.count; ++f) {
                        raster::setupTriangle(path.faces[f].clip, std::uint32_t(p), scene.camera.zNear, viewport, raster::CullMode::None, setup);
                        chunkFaces[c].insert(chunkFaces[c].end(), setup.triangles.begin(), setup.triangles.begin() + setup.count);
                    }
                }
                culledPaths += localCulled;
            });
            for (const auto& chunk : chunkFaces) faces.insert(faces.end(), chunk.begin(), chunk.end());
            numBackFacingPaths = culledPaths.load();
        }

        // Corners of a path at time t on its linear clip-space segment.
        std::array<glm::vec4, 3> clipAt(const SegmentPath& p, float t) const {
            const float u = p.t1 > p.t0 ? (t - p.t0) / (p.t1 - p.t0) : 0.0f;
            return {glm::mix(p.clip0[0], p.clip1[0], u), glm::mix(p.clip0[1], p.clip1[1], u), glm::mix(p.clip0[2], p.clip1[2], u)};
        }

        // The exact time spans in which the sample lies inside the path's triangle (Gribel et
        // al. 2010): between consecutive roots of the three moving edge equations and the
        // segment ends, the sample is inside where all three edge functions share a sign and the
        // triangle's plane lies beyond the near plane. Appends start/end pairs to `events`.
        void exactSpans(const SegmentPath& p, const glm::dvec2& ndc, std::vector<float>& events) const {
            std::array<double, 8> breaks;
            int n = 0;
            breaks[n++] = 0.0;
            std::array<raster::Quadratic, 3> q;
            for (int e = 0; e < 3; ++e) {
                const int f = (e + 1) % 3;
                q[e] = raster::movingEdgeFunction(p.clip0[e], p.clip1[e], p.clip0[f], p.clip1[f], ndc);
                double roots[2];
                const int m = raster::solveQuadratic(q[e], roots);
                for (int i = 0; i < m; ++i)
                    if (roots[i] > 0.0 && roots[i] < 1.0) breaks[n++] = roots[i];
            }
            breaks[n++] = 1.0;
            // At most 8 breaks: insertion sort.
            for (int i = 1; i < n; ++i)
                for (int j = i; j > 0 && breaks[j] < breaks[j - 1]; --j) std::swap(breaks[j], breaks[j - 1]);
            bool wasInside = false;
            for (int i = 0; i + 1 < n; ++i) {
                if (!(breaks[i + 1] > breaks[i])) continue;
                const double u = 0.5 * (breaks[i] + breaks[i + 1]);
                const double e0 = q[0](u), e1 = q[1](u), e2 = q[2](u);
                bool inside = (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
                // Depth on the triangle is a convex combination of its corners' depths, so only a
                // path reaching nearer than the near plane needs the depth check.
                if (inside && !(p.nearness > 0.0f && p.nearness <= 1.0f / scene.camera.zNear))
                    inside = raster::evaluateHomogeneous(clipAt(p, float(p.t0 + u * (p.t1 - p.t0))), ndc).viewDepth >= scene.camera.zNear;
                if (inside != wasInside) events.push_back(float(p.t0 + breaks[i] * (p.t1 - p.t0)));
                wasInside = inside;
            }
            if (wasInside) events.push_back(p.t1);
        }

        const Scene& scene;
        const RenderSettings& settings;
        const Options& options;
        FlatGeometry geometry;
        raster::Viewport viewport;
        raster::SamplePattern pattern;
        float aspect;
        int numSegments = 1;
        std::vector<SegmentPath> paths;            ///< triangle-major, numSegments per triangle
        std::vector<raster::RasterTriangle> faces; ///< source = index into paths
        std::int64_t numBackFacingPaths = 0;       ///< skipped: back-facing all through their segment
    };

    // The shaded mean colour of a path over [t0, t1] at a sample, or false when the triangle
    // shows its back there (single-sided) or cannot be evaluated.
    bool shadeInterval(const Frame& frame, const SegmentPath& p, float t0, float t1, const glm::dvec2& ndc, Interval& out) const {
        const Scene& scene = frame.scene;
        const FlatTriangle& tri = frame.geometry.triangles()[p.triangle];
        const Material& material = scene.materials[tri.material];
        const float tm = 0.5f * (t0 + t1);
        const raster::HomogeneousSample s0 = raster::evaluateHomogeneous(frame.clipAt(p, t0), ndc);
        const raster::HomogeneousSample s1 = raster::evaluateHomogeneous(frame.clipAt(p, t1), ndc);
        const raster::HomogeneousSample sm = raster::evaluateHomogeneous(frame.clipAt(p, tm), ndc);
        if (!s0.isValid || !s1.isValid || !sm.isValid) return false;
        if (!tri.isDoubleSided && !sm.isFrontFacing) return false;

        const Mesh& mesh = frame.geometry.meshOf(tri);
        const std::uint32_t base = frame.geometry.meshVertexOffset(tri.mesh);
        const std::array<glm::vec2, 3> uv{mesh.uv(tri.vertices.x - base), mesh.uv(tri.vertices.y - base), mesh.uv(tri.vertices.z - base)};
        auto at = [](const auto& corners, const glm::dvec3& b) { return float(b.x) * corners[0] + float(b.y) * corners[1] + float(b.z) * corners[2]; };
        const glm::vec2 uv0 = at(uv, s0.bary), uv1 = at(uv, s1.bary);

        // Albedo: the mean of k texture samples along the interval (section 4.4). The paper
        // samples the straight uv path uv0 -> uv1. Where the true path bends (rotation, a
        // triangle turning over), the uv at mid-interval lies off that line; if it is more
        // than half a texel off, the k samples take the exact uv at k times instead. The level
        // is the coarser of the path's (length / k) and the pixel's own footprint: the paper's
        // alone aliases minified textures on slow intervals.
        glm::vec3 albedo = material.baseColor;
        float textureAlpha = 1.0f;
        if (material.baseColorTexture >= 0) {
            const Texture& texture = scene.textures[std::size_t(material.baseColorTexture)];
            const int k = frame.options.textureSamples;
            const glm::vec2 size(float(texture.width()), float(texture.height()));
            const glm::vec2 uvMid = at(uv, sm.bary);
            const bool isCurved = glm::length((uvMid - 0.5f * (uv0 + uv1)) * size) > 0.5f;
            const glm::vec2 half0 = glm::abs(uvMid - uv0) * size, half1 = glm::abs(uv1 - uvMid) * size;
            const float pathTexels = isCurved ? std::max(half0.x + half1.x, half0.y + half1.y)
                                              : std::max(std::abs(uv1.x - uv0.x) * size.x, std::abs(uv1.y - uv0.y) * size.y);
            float lod = std::log2(std::max(pathTexels / float(k), 1e-8f));
            const glm::dvec2 pixel(2.0 / frame.viewport.width, 2.0 / frame.viewport.height);
            const std::array<glm::vec4, 3> clipMid = frame.clipAt(p, tm);
            const raster::HomogeneousSample right = raster::evaluateHomogeneous(clipMid, ndc + glm::dvec2(pixel.x, 0.0));
            const raster::HomogeneousSample down = raster::evaluateHomogeneous(clipMid, ndc - glm::dvec2(0.0, pixel.y));
            if (right.isValid && down.isValid && right.viewDepth > 0.0 && down.viewDepth > 0.0)
                lod = std::max(lod, texture.lodFromFootprint(at(uv, right.bary) - uvMid, at(uv, down.bary) - uvMid));
            // Samples closer than a texel of the chosen level add nothing: a slow interval on a
            // minified texture needs fewer than k.
            const int count = std::clamp(int(std::ceil(pathTexels / std::exp2(lod))), 1, k);
            glm::vec4 sum(0.0f);
            for (int i = 0; i < count; ++i) {
                const float f = (float(i) + 0.5f) / float(count);
                glm::vec2 uvAt = glm::mix(uv0, uv1, f);
                if (isCurved) {
                    const raster::HomogeneousSample s = raster::evaluateHomogeneous(frame.clipAt(p, t0 + f * (t1 - t0)), ndc);
                    if (s.isValid) uvAt = at(uv, s.bary);
                }
                sum += texture.sample(uvAt, lod);
            }
            sum /= float(count);
            albedo *= glm::vec3(sum);
            textureAlpha = sum.w;
        }
        glm::vec3 color = albedo;
        if (frame.settings.shading == ShadingMode::Phong) {
            // Lighting by Simpson's rule over the interval: ends weighted 1, middle 4.
            auto lightAt = [&](const raster::HomogeneousSample& s, float t, bool isFrontFacing) {
                const float u = p.t1 > p.t0 ? (t - p.t0) / (p.t1 - p.t0) : 0.0f;
                std::array<glm::vec3, 3> world, normal;
                for (int i = 0; i < 3; ++i) {
                    world[i] = glm::mix(p.world0[i], p.world1[i], u);
                    normal[i] = glm::mix(p.normal0[i], p.normal1[i], u);
                }
                glm::vec3 n = at(normal, s.bary);
                if (!mesh.hasNormals()) n = glm::cross(world[1] - world[0], world[2] - world[0]);
                return lightPhong(scene, material, albedo, at(world, s.bary), n, isFrontFacing, scene.camera.positionAt(t));
            };
            color = (lightAt(s0, t0, sm.isFrontFacing) + 4.0f * lightAt(sm, tm, sm.isFrontFacing) + lightAt(s1, t1, sm.isFrontFacing)) / 6.0f;
        }
        out.t0 = t0, out.t1 = t1;
        out.depth0 = float(s0.viewDepth), out.depth1 = float(s1.viewDepth);
        out.color = color;
        out.alpha = material.isTranslucent() ? material.opacity * textureAlpha : 1.0f;
        out.source = p.triangle;
        return true;
    }

    // Builds the intervals of one sample from its fragments (sorted by path).
    void buildIntervals(const Frame& frame, std::span<const Fragment> fragments, const glm::dvec2& ndc, TileScratch& scratch) const {
        scratch.intervals.clear();
        for (std::size_t i = 0; i < fragments.size(); ++i) {
            if (i > 0 && fragments[i].path == fragments[i - 1].path) continue;
            const SegmentPath& path = frame.paths[fragments[i].path];
            scratch.events.clear();
            frame.exactSpans(path, ndc, scratch.events);
            for (std::size_t e = 0; e + 1 < scratch.events.size(); e += 2) {
                Interval interval;
                if (shadeInterval(frame, path, scratch.events[e], scratch.events[e + 1], ndc, interval)) scratch.intervals.push_back(interval);
                else ++scratch.counters.culledIntervals;
            }
        }
    }

    void renderTile(const Frame& frame, const raster::TileGrid& grid, int tile, TileScratch& scratch, std::vector<glm::vec3>& image) const {
        using Clock = std::chrono::steady_clock;
        const raster::PixelBounds rect = grid.tileBounds(tile);
        const int tileWidth = rect.x1 - rect.x0 + 1, tileHeight = rect.y1 - rect.y0 + 1;
        const int spp = frame.pattern.count();
        const std::size_t numSamples = std::size_t(tileWidth) * tileHeight * spp;
        Counters& counters = scratch.counters;

        auto start = Clock::now();
        scratch.fragments.clear();
        for (const std::uint32_t index : grid.items(tile)) {
            const raster::RasterTriangle& rt = frame.faces[index];
            const float nearness = frame.paths[rt.source].nearness;
            raster::scanTriangle(rt.screen, rect, frame.pattern, [&](int px, int py, int s, const raster::EdgeValues&) {
                const std::uint32_t sample = std::uint32_t((std::size_t(py - rect.y0) * tileWidth + (px - rect.x0)) * spp + s);
                scratch.fragments.push_back({sample, rt.source, nearness});
            });
        }
        counters.fragments += std::int64_t(scratch.fragments.size());
        // Counting sort by sample: each sample's fragments become one contiguous run.
        scratch.offsets.assign(numSamples + 1, 0);
        for (const Fragment& f : scratch.fragments) ++scratch.offsets[f.sample + 1];
        for (std::size_t i = 1; i <= numSamples; ++i) scratch.offsets[i] += scratch.offsets[i - 1];
        scratch.bySample.resize(scratch.fragments.size());
        {
            std::vector<std::uint32_t> cursor(scratch.offsets.begin(), scratch.offsets.end() - 1);
            for (const Fragment& f : scratch.fragments) scratch.bySample[cursor[f.sample]++] = f;
        }
        counters.rasterSeconds += secondsSince(start);

        scratch.color.assign(numSamples, frame.scene.background);
        for (std::size_t i = 0; i < numSamples; ++i) {
            std::span<Fragment> fragments(scratch.bySample.data() + scratch.offsets[i], scratch.offsets[i + 1] - scratch.offsets[i]);
            if (fragments.empty()) continue;
            start = Clock::now();
            std::sort(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) { return a.path < b.path; });
            fragments = fragments.first(std::size_t(std::unique(fragments.begin(), fragments.end(),
                                                                [](const Fragment& a, const Fragment& b) { return a.path == b.path; }) -
                                                    fragments.begin()));
            if (int(fragments.size()) > frame.options.maxFragments) {
                // Over budget: keep the nearest paths.
                ++counters.fragmentOverflowSamples;
                std::nth_element(fragments.begin(), fragments.begin() + frame.options.maxFragments, fragments.end(),
                                 [](const Fragment& a, const Fragment& b) { return a.nearness > b.nearness; });
                fragments = fragments.first(std::size_t(frame.options.maxFragments));
                std::sort(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) { return a.path < b.path; });
            }
            const int pixel = int(i / spp), s = int(i % spp);
            const int px = rect.x0 + pixel % tileWidth, py = rect.y0 + pixel / tileWidth;
            const glm::i64vec2 offset = frame.pattern.offsets[s];
            const glm::dvec2 ndc = raster::ndcFromRaster(double(std::int64_t(px) * raster::kSubpixelScale + offset.x) / raster::kSubpixelScale,
                                                         double(std::int64_t(py) * raster::kSubpixelScale + offset.y) / raster::kSubpixelScale,
                                                         frame.viewport.width, frame.viewport.height);
            buildIntervals(frame, fragments, ndc, scratch);
            std::vector<Interval>& intervals = scratch.intervals;
            if (int(intervals.size()) > frame.options.maxIntervals) {
                ++counters.intervalOverflowSamples;
                std::nth_element(intervals.begin(), intervals.begin() + frame.options.maxIntervals, intervals.end(),
                                 [](const Interval& a, const Interval& b) { return a.minDepth() < b.minDepth(); });
                intervals.resize(std::size_t(frame.options.maxIntervals));
            }
            counters.intervals += std::int64_t(intervals.size());
            counters.maxIntervals = std::max<std::int64_t>(counters.maxIntervals, std::int64_t(intervals.size()));
            const auto sorted = Clock::now();
            counters.buildSeconds += std::chrono::duration<double>(sorted - start).count();
            if (frame.options.sortIntervals) {
                motion_path::SortCounters sortCounters;
                motion_path::sortDepthTime(intervals, frame.options.maxIntervals, sortCounters);
                counters.splits += sortCounters.splits;
                counters.cycles += sortCounters.cycles;
                counters.intervalOverflowSamples += sortCounters.overflow > 0;
            } else {
                std::sort(intervals.begin(), intervals.end(), [](const Interval& a, const Interval& b) { return a.minDepth() < b.minDepth(); });
            }
            const auto resolved = Clock::now();
            counters.sortSeconds += std::chrono::duration<double>(resolved - sorted).count();
            scratch.color[i] = motion_path::resolveIntervals(intervals, frame.options.maskBits, frame.scene.background);
            counters.resolveSeconds += secondsSince(resolved);
        }
        // The image holds the background already; replace each tile pixel with its mean.
        for (int py = rect.y0; py <= rect.y1; ++py)
            for (int px = rect.x0; px <= rect.x1; ++px) image[std::size_t(py) * frame.viewport.width + px] = glm::vec3(0.0f);
        raster::addTileToImage(rect, spp, scratch.color, 1.0f, image, frame.viewport.width);
    }

    Options m_options;
};

}  // namespace

std::unique_ptr<Renderer> createMotionPathRenderer(OptionMap& options) {
    Options o;
    o.maxFragments = options.getInt("max-fragments", 150, 2, 1 << 16);
    o.maxIntervals = options.getInt("max-intervals", 90, 1, 1 << 16);
    o.maskBits = options.getInt("mask-bits", 128, 32, 256);
    if (o.maskBits != 32 && o.maskBits != 64 && o.maskBits != 128 && o.maskBits != 256)
        throw Error("method 'motion-path': mask-bits must be 32, 64, 128 or 256, got " + std::to_string(o.maskBits));
    o.textureSamples = options.getInt("texture-samples", 16, 1, 1024);
    o.sortIntervals = options.getInt("sort", 1, 0, 1) != 0;
    return std::make_unique<MotionPathRenderer>(o);
}

}  // namespace streak
