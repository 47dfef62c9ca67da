#include "methods/higher_order/higher_order_renderer.h"

#include "exposure/curved_geometry.h"
#include "exposure/curved_surface_point.h"
#include "exposure/pixel_shading.h"
#include "exposure/sample_resolve.h"
#include "exposure/tile_pass.h"
#include "raster/curved_triangle.h"
#include "raster/tile_grid.h"
#include "util/error.h"
#include "util/random.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace streak {

namespace {

using exposure::ExposureInterval;

constexpr int kTileSize = 16;
constexpr int kMaxDepthSplits = 4;  ///< refined depth: levels of halving per span
constexpr int kTilePieces = 8;      ///< TILE: slefe pieces of the shutter per block test

enum class Traversal { BoundingBox, Interval, Tile };

struct Options {
    Traversal traversal = Traversal::Interval;
    int intervals = 8;
    int tilePixels = 2;  ///< TILE: the side of the blocks tested
    raster::RootSolver solver = raster::RootSolver::ClosedForm;
    int cameraOrder = 3;
    double depthTolerance = 1e-3;
    exposure::ExactResolveOptions resolve;
    int checkVisibility = 0;
    exposure::SpanShadingSettings spanShading;  ///< texture-samples, taps-per-texel, texture-filter
};

struct Counters {
    std::int64_t coverageTests = 0, coverageHits = 0, culledBackFacing = 0, depthSplits = 0, pixelsSkipped = 0, blockTests = 0,
                 blocksCulled = 0, blocksCulledByCorners = 0, timePiecesTested = 0, timePiecesCulled = 0, timePiecesCulledByCorners = 0;
    raster::BernsteinRootCounts roots;
    double intervalSeconds = 0;
    exposure::SampleResolveCounters resolve;
};

// Its cache: the tile's curved triangles.
using TileScratch = exposure::ExactTileScratch<exposure::CurvedTriangleCache, Counters>;

bool contains(const raster::PixelBounds& b, int x, int y) { return x >= b.x0 && x <= b.x1 && y >= b.y0 && y <= b.y1; }

class HigherOrderRenderer final : public Renderer {
public:
    explicit HigherOrderRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        const raster::Viewport viewport{settings.width, settings.height};
        Options options = m_options;
        options.resolve.shading = m_options.resolve.shading.forMode(settings.shading);
        Frame frame{scene, settings, options, viewport, raster::samplePatternFor(settings.aa, settings.isGridPattern), {}, {}, {}, {}, 1};
        if (settings.passes.any()) frame.passes.emplace(scene, settings.passes, settings.width, settings.height);
        {
            PhaseTimer timer(context.stats, "setup");
            frame.geometry.emplace(scene, float(settings.width) / float(settings.height), m_options.cameraOrder);
            frame.spanShading = m_options.spanShading;
            frame.numBoxes = m_options.traversal == Traversal::Interval ? m_options.intervals : 1;
            frame.boxes = frame.geometry->screenBounds(viewport, frame.numBoxes);
            frame.bounds.resize(frame.geometry->segments().size());
            for (std::size_t i = 0; i < frame.bounds.size(); ++i) {
                raster::PixelBounds u{std::numeric_limits<int>::max(), std::numeric_limits<int>::max(), -1, -1};
                for (int k = 0; k < frame.numBoxes; ++k) {
                    const raster::PixelBounds& b = frame.boxes[i * std::size_t(frame.numBoxes) + std::size_t(k)];
                    if (b.empty()) continue;
                    u.x0 = std::min(u.x0, b.x0), u.y0 = std::min(u.y0, b.y0), u.x1 = std::max(u.x1, b.x1), u.y1 = std::max(u.y1, b.y1);
                }
                frame.bounds[i] = u.x1 < 0 ? raster::PixelBounds{} : u;
            }
        }
        tbb::enumerable_thread_specific<TileScratch> scratch;
        exposure::TileBudget budget(settings.memoryBudgetMB, settings.tileShareBytes);
        std::optional<exposure::AdaptiveSampling> refinement;
        Image image = exposure::runExactTilePasses(frame, kTileSize, scene.background, settings.adaptiveThreshold, settings.adaptiveFullContrast,
                                                   settings.region, context.stats, context.progress, budget, scratch, refinement,
                                                   [&](auto items, const raster::PixelBounds& rect, bool isPixel, TileScratch& local, Image& pixels) {
            return renderRect(frame, items, rect, isPixel, exposure::maxTileRecords(budget), local, pixels);
        });

        Counters total;
        exposure::TileBudgetCounters budgetTotal;
        for (const TileScratch& s : scratch) {
            budgetTotal.add(s.budget);
            const Counters& c = s.counters;
            total.coverageTests += c.coverageTests, total.coverageHits += c.coverageHits, total.culledBackFacing += c.culledBackFacing;
            total.depthSplits += c.depthSplits, total.pixelsSkipped += c.pixelsSkipped;
            total.blockTests += c.blockTests, total.blocksCulled += c.blocksCulled;
            total.blocksCulledByCorners += c.blocksCulledByCorners;
            total.timePiecesTested += c.timePiecesTested, total.timePiecesCulled += c.timePiecesCulled;
            total.timePiecesCulledByCorners += c.timePiecesCulledByCorners;
            total.roots.add(c.roots);
            total.intervalSeconds += c.intervalSeconds;
            total.resolve.add(c.resolve);
        }
        RenderStats& stats = context.stats;
        const double numPixels = double(settings.width) * settings.height;
        const double numSamples = refinement ? refinement->numSamples(numPixels, frame.pattern) : numPixels * frame.pattern.count();
        if (refinement) refinement->record(stats, settings.adaptiveThreshold);
        exposure::recordResolveStats(stats, total.resolve, total.intervalSeconds, numSamples,
                                     refinement ? refinement->numPixelRenders(numPixels) : numPixels,
                                     m_options.resolve.maxIntervals, options.resolve.shading);
        budget.record(stats, budgetTotal, exposure::kBytesPerTileRecord);
        stats.setCounter("motion_order", frame.geometry->order());
        exposure::recordSpanShadingSettings(stats, m_options.spanShading);
        stats.setCounter("motion_fitted", frame.geometry->isFitted() ? 1.0 : 0.0);
        stats.setCounter("pieces_per_triangle", frame.geometry->numPieces());
        stats.setCounter("curved_segments", double(frame.bounds.size()));
        stats.setCounter("traversal_boxes", frame.numBoxes);
        stats.setCounter("coverage_tests", double(total.coverageTests));
        stats.setCounter("coverage_hits", double(total.coverageHits));
        stats.setCounter("sample_test_efficiency", total.coverageTests > 0 ? double(total.coverageHits) / double(total.coverageTests) : 0.0);
        stats.setCounter("pixels_skipped_by_intervals", double(total.pixelsSkipped));
        stats.setCounter("tile_tests", double(total.blockTests));
        stats.setCounter("tiles_culled", double(total.blocksCulled));
        stats.setCounter("tiles_culled_by_triangle_test", double(total.blocksCulledByCorners));
        // TILE's culled time spans: the share of the blocks' slefe pieces of the shutter proved
        // missed (by either test), and by the Triangle-Tile test alone.
        const auto share = [&](std::int64_t pieces) { return total.timePiecesTested > 0 ? double(pieces) / double(total.timePiecesTested) : 0.0; };
        stats.setCounter("tile_time_culled_fraction", share(total.timePiecesCulled));
        stats.setCounter("tile_time_culled_by_triangle_test", share(total.timePiecesCulledByCorners));
        stats.setCounter("roots_solves", double(total.roots.solves));
        stats.setCounter("roots_no_sign_change", double(total.roots.noSignChange));
        stats.setCounter("roots_found", double(total.roots.roots));
        stats.setCounter("roots_iterations", double(total.roots.iterations));
        stats.setCounter("backface_intervals_culled", double(total.culledBackFacing));
        stats.setCounter("depth_splits", double(total.depthSplits));
        if (m_options.checkVisibility > 0) {
            PhaseTimer timer(stats, "check_visibility");
            raster::TileGrid grid(viewport, kTileSize, settings.region);
            grid.bin(frame.bounds.size(), [&](std::size_t i) { return frame.bounds[i]; });
            stats.setCounter("visibility_accuracy", visibilityAccuracy(frame, grid));
            stats.setCounter("visibility_checks", m_options.checkVisibility);
        }

        if (frame.passes) frame.passes->writeTo(image, context.stats);
        return image;
    }

    bool writesPasses() const override { return true; }
    bool refinesAdaptively() const override { return true; }

private:
    struct Frame {
        const Scene& scene;
        const RenderSettings& settings;
        const Options& options;
        raster::Viewport viewport;
        raster::SamplePattern pattern;
        std::optional<exposure::CurvedGeometry> geometry;
        exposure::SpanShadingSettings spanShading;
        std::vector<raster::PixelBounds> boxes;   ///< numBoxes per segment (traversal)
        std::vector<raster::PixelBounds> bounds;  ///< per segment: the union of its boxes, for binning
        int numBoxes = 1;
        mutable std::optional<exposure::PassFrame> passes;  ///< when settings.passes asks for any (tiles write their own pixels)
        exposure::FirstPassGeometry* firstPass = nullptr;  ///< adaptive sampling's first pass: what its samples show and miss

        // The pass's sample pattern (runExactTilePasses), and what its first pass tells (null in
        // any other).
        void usePass(const raster::SamplePattern& passPattern, exposure::FirstPassGeometry* passGeometry) {
            pattern = passPattern, firstPass = passGeometry;
        }

        // A segment's surface and nearest depth, for the first pass's unseen segments.
        std::pair<std::uint64_t, float> unseenSurfaceOf(std::uint32_t segment) const {
            return exposure::unseenSurface(geometry->flat().triangles()[geometry->segments()[segment].triangle], geometry->segments()[segment].nearness);
        }

        // A span's colour at a site (its point and footprint), in the row's shutter window.
        ShadedColor shade(std::uint32_t triangle, float t0, float t1, const exposure::ShadingSite& site, int row,
                          exposure::CurvedTriangleCache& cache) const {
            exposure::SpanShadingSettings rowShading = spanShading;
            rowShading.window = scene.shutter.rowWindow(row, viewport.height);
            return exposure::shadeCurvedSpan(*geometry, viewport, settings.shading, rowShading, triangle, t0, t1, site, cache);
        }
    };

    // The sample's exposure intervals from one segment: its exact inside spans, each cut where
    // linear depth between the ends departs from the true depth (refined depth), appended to
    // `out` with shutter times. Returns whether the coverage test hit.
    template <class Emit>
    static bool intervalsOf(const Frame& frame, std::uint32_t index, const raster::CurvedTriangle& curved, const glm::dvec2& ndc,
                            Counters& counters, Emit&& emit) {
        const exposure::CurvedSegment& segment = frame.geometry->segments()[index];
        const FlatTriangle& tri = frame.geometry->flat().triangles()[segment.triangle];
        const double zNear = frame.scene.camera.zNear;
        const bool checkNearPlane = !(segment.isInFront() && segment.nearness <= 1.0f / zNear);
        std::array<double, raster::CurvedTriangle::kMaxSpanBounds> b;
        const int n = curved.insideSpans(ndc, zNear, checkNearPlane, frame.options.solver, b, &counters.roots);
        ++counters.coverageTests;
        if (n == 0) return false;
        ++counters.coverageHits;
        const double dt = double(segment.t1) - double(segment.t0);
        for (int k = 0; k + 1 < n; k += 2) {
            const double u0 = b[std::size_t(k)], u1 = b[std::size_t(k + 1)];
            const raster::HomogeneousSample s0 = curved.sample(u0, ndc), s1 = curved.sample(u1, ndc);
            // The triangle cannot turn over inside a span (its edges would pass the sample).
            if (!s0.isValid || !s1.isValid || (!tri.isDoubleSided && !curved.sample(0.5 * (u0 + u1), ndc).isFrontFacing)) {
                ++counters.culledBackFacing;
                continue;
            }
            split(frame, curved, ndc, u0, s0.viewDepth, u1, s1.viewDepth, 0, counters, [&](double a, double da, double c, double dc) {
                ExposureInterval interval;
                interval.t0 = float(segment.t0 + a * dt), interval.t1 = float(segment.t0 + c * dt);
                interval.depth0 = float(da), interval.depth1 = float(dc);
                interval.source = index;
                if (interval.t1 > interval.t0) emit(interval);
            });
        }
        return true;
    }

    template <class Emit>
    static void split(const Frame& frame, const raster::CurvedTriangle& curved, const glm::dvec2& ndc, double u0, double d0, double u1,
                      double d1, int level, Counters& counters, Emit&& emit) {
        if (frame.options.depthTolerance > 0.0 && level < kMaxDepthSplits) {
            const double um = 0.5 * (u0 + u1);
            const raster::HomogeneousSample m = curved.sample(um, ndc);
            if (m.isValid && std::abs(m.viewDepth - 0.5 * (d0 + d1)) > frame.options.depthTolerance * std::abs(m.viewDepth)) {
                ++counters.depthSplits;
                split(frame, curved, ndc, u0, d0, um, m.viewDepth, level + 1, counters, emit);
                split(frame, curved, ndc, um, m.viewDepth, u1, d1, level + 1, counters, emit);
                return;
            }
        }
        emit(u0, d0, u1, d1);
    }

    // TILE: whether the block of pixels [bx, bx1] x [by, by1] (its samples lie in
    // [bx, bx1 + 1) x [by, by1 + 1)) is missed for the whole shutter, each piece of it proved
    // missed by the Triangle-Tile test or the Edge-Tile test. The cheap Triangle-Tile test
    // goes first; the Edge-Tile test runs only while pieces remain.
    static bool isBlockMissed(const raster::CurvedTriangle& curved, const raster::CurvedTriangle::FrustumSlefes& frustum, int bx, int by,
                              int bx1, int by1, int width, int height, Counters& counters) {
        using Mask = raster::CurvedTriangle::PieceMask;
        ++counters.blockTests;
        const glm::dvec2 lo = raster::ndcFromRaster(bx, by1 + 1, width, height), hi = raster::ndcFromRaster(bx1 + 1, by, width, height);
        const glm::dvec2 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
        const Mask all = raster::CurvedTriangle::allPieces(kTilePieces);
        const Mask byCorners = raster::CurvedTriangle::piecesMissedByCorners(frustum, centre, half);
        const Mask missed = byCorners == all ? all : byCorners | curved.piecesMissedByEdges(centre, half, kTilePieces);
        counters.timePiecesTested += kTilePieces;
        counters.timePiecesCulled += std::popcount(missed);
        counters.timePiecesCulledByCorners += std::popcount(byCorners);
        if (missed != all) return false;
        ++counters.blocksCulled;
        counters.blocksCulledByCorners += byCorners == all;
        return true;
    }

    // Whether generalized INTERVAL lets segment `index` reach pixel (px, py) at all.
    static bool isInSomeBox(const Frame& frame, std::uint32_t index, int px, int py) {
        if (frame.numBoxes == 1) return true;
        const raster::PixelBounds* boxes = &frame.boxes[std::size_t(index) * std::size_t(frame.numBoxes)];
        for (int k = 0; k < frame.numBoxes; ++k)
            if (contains(boxes[k], px, py)) return true;
        return false;
    }

    // The pixels of rect, within a tile whose segments are `items` (exposure::renderExactTile);
    // false, with the image left alone, once its records pass maxRecords (a single pixel cuts
    // them instead).
    bool renderRect(const Frame& frame, std::span<const std::uint32_t> items, const raster::PixelBounds& rect, bool isPixel,
                    std::size_t maxRecords, TileScratch& scratch, Image& image) const {
        using Clock = std::chrono::steady_clock;
        const int tileWidth = rect.x1 - rect.x0 + 1, tileHeight = rect.y1 - rect.y0 + 1;
        const int spp = frame.pattern.count();
        const exposure::CurvedGeometry& geometry = *frame.geometry;
        const auto segments = geometry.segments();
        const auto& triangles = geometry.flat().triangles();
        const int width = frame.viewport.width, height = frame.viewport.height;
        Counters& counters = scratch.counters;

        const auto start = Clock::now();
        scratch.records.clear();
        exposure::tileSampleNdc(rect, frame.pattern, width, height, scratch.sampleNdc);
        const std::size_t numSamples = scratch.sampleNdc.size();
        for (std::size_t k = 0; k < items.size(); ++k) {
            if (!exposure::keepRecordsWithinShare(scratch, maxRecords, isPixel, numSamples, k, items.size())) return false;
            const std::uint32_t index = items[k];
            const raster::PixelBounds& box = frame.bounds[index];
            const raster::PixelBounds region{std::max(box.x0, rect.x0), std::max(box.y0, rect.y0), std::min(box.x1, rect.x1),
                                             std::min(box.y1, rect.y1)};
            if (region.empty()) continue;
            const raster::CurvedTriangle& curved = exposure::curvedTriangleOf(geometry, index, scratch.cache);
            const bool isTile = frame.options.traversal == Traversal::Tile;
            const int block = isTile ? frame.options.tilePixels : std::max(tileWidth, tileHeight);
            // TILE: the Triangle-Tile test's corner slefes, once per segment and tile.
            std::optional<raster::CurvedTriangle::FrustumSlefes> frustum;
            if (isTile) frustum = curved.frustumSlefes(kTilePieces);
            for (int by = region.y0; by <= region.y1; by += block)
                for (int bx = region.x0; bx <= region.x1; bx += block) {
                    const int bx1 = std::min(bx + block - 1, region.x1), by1 = std::min(by + block - 1, region.y1);
                    if (isTile && isBlockMissed(curved, *frustum, bx, by, bx1, by1, width, height, counters)) continue;
                    for (int py = by; py <= by1; ++py)
                        for (int px = bx; px <= bx1; ++px) {
                            if (!isInSomeBox(frame, index, px, py)) {
                                counters.pixelsSkipped += 1;
                                continue;
                            }
                            for (int s = 0; s < spp; ++s) {
                                const auto sample = std::uint32_t((std::size_t(py - rect.y0) * tileWidth + (px - rect.x0)) * spp + s);
                                intervalsOf(frame, index, curved, scratch.sampleNdc[sample], counters, [&](const ExposureInterval& interval) {
                                    scratch.records.push_back({sample, interval});
                                });
                            }
                        }
                }
        }
        if (!exposure::keepRecordsWithinShare(scratch, maxRecords, isPixel, numSamples, items.size(), items.size())) return false;
        const auto triangleOfSource = [&](std::uint32_t source) { return segments[source].triangle; };
        exposure::resolveExactTile(
            rect, frame.pattern, frame.scene, triangles, width, height, frame.options.resolve, start, scratch, image,
            triangleOfSource,
            [&](std::uint32_t triangle, float t0, float t1, const exposure::ShadingSite& site, int row) {
                return frame.shade(triangle, t0, t1, site, row, scratch.cache);
            },
            // (A curved point looks up its texture at its own place only: no still sharing.)
            [](std::uint32_t) { return false; }, nullptr, frame.passes ? &*frame.passes : nullptr, frame.firstPass);
        return true;
    }

    // Gribel et al. 2013's visibility accuracy: at seeded random (sample, time) pairs, whether the
    // nearest of the sample's resolved intervals covering that time (linear depth, as the opaque
    // resolve orders them) belongs to the triangle that is nearest at that exact time, found by
    // testing every triangle binned to the sample's tile with the scene's own corners at that
    // time (key poses through the camera: fitting errors count). Pairs where both see the
    // background are left out.
    static double visibilityAccuracy(const Frame& frame, const raster::TileGrid& grid) {
        const exposure::CurvedGeometry& geometry = *frame.geometry;
        const auto segments = geometry.segments();
        const auto& triangles = geometry.flat().triangles();
        const double zNear = frame.scene.camera.zNear;
        const int width = frame.viewport.width, height = frame.viewport.height, spp = frame.pattern.count();
        Rng rng(frame.settings.seed * 7919u + 3u);
        Counters ignored;
        exposure::CurvedTriangleCache cache;
        int agree = 0, counted = 0;
        for (int check = 0; check < frame.options.checkVisibility; ++check) {
            const int px = std::min(width - 1, int(rng.uniform() * float(width)));
            const int py = std::min(height - 1, int(rng.uniform() * float(height)));
            const int s = std::min(spp - 1, int(rng.uniform() * float(spp)));
            const float t = rng.uniform();
            const glm::dvec2 ndc = frame.pattern.ndcOf(px, py, s, width, height);
            const int tile = (py / kTileSize) * ((width + kTileSize - 1) / kTileSize) + px / kTileSize;
            std::int64_t resolved = -1, truth = -1;
            double resolvedDepth = std::numeric_limits<double>::max(), trueDepth = std::numeric_limits<double>::max();
            for (const std::uint32_t index : grid.items(tile)) {
                const exposure::CurvedSegment& segment = segments[index];
                if (t < segment.t0 || t > segment.t1 || !isInSomeBox(frame, index, px, py) || !contains(frame.bounds[index], px, py)) continue;
                const raster::CurvedTriangle& curved = exposure::curvedTriangleOf(geometry, index, cache);
                intervalsOf(frame, index, curved, ndc, ignored, [&](const ExposureInterval& interval) {
                    if (t >= interval.t0 && t <= interval.t1 && interval.depthAt(t) < resolvedDepth)
                        resolvedDepth = interval.depthAt(t), resolved = segment.triangle;
                });
                // Brute force: the scene's triangle at exactly time t (its key poses and the
                // camera, not the curves fitted to them).
                const FlatTriangle& tri = triangles[segment.triangle];
                const std::array<glm::vec3, 3> world = geometry.flat().cornersAt(tri, t);
                const glm::mat4 clipFromWorld = frame.scene.camera.clipFromWorld(t, float(width) / float(height));
                std::array<glm::dvec3, 3> c;
                for (std::size_t i = 0; i < 3; ++i) {
                    const glm::vec4 clip = clipFromWorld * glm::vec4(world[i], 1.0f);
                    c[i] = glm::dvec3(clip.x, clip.y, clip.w);
                }
                const std::array<glm::dvec3, 3> edges{glm::cross(c[0], c[1]), glm::cross(c[1], c[2]), glm::cross(c[2], c[0])};
                const glm::dvec3 p(ndc, 1.0);
                if (!raster::isInsideByEdges(edges, ndc, {glm::dot(edges[0], p), glm::dot(edges[1], p), glm::dot(edges[2], p)})) continue;
                const raster::HomogeneousSample h = raster::evaluateHomogeneousXyw(c, ndc);
                if (!h.isValid || h.viewDepth < zNear || (!tri.isDoubleSided && !h.isFrontFacing)) continue;
                if (h.viewDepth < trueDepth) trueDepth = h.viewDepth, truth = segment.triangle;
            }
            if (resolved < 0 && truth < 0) continue;  // background both ways: no visibility to get right
            ++counted;
            agree += resolved == truth;
        }
        return counted > 0 ? double(agree) / double(counted) : 1.0;
    }

    Options m_options;
};

}  // namespace

std::unique_ptr<Renderer> createHigherOrderRenderer(OptionMap& options) {
    Options o;
    const std::string traversal = options.getString("traversal", "interval");
    if (traversal == "bbox") o.traversal = Traversal::BoundingBox;
    else if (traversal == "interval") o.traversal = Traversal::Interval;
    else if (traversal == "tile") o.traversal = Traversal::Tile;
    else throw Error("method 'higher-order': traversal must be bbox, interval or tile, got '" + traversal + "'");
    o.tilePixels = options.getInt("tile", 2, 1, 16);
    if (o.tilePixels != 1 && o.tilePixels != 2 && o.tilePixels != 4)
        throw Error("method 'higher-order': tile must be 1, 2 or 4 pixels, got " + std::to_string(o.tilePixels));
    o.intervals = options.getInt("intervals", 8, 1, 64);
    const std::string solver = options.getString("solver", "closed-form");
    if (solver == "closed-form") o.solver = raster::RootSolver::ClosedForm;
    else if (solver == "clipping") o.solver = raster::RootSolver::BezierClipping;
    else throw Error("method 'higher-order': solver must be closed-form or clipping, got '" + solver + "'");
    o.cameraOrder = options.getInt("camera-order", 3, 1, raster::CurvedTriangle::kMaxOrder);
    o.depthTolerance = options.getDouble("depth-tolerance", 1e-3, 0.0, 1.0);
    o.resolve.maxIntervals = options.getInt("max-intervals", 0, 0, 1 << 16);
    o.checkVisibility = options.getInt("check-visibility", 0, 0, 20000);
    o.resolve.occlusionCull = options.getInt("occlusion-cull", 1, 0, 1) != 0;
    o.spanShading = exposure::spanShadingSettings(options, "higher-order");
    o.resolve.shading = exposure::pixelShadingOptions(options, "higher-order");
    return std::make_unique<HigherOrderRenderer>(o);
}

}  // namespace streak
