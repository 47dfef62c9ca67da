#include "methods/analytic/analytic_renderer.h"

#include "exposure/early_cull.h"
#include "exposure/line_samples.h"
#include "exposure/pixel_shading.h"
#include "exposure/sample_resolve.h"
#include "exposure/tile_pass.h"
#include "exposure/segmented_geometry.h"
#include "exposure/triangle_surface_point.h"
#include "exposure/exposure_interval.h"
#include "raster/edge_batch.h"
#include "raster/moving_triangle.h"
#include "raster/swept_hull.h"
#include "raster/swept_pieces.h"
#include "raster/tile_grid.h"
#include "util/error.h"
#include "util/simd.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

namespace streak {

namespace {

using exposure::ExposureInterval;

constexpr double kRowMargin = 1e-9;  ///< NDC: a millionth of a pixel at 2000 pixels
constexpr int kRowSpanMinWidth = 4;  ///< pixels: narrower still boxes test every sample
constexpr double kHullShare = 0.5;  ///< a moving box takes row spans where its swept hull covers at most this share of it

constexpr int kTileSize = 16;

struct Options {
    exposure::ExactResolveOptions resolve;
    bool tileCull = true;  ///< skip the tiles, and the samples of a box, a segment stays outside
    bool hullCull = true;  ///< and a moving segment's samples beyond its swept hull (with tileCull)
    bool earlyCull = true; ///< skip the samples where nearer opaque triangles hide a segment all the shutter (renderRect)
    bool checkDepthOrder = false;
    bool lineSamples = false;  ///< line-samples=1: still tiles take each sample as a line across its pixel (exposure/line_samples.h)
    int lineRows = 0;          ///< line-rows: a line tile's lines per pixel; 0, the pattern's N^2 rows
    exposure::SpanShadingSettings spanShading;  ///< texture-samples, taps-per-texel, texture-filter
    int curveSegments = exposure::SegmentedGeometry::kAutoCurveSegments;
    bool closedCull = true;  ///< drop the back faces closed surfaces hide (exposure/closed_surfaces.h)
};

struct Counters {
    std::int64_t culledBackFacing = 0, tileTests = 0, tilesCulled = 0, samplesCulled = 0, samplesHidden = 0;
    std::int64_t lineSampleSurplus = 0;  ///< samples line tiles took beyond the point pattern's (line-rows)
    raster::RootCaseCounts roots;
    double intervalSeconds = 0;
    exposure::SampleResolveCounters resolve;
};

// Its cache: the tile's segments' edge equations; and the box loop's batch of them and bounds
// of a segment's samples (kept here so a segment that needs none does not construct them).
struct TileScratch : exposure::ExactTileScratch<exposure::MovingTriangleCache, Counters> {
    raster::EdgeBatch batch;
    raster::SweptHull hull;
    raster::SweptPieces pieces;  // where a segment has no hull (it turns over)
    exposure::EarlyCull earlyCull;
    bool isLineTile = false;  ///< this tile's samples are lines across their pixels (renderRect)
};

class AnalyticRenderer final : public Renderer {
public:
    explicit AnalyticRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        const raster::Viewport viewport{settings.width, settings.height};
        Options options = m_options;
        options.resolve.shading = m_options.resolve.shading.forMode(settings.shading);
        Frame frame{scene, settings, options, viewport, raster::samplePatternFor(settings.aa, settings.isGridPattern), {}, {}, {}};
        if (settings.passes.any()) frame.passes.emplace(scene, settings.passes, settings.width, settings.height);
        {
            PhaseTimer timer(context.stats, "setup");
            frame.segmented.emplace(scene, viewport, m_options.curveSegments, exposure::SegmentedGeometry::kMergeTolerancePixels, m_options.closedCull);
            frame.spanShading = m_options.spanShading;
            frame.computeBounds();
        }
        // (The passes take a surface's share and depths as they come: along a line, its coverage
        // and its depths there. The depth-order check measures in time.)
        frame.canLineSample = m_options.lineSamples && exposure::lineSamplingAllowed(scene, *frame.segmented) && !m_options.checkDepthOrder;
        // Every line spans its pixel, so cells across x divide nothing: a line tile's samples share
        // their shadings over the whole pixel, each a box over the stretches and rows it serves.
        frame.lineResolve = options.resolve;
        frame.lineResolve.shading.cellsPerAxis = 1;
        context.stats.setCounter("line_samples", frame.canLineSample ? 1 : 0);
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
            total.culledBackFacing += c.culledBackFacing, total.tileTests += c.tileTests, total.tilesCulled += c.tilesCulled;
            total.samplesCulled += c.samplesCulled, total.samplesHidden += c.samplesHidden;
            total.lineSampleSurplus += c.lineSampleSurplus;
            total.roots.add(c.roots);
            total.intervalSeconds += c.intervalSeconds;
            total.resolve.add(c.resolve);
        }
        RenderStats& stats = context.stats;
        const double numPixels = double(settings.width) * settings.height;
        const double numSamples = (refinement ? refinement->numSamples(numPixels, frame.pattern) : numPixels * frame.pattern.count()) +
                                  double(total.lineSampleSurplus);
        if (refinement) refinement->record(stats, settings.adaptiveThreshold);
        exposure::recordResolveStats(stats, total.resolve, total.intervalSeconds, numSamples,
                                     refinement ? refinement->numPixelRenders(numPixels) : numPixels, m_options.resolve.maxIntervals,
                                     options.resolve.shading);
        budget.record(stats, budgetTotal, exposure::kBytesPerTileRecord);
        stats.setInfo("simd", simd::levelName(frame.simd));
        exposure::recordSpanShadingSettings(stats, m_options.spanShading);
        exposure::recordSegments(stats, *frame.segmented);
        stats.setCounter("triangle_segments", double(frame.bounds.size()));
        stats.setCounter("backfacing_segments_skipped", double(frame.segmented->numBackFacing()));
        stats.setCounter("backface_intervals_culled", double(total.culledBackFacing));
        stats.setCounter("tile_tests", double(total.tileTests));
        stats.setCounter("tiles_culled", double(total.tilesCulled));
        stats.setCounter("samples_culled", double(total.samplesCulled));
        stats.setCounter("samples_hidden_before_solving", double(total.samplesHidden));
        stats.setCounter("roots_constant", double(total.roots.constant));
        stats.setCounter("roots_linear", double(total.roots.linear));
        stats.setCounter("roots_none", double(total.roots.noRealRoot));
        stats.setCounter("roots_double", double(total.roots.doubleRoot));
        stats.setCounter("roots_two", double(total.roots.twoRoots));
        if (m_options.checkDepthOrder) {
            const exposure::SampleResolveCounters& r = total.resolve;
            stats.setCounter("depth_overlap_time", r.coveredPairTime);
            stats.setCounter("depth_misordered_time", r.misorderedTime);
            stats.setCounter("depth_misordered_fraction", r.coveredPairTime > 0.0 ? r.misorderedTime / r.coveredPairTime : 0.0);
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
        std::optional<exposure::SegmentedGeometry> segmented;
        exposure::SpanShadingSettings spanShading;
        LargeBuffer<raster::PixelBounds> bounds;  ///< per triangle segment: the pixels it may cover
        LargeBuffer<float> occluderDepths;        ///< per triangle segment: EarlyCull::occluderDepths
        simd::Level simd = simd::activeLevel();    ///< how the box loop's edge batches run
        mutable std::optional<exposure::PassFrame> passes;  ///< when settings.passes asks for any (tiles write their own pixels)
        exposure::FirstPassGeometry* firstPass = nullptr;  ///< adaptive sampling's first pass: what its samples show and miss
        bool canLineSample = false;  ///< line-samples=1 where the frame allows it (render)
        exposure::ExactResolveOptions lineResolve;  ///< the resolve's options in a line tile: one shading cell
        raster::SamplePattern linePattern;          ///< a line tile's rows (line-rows; else the pass's pattern)

        // The pass's sample pattern (runExactTilePasses), with the line tiles' rows that follow
        // from it, and what its first pass tells (null in any other).
        void usePass(const raster::SamplePattern& passPattern, exposure::FirstPassGeometry* geometry) {
            pattern = passPattern, firstPass = geometry;
            linePattern = exposure::linePatternFor(pattern, options.lineRows);
        }

        // A segment's surface and nearest depth, for the first pass's unseen segments.
        std::pair<std::uint64_t, float> unseenSurfaceOf(std::uint32_t segment) const {
            return exposure::unseenSurface(segmented->flat().triangles()[segmented->segments()[segment].triangle], segmented->segments()[segment].nearness);
        }

        void computeBounds() {
            bounds = segmented->screenBounds(viewport);
            occluderDepths = exposure::EarlyCull::occluderDepths(*segmented, viewport);
        }

        // A span's colour at a site (its point and footprint), in the row's shutter window.
        ShadedColor shade(std::uint32_t triangle, float t0, float t1, const exposure::ShadingSite& site, int row,
                          exposure::MovingTriangleCache& cache) const {
            exposure::SpanShadingSettings rowShading = spanShading;
            rowShading.window = scene.shutter.rowWindow(row, viewport.height);
            return exposure::shadeTriangleSpan(*segmented, viewport, settings.shading, rowShading, triangle, t0, t1, site, cache);
        }
    };

    // True when the segment keeps one orientation and stays outside one of its edges over the
    // whole rectangle (NDC corners lo, hi) for its whole time. An edge function is linear in
    // the point, so over the rectangle it peaks at a corner; at each corner it is a quadratic
    // in u, whose largest value on [0, 1] is at an end or its vertex.
    static bool isOutsideTile(const exposure::TriangleSegment& s, const raster::MovingTriangle& moving, const glm::dvec2& lo,
                              const glm::dvec2& hi) {
        if (s.orientation == 0) return false;
        const double orientation = s.orientation;
        const glm::dvec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
        for (int e = 0; e < 3; ++e) {
            bool outside = true;
            for (const glm::dvec2& c : corners) {
                raster::Quadratic q = moving.edgeFunction(e, c);
                q.a *= orientation, q.b *= orientation, q.c *= orientation;
                if (q.maxOnUnitInterval() >= 0.0) {
                    outside = false;
                    break;
                }
            }
            if (outside) return true;
        }
        return false;
    }

    // The pixels of rect, within a tile whose segments are `items` (exposure::renderExactTile);
    // false, with the image left alone, once its records pass maxRecords (a single pixel cuts
    // them instead).
    bool renderRect(const Frame& frame, std::span<const std::uint32_t> items, const raster::PixelBounds& rect, bool isPixel,
                    std::size_t maxRecords, TileScratch& scratch, Image& image) const {
        using Clock = std::chrono::steady_clock;
        const int tileWidth = rect.x1 - rect.x0 + 1;
        const Scene& scene = frame.scene;
        const auto segments = frame.segmented->segments();
        // Line samples (exposure/line_samples.h) where every segment of the tile is still; not in
        // adaptive sampling's first pass, one point per pixel. A line tile takes its own rows.
        scratch.isLineTile = frame.canLineSample && !frame.firstPass && exposure::isLineTile(items, segments, scene.camera.zNear);
        const raster::SamplePattern& pattern = scratch.isLineTile ? frame.linePattern : frame.pattern;
        const int spp = pattern.count();
        const auto& triangles = frame.segmented->flat().triangles();
        const int width = frame.viewport.width, height = frame.viewport.height;
        Counters& counters = scratch.counters;

        // Intervals: every sample in each segment's box solves the segment's edge equations.
        const auto start = Clock::now();
        scratch.records.clear();
        exposure::tileSampleNdc(rect, pattern, width, height, scratch.sampleNdc);
        const std::size_t numSamples = scratch.sampleNdc.size();
        // The early cull (exposure::EarlyCull): a sample that opaque triangles cover all the
        // shutter (one, or a mesh's several in turn) from nearer than a later segment's nearest
        // corner is not solved for it. It is
        // off where the resolve sees every interval (a budget to compress to, the depth-order
        // check, occlusion-cull=0), in adaptive sampling's first pass, whose unseen-segment rule
        // counts intervals, where no segment spans the shutter, and in a tile where no segment
        // may hide another (EarlyCull::mayHideAny: a dense mesh's tiny triangles under a camera
        // move), which then keeps its order. The segments go nearest first, so that what hides
        // others is mostly drawn before them; the resolve puts each sample's list back in the
        // tile's order (sortRunsBySource), so the order changes nothing it sees.
        const bool isCullingEarly = frame.options.earlyCull && frame.options.resolve.occlusionCull && frame.options.resolve.maxIntervals == 0 &&
                                    !frame.options.checkDepthOrder && !frame.firstPass && frame.segmented->hasWholeShutterSegments() &&
                                    exposure::EarlyCull::mayHideAny(items, segments, frame.occluderDepths);
        exposure::EarlyCull& earlyCull = scratch.earlyCull;
        if (isCullingEarly) items = earlyCull.begin(numSamples, spp, tileWidth, items, segments);
        scratch.sortRunsBySource = isCullingEarly;
        const glm::dvec2 tileLo = raster::ndcFromRaster(rect.x0, rect.y1 + 1, width, height);
        const glm::dvec2 tileHi = raster::ndcFromRaster(rect.x1 + 1, rect.y0, width, height);
        for (std::size_t k = 0; k < items.size(); ++k) {
            if (!exposure::keepRecordsWithinShare(scratch, maxRecords, isPixel, numSamples, k, items.size())) return false;
            const std::uint32_t index = items[k];
            const exposure::TriangleSegment& segment = segments[index];
            const raster::PixelBounds& box = frame.bounds[index];
            const raster::PixelBounds region{std::max(box.x0, rect.x0), std::max(box.y0, rect.y0), std::min(box.x1, rect.x1),
                                             std::min(box.y1, rect.y1)};
            if (region.empty()) continue;
            const float nearest = isCullingEarly ? exposure::EarlyCull::nearestOf(segment.nearness) : -std::numeric_limits<float>::infinity();
            if (isCullingEarly && earlyCull.isRegionHidden(region, rect.x0, rect.y0, nearest)) {
                counters.samplesHidden += std::int64_t(region.x1 - region.x0 + 1) * (region.y1 - region.y0 + 1) * spp;
                continue;
            }
            const raster::MovingTriangle& moving = scratch.cache.get(*frame.segmented, index);
            if (frame.options.tileCull) {
                ++counters.tileTests;
                if (isOutsideTile(segment, moving, tileLo, tileHi)) {
                    ++counters.tilesCulled;
                    continue;
                }
            }
            const FlatTriangle& tri = triangles[segment.triangle];
            const bool isOccluder = isCullingEarly && !scene.materials[tri.material].isTranslucent();
            if (scratch.isLineTile) {
                // The stretches of its rows' lines it covers, as records (exposure/line_samples.h).
                const bool isSeen = exposure::forEachTileLineStretch(
                    moving, segment, tri.isDoubleSided, rect, region, pattern, frame.viewport, isCullingEarly ? &earlyCull : nullptr,
                    nearest, isOccluder, counters.samplesHidden, counters.samplesCulled, [&](std::uint32_t sample, const exposure::LineStretch& stretch) {
                        exposure::TileRecord r;
                        r.sample = sample;
                        r.interval.t0 = stretch.u0, r.interval.t1 = stretch.u1;
                        r.interval.depth0 = stretch.depth0, r.interval.depth1 = stretch.depth1;
                        r.interval.source = index;
                        scratch.records.push_back(r);
                    });
                counters.culledBackFacing += !isSeen;
                continue;
            }
            // Depth on the triangle is a convex combination of its corners' depths, so only a
            // segment reaching nearer than the near plane needs the depth check.
            const bool checkNearPlane = !(segment.isInFront() && segment.nearness <= 1.0f / scene.camera.zNear);
            // A run of the box's samples (`count` of them from `first`, `stride` apart): their
            // edge quadratics and staysOutside answers in batches (EdgeBatch, SIMD), then the
            // exact spans of the samples not culled, as records, in the run's order.
            const int cullOrientation = frame.options.tileCull ? segment.orientation : 0;
            auto visitRun = [&](std::uint32_t first, std::ptrdiff_t stride, int count) __attribute__((always_inline)) {
                for (int done = 0; done < count; done += raster::EdgeBatch::kCapacity) {
                    const int n = std::min(count - done, raster::EdgeBatch::kCapacity);
                    const auto batchFirst = std::uint32_t(first + done * stride);
                    raster::evaluateEdgeBatch(moving, cullOrientation, &scratch.sampleNdc[batchFirst], stride, n, scratch.batch, frame.simd);
                    for (int i = 0; i < n; ++i) {
                        if (scratch.batch.staysOutside[std::size_t(i)]) {
                            ++counters.samplesCulled;
                            continue;
                        }
                        const auto sample = std::uint32_t(batchFirst + i * stride);
                        if (isCullingEarly && earlyCull.isHidden(sample, nearest)) {
                            ++counters.samplesHidden;
                            continue;
                        }
                        const glm::dvec2 ndc = scratch.sampleNdc[sample];
                        std::array<double, 8> b;
                        const int m = raster::insideSpansOf(moving, scratch.batch, i, ndc, scene.camera.zNear, checkNearPlane, b, &counters.roots);
                        for (int k = 0; k + 1 < m; k += 2) {
                            // (A still triangle is the same at both ends.)
                            // (A still one's from the edge values the batch found.)
                            const raster::HomogeneousSample s0 =
                                moving.isStill() ? moving.stillSample(scratch.batch.edges[std::size_t(i)]) : moving.sample(b[k], ndc);
                            const raster::HomogeneousSample s1 = moving.isStill() ? s0 : moving.sample(b[k + 1], ndc);
                            // The triangle cannot turn over inside a span (its edges would have to
                            // pass the sample), so its facing at mid-span is its facing throughout.
                            if (!s0.isValid || !s1.isValid || (!tri.isDoubleSided && !moving.isFrontFacing(0.5 * (b[k] + b[k + 1])))) {
                                ++counters.culledBackFacing;
                                continue;
                            }
                            // (Written in place: copying in a record built on the stack stalled
                            // on its partly written fields.)
                            exposure::TileRecord& r = scratch.records.emplace_back();
                            r.sample = sample;
                            const double dt = double(segment.t1) - double(segment.t0);
                            r.interval.t0 = float(segment.t0 + b[k] * dt), r.interval.t1 = float(segment.t0 + b[k + 1] * dt);
                            r.interval.depth0 = float(s0.viewDepth), r.interval.depth1 = float(s1.viewDepth);
                            r.interval.source = index;
                            // What a mesh's opaque intervals cover together (coverStretch): a
                            // moving surface passes its triangles over a sample one after another.
                            if (isOccluder) {
                                const float farthest = std::max(r.interval.depth0, r.interval.depth1);
                                if (r.interval.t0 == 0.0f && r.interval.t1 == 1.0f) earlyCull.cover(sample, farthest);
                                else if (r.interval.t1 - r.interval.t0 >= exposure::EarlyCull::kShortestStretch)
                                    earlyCull.coverStretch(sample, r.interval.t0, r.interval.t1, farthest);
                            }
                        }
                    }
                }
            };
            // A segment whose box is wide enough visits per sample row only the span that can
            // hold its samples: a still one the x range beyond which staysOutside holds
            // (stillRowRange), a moving one its swept hull's (SweptHull). The samples beyond
            // are counted as culled all the same. A sample's x is the row's first plus whole
            // pixel steps to within 1e-15; kRowMargin leaves far more than that either side.
            // (A still box under kRowSpanMinWidth pixels wide tests its few samples faster than
            // it finds each row's span: with row spans for every box, the sub-pixel spheres'
            // interval phase at --aa 8 took 33% longer, ToyCar's 7%. A moving box takes row spans
            // only where it is as wide and two rows high, and its swept hull is at most kHullShare
            // of it, as under fast motion across the rows: on every moving box they culled under
            // 1% more of CesiumMan's samples, and building the hulls of MorphStressTest's many
            // small boxes made its interval phase 10% slower. That is the whole box's size, not
            // its part in this tile: a long diagonal box crossing a tile's side or its first or
            // last row leaves a part a few pixels wide or one row high, whose samples, tested
            // one by one, were 61% of the dense move's and held 1.5% of its intervals.)
            const int boxWidth = region.x1 - region.x0 + 1;
            bool isRowSpan = false;
            raster::SweptHull& hull = scratch.hull;
            raster::SweptPieces& pieces = scratch.pieces;
            bool isPieces = false;
            if (frame.options.tileCull) {
                if (moving.isStill()) {
                    isRowSpan = segment.orientation != 0 && boxWidth >= kRowSpanMinWidth;
                } else if (frame.options.hullCull && box.x1 - box.x0 + 1 >= kRowSpanMinWidth && box.y1 > box.y0) {
                    // A hull for the whole segment where its triangle keeps one orientation, else
                    // its time pieces'.
                    const bool hasHull = segment.orientation != 0 && hull.build(segment.clip0, segment.clip1);
                    isPieces = !hasHull && pieces.build(segment.clip0, segment.clip1);
                    const double boxArea = double(box.x1 - box.x0 + 1) * double(box.y1 - box.y0 + 1) * (4.0 / (double(width) * double(height)));
                    isRowSpan = (hasHull || isPieces) && (isPieces ? pieces.area() : hull.area()) <= kHullShare * boxArea;
                }
            }
            // Pixels per NDC unit: a product where a quotient by the step stalled each sample
            // row (the 1e-16 it differs by is far inside kRowMargin).
            const double perNdc = 0.5 * double(width);
            for (int py = region.y0; py <= region.y1; ++py) {
                const auto rowFirst = std::uint32_t((std::size_t(py - rect.y0) * tileWidth + (region.x0 - rect.x0)) * spp);
                // The row's pixels not wholly hidden from the segment, [open0, open1].
                int open0 = region.x0, open1 = region.x1;
                if (isCullingEarly) {
                    earlyCull.openRow(py, rect.x0, rect.y0, nearest, open0, open1);
                    counters.samplesHidden += std::int64_t(boxWidth - std::max(0, open1 - open0 + 1)) * spp;
                    if (open0 > open1) continue;
                }
                if (!isRowSpan) {
                    visitRun(rowFirst + std::uint32_t((open0 - region.x0) * spp), 1, (open1 - open0 + 1) * spp);
                    continue;
                }
                for (int s = 0; s < spp; ++s) {
                    const glm::dvec2 first = scratch.sampleNdc[rowFirst + std::uint32_t(s)];
                    int pxFirst = region.x1 + 1, pxLast = region.x1;
                    double xLo, xHi;
                    const bool hasRange = moving.isStill() ? moving.stillRowRange(first.y, segment.orientation, xLo, xHi)
                                                           : isPieces ? pieces.rowRange(first.y, xLo, xHi) : hull.rowRange(first.y, xLo, xHi);
                    if (hasRange) {
                        const double limit = double(boxWidth) + 1.0;
                        pxFirst = std::max(region.x0, region.x0 + int(std::ceil(std::clamp((xLo - kRowMargin - first.x) * perNdc, -limit, limit))));
                        pxLast = std::min(region.x1, region.x0 + int(std::floor(std::clamp((xHi + kRowMargin - first.x) * perNdc, -limit, limit))));
                    }
                    counters.samplesCulled += boxWidth - std::max(0, pxLast - pxFirst + 1);
                    pxFirst = std::max(pxFirst, open0), pxLast = std::min(pxLast, open1);
                    if (pxLast >= pxFirst) visitRun(rowFirst + std::uint32_t((pxFirst - region.x0) * spp + s), spp, pxLast - pxFirst + 1);
                }
            }
        }
        if (!exposure::keepRecordsWithinShare(scratch, maxRecords, isPixel, numSamples, items.size(), items.size())) return false;
        // Per sample: resolve the intervals exactly and shade what shows.
        const exposure::ExactDepthOfSource exactDepth = [&](std::uint32_t source, float t, const glm::dvec2& ndc) {
            const exposure::TriangleSegment& s = segments[source];
            return raster::MovingTriangle(s.clip0, s.clip1).sample(s.localTime(t), ndc).viewDepth;
        };
        const auto triangleOfSource = [&](std::uint32_t source) { return segments[source].triangle; };
        exposure::resolveExactTile(
            rect, pattern, scene, triangles, width, height, scratch.isLineTile ? frame.lineResolve : frame.options.resolve, start, scratch, image,
            triangleOfSource,
            [&](std::uint32_t triangle, float t0, float t1, const exposure::ShadingSite& site, int row) {
                if (!scratch.isLineTile) return frame.shade(triangle, t0, t1, site, row, scratch.cache);
                // A still triangle, at the middle of the stretch of the line that the span is.
                return frame.shade(triangle, 0.0f, 1.0f, exposure::lineSite(site, t0, t1, width), row, scratch.cache);
            },
            [&](std::uint32_t triangle) { return !scratch.isLineTile && frame.segmented->isStillAllShutter(triangle); },
            frame.options.checkDepthOrder ? &exactDepth : nullptr, frame.passes ? &*frame.passes : nullptr, frame.firstPass);
        if (scratch.isLineTile) counters.lineSampleSurplus += std::int64_t(numSamples / std::size_t(spp)) * (spp - frame.pattern.count());
        return true;
    }

    Options m_options;
};

}  // namespace

std::unique_ptr<Renderer> createAnalyticRenderer(OptionMap& options) {
    Options o;
    o.resolve.maxIntervals = options.getInt("max-intervals", 0, 0, 1 << 16);
    const std::string weights = options.getString("oracle-weights", "");
    if (!weights.empty()) {
        std::istringstream in(weights);
        float h[5];
        char comma = ',';
        for (int i = 0; i < 5; ++i) {
            if (i > 0) in >> comma;
            if (!(in >> h[i]) || comma != ',' || !(h[i] >= 0.0f))
                throw Error("method 'analytic': oracle-weights must be five non-negative numbers h1,...,h5, got '" + weights + "'");
        }
        if (!(in >> std::ws).eof()) throw Error("method 'analytic': oracle-weights must be five numbers, got '" + weights + "'");
        o.resolve.oracle = {h[0], h[1], h[2], h[3], h[4]};
    }
    o.tileCull = options.getInt("tile-cull", 1, 0, 1) != 0;
    o.hullCull = options.getInt("hull-cull", 1, 0, 1) != 0;
    o.resolve.occlusionCull = options.getInt("occlusion-cull", 1, 0, 1) != 0;
    o.earlyCull = options.getInt("early-cull", 1, 0, 1) != 0;
    o.closedCull = options.getInt("closed-cull", 1, 0, 1) != 0;
    o.checkDepthOrder = options.getInt("check-depth-order", 0, 0, 1) != 0;
    o.lineSamples = options.getInt("line-samples", 0, 0, 1) != 0;
    o.lineRows = options.getInt("line-rows", 0, 0, exposure::kMaxLineRows);
    if (o.lineRows > 0 && !o.lineSamples) throw Error("method 'analytic': line-rows sets the rows of line samples, and needs line-samples=1");
    o.spanShading = exposure::spanShadingSettings(options, "analytic");
    o.curveSegments = options.getInt("curve-segments", o.curveSegments, 0, exposure::SegmentedGeometry::kMaxCurveSegments);
    o.resolve.shading = exposure::pixelShadingOptions(options, "analytic");
    return std::make_unique<AnalyticRenderer>(o);
}

}  // namespace streak
