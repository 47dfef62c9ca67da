#include "methods/motion_path/motion_path_renderer.h"

#include "exposure/early_cull.h"
#include "exposure/line_samples.h"
#include "exposure/pixel_shading.h"
#include "exposure/sample_passes.h"
#include "exposure/segmented_geometry.h"
#include "exposure/tile_budget.h"
#include "exposure/tile_pass.h"
#include "exposure/triangle_surface_point.h"
#include "exposure/visible_pieces.h"
#include "methods/motion_path/interval.h"
#include "methods/motion_path/motion_path.h"
#include "methods/motion_path/resolve.h"
#include "methods/motion_path/time_mask.h"
#include "raster/clip.h"
#include "raster/moving_triangle.h"
#include "raster/tile_grid.h"
#include "scene/flat_geometry.h"
#include "util/error.h"

#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace streak {

namespace {

using motion_path::Interval;
using motion_path::MotionPath;

constexpr int kTileSize = 32;
constexpr int kLosslessFragments = 4096, kLosslessIntervals = 2048;

struct Options {
    // The paper's GPU budgets are 150 and 90 (motion-path-gl keeps them); on the CPU the lists
    // grow, so the defaults only bound a pathological sample, and overflow is still counted.
    int maxFragments = kLosslessFragments;
    int maxIntervals = kLosslessIntervals;
    int maskBits = 128;
    bool exactWeights = true;  ///< opaque pieces measured in time, not in mask slices
    // Abutting intervals of one opaque triangle over consecutive segments become one, with a
    // polyline depth, before the sort (with exact weights only: the GL twin's slices keep one
    // interval per segment, as the paper does).
    bool mergeSegments = true;
    bool sortIntervals = true;
    bool earlyCull = true;  ///< skip the samples where nearer opaque triangles hide a path all the shutter (renderRect)
    bool lineSamples = false;  ///< line-samples=1: still tiles take each sample as a line across its pixel (exposure/line_samples.h)
    int lineRows = 0;          ///< line-rows: a line tile's lines per pixel; 0, the pattern's N^2 rows
    int curveSegments = exposure::SegmentedGeometry::kAutoCurveSegments;
    bool closedCull = true;  ///< drop the back faces closed surfaces hide (exposure/closed_surfaces.h)
    exposure::SpanShadingSettings spanShading;  ///< texture-samples, taps-per-texel, texture-filter
    exposure::PixelShadingOptions shading;
};

// A sample a motion path may cover. Paths are conservative and overlap themselves, so a sample
// can hold several fragments of one path; it counts once.
struct Fragment {
    std::uint32_t sample = 0;  ///< within the tile
    std::uint32_t path = 0;    ///< index into the segment paths
    float nearness = 0.0f;     ///< 1 / the path's smallest view depth: which to keep on overflow
    // A still opaque path's depth at the sample where the early cover found it covering the
    // sample all the shutter (its interval is then [0, 1] at this depth, as the build would
    // find it again); NaN where that is not known.
    float stillDepth = std::numeric_limits<float>::quiet_NaN();
};

// Counters of one thread, summed at the end.
struct Counters {
    std::int64_t fragments = 0, fragmentOverflowSamples = 0, intervals = 0, maxIntervals = 0,
                 intervalOverflowSamples = 0, splits = 0, cycles = 0, culledIntervals = 0, pathFaces = 0, mergedIntervals = 0,
                 samplesHidden = 0, snappedAwayFaces = 0;
    std::int64_t lineSampleSurplus = 0;  ///< samples line tiles took beyond the point pattern's (line-rows)
    exposure::PixelShadingCounters shading;
    double rasterSeconds = 0, buildSeconds = 0, sortSeconds = 0, resolveSeconds = 0, shadeSeconds = 0;
};

// A tile works in phases over all its samples (rasterize, build, sort, resolve, shade), each
// phase leaving per-sample runs in one tile-wide array: runs[i]..runs[i + 1] belong to sample i.
struct TileScratch {
    std::vector<Fragment> fragments;
    std::vector<Fragment> bySample;
    std::vector<std::uint32_t> fragmentRuns;
    std::vector<Interval> built;
    std::vector<std::uint32_t> builtRuns;
    std::vector<Interval> sorted;
    std::vector<std::uint32_t> sortedRuns;
    std::vector<float> weights;            ///< per sorted interval: its share of the sample
    std::vector<float> backgroundWeights;  ///< per sample
    std::vector<motion_path::DepthKnot> knots;  ///< the tile's merged intervals' depth corners
    std::vector<exposure::VisibleSpan> visible;  ///< per sample with exact opaque weights: where its intervals show
    std::vector<std::uint32_t> visibleRuns;     ///< per sample; runs[i] == runs[i + 1] with none (or not resolved so)
    std::vector<char> hasVisibleSpans;          ///< per sample: its opaque pieces are its visible spans
    std::vector<Interval> work;            ///< one sample's list while it is sorted
    std::vector<exposure::VisiblePiece> spans;  ///< one sample's visible opaque pieces
    exposure::PixelShading pixelShading;        ///< one pixel's, shaded together
    std::vector<float> events;
    std::vector<float> nearness;           ///< a cut pixel's keys (the memory budget)
    std::vector<std::uint32_t> seenPaths;  ///< an adaptive first pass's paths with intervals in the tile (noteUnseenItems)
    exposure::EarlyCull earlyCull;
    bool isLineTile = false;               ///< this tile's samples are lines across their pixels (renderRect)
    std::vector<glm::dvec2> sampleNdc;     ///< the tile's samples in NDC (exposure::tileSampleNdc of its pattern)
    std::vector<glm::vec3> color;
    std::vector<float> coverage;           ///< per sample
    exposure::PixelPasses passes;          ///< one pixel's, when passes are asked for
    exposure::MovingTriangleCache movingTriangles;  ///< the tile's paths' edge equations
    MotionPath path;
    raster::TriangleSetup setup;
    raster::SnappedAwayTriangle snappedAway;  ///< a path face the grid snaps to no area (raster::SnappedAwayTriangle)
    Counters counters;
    exposure::TileBudgetCounters budget;
};

// What a fragment may cost a tile's lists of the thread's memory share: itself and its copy by
// sample, the interval it may become (built, then sorted), its weight, its visible span and a
// depth knot.
constexpr std::size_t kBytesPerFragment = 2 * sizeof(Fragment) + 2 * sizeof(Interval) + sizeof(float) + sizeof(exposure::VisibleSpan) +
                                          sizeof(motion_path::DepthKnot);

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class MotionPathRenderer final : public Renderer {
public:
    explicit MotionPathRenderer(const Options& options) : m_options(options) {}

    Image render(const Scene& scene, const RenderSettings& settings, RenderContext& context) override {
        Options options = m_options;
        options.shading = m_options.shading.forMode(settings.shading);
        Frame frame(scene, settings, options);
        if (settings.passes.any()) frame.passes.emplace(scene, settings.passes, settings.width, settings.height);
        {
            PhaseTimer timer(context.stats, "generate");
            frame.generate();
        }
        frame.canLineSample = options.lineSamples && exposure::lineSamplingAllowed(scene, frame.segmented);
        context.stats.setCounter("line_samples", frame.canLineSample ? 1 : 0);
        tbb::enumerable_thread_specific<TileScratch> scratch;
        exposure::TileBudget budget(settings.memoryBudgetMB, settings.tileShareBytes);
        std::optional<raster::TileGrid> grid;
        std::optional<exposure::AdaptiveSampling> refinement;
        const raster::SamplePattern fullPattern = frame.pattern;
        Image image = exposure::renderAdaptively(
            fullPattern, settings.adaptiveThreshold, settings.adaptiveFullContrast, settings.region, settings.width, settings.height, context.stats,
            context.progress, refinement,
            [&](const raster::SamplePattern& pattern, const std::optional<raster::PixelBounds>& region, ProgressReporter* progress,
                exposure::FirstPassGeometry* firstPass) {
                frame.usePass(pattern, firstPass);
                grid.emplace(frame.viewport, kTileSize, region);
                return exposure::runTilePass(*grid, std::span<const raster::PixelBounds>(frame.bounds), scene.background, settings.width,
                                             settings.height, context.stats, progress, budget, scratch, [&](int tile, TileScratch& local, Image& pixels) {
                    local.movingTriangles.clear();
                    local.seenPaths.clear();
                    renderPixels(frame, *grid, tile, grid->tileBounds(tile), budget.maxItems(kBytesPerFragment), local, pixels);
                    if (firstPass)
                        exposure::noteUnseenItems(grid->items(tile), std::span<const raster::PixelBounds>(frame.bounds), grid->tileBounds(tile),
                                                  local.seenPaths, *firstPass, [&](std::uint32_t path) { return frame.unseenSurfaceOf(path); });
                });
            },
            [&](const exposure::AdaptiveSampling& marks, exposure::AdaptiveSampling::Level level, const raster::SamplePattern& pattern,
                Image& pixels, ProgressReporter* progress) {
                frame.usePass(pattern, nullptr);
                PhaseTimer timer(context.stats, "tiles");
                const std::size_t shareFragments = budget.maxItems(kBytesPerFragment);
                exposure::runRefinementPass(*grid, marks, level, progress, scratch, [&](int tile, TileScratch& local) {
                    local.movingTriangles.clear();
                    marks.forEachRun(grid->tileBounds(tile), level, [&](const raster::PixelBounds& run) {
                        renderPixels(frame, *grid, tile, run, shareFragments, local, pixels);
                    });
                });
                frame.usePass(fullPattern, nullptr);
            });

        Counters total;
        exposure::TileBudgetCounters budgetTotal;
        for (const TileScratch& s : scratch) {
            budgetTotal.add(s.budget);
            const Counters& c = s.counters;
            total.fragments += c.fragments, total.fragmentOverflowSamples += c.fragmentOverflowSamples;
            total.intervals += c.intervals, total.maxIntervals = std::max(total.maxIntervals, c.maxIntervals);
            total.intervalOverflowSamples += c.intervalOverflowSamples, total.splits += c.splits, total.cycles += c.cycles;
            total.culledIntervals += c.culledIntervals, total.pathFaces += c.pathFaces, total.mergedIntervals += c.mergedIntervals;
            total.snappedAwayFaces += c.snappedAwayFaces;
            total.samplesHidden += c.samplesHidden;
            total.lineSampleSurplus += c.lineSampleSurplus;
            total.shading.add(c.shading);
            total.rasterSeconds += c.rasterSeconds, total.buildSeconds += c.buildSeconds;
            total.sortSeconds += c.sortSeconds, total.resolveSeconds += c.resolveSeconds;
            total.shadeSeconds += c.shadeSeconds;
        }
        // Tile work runs on all threads at once: split the tiles' wall time by thread time.
        const double tileWall = context.stats.time("tiles");
        const double threadTime = total.rasterSeconds + total.buildSeconds + total.sortSeconds + total.resolveSeconds + total.shadeSeconds;
        const double scale = threadTime > 0.0 ? tileWall / threadTime : 0.0;
        context.stats.addTime("rasterize", total.rasterSeconds * scale);
        context.stats.addTime("build intervals", total.buildSeconds * scale);
        context.stats.addTime("sort", total.sortSeconds * scale);
        context.stats.addTime("resolve", total.resolveSeconds * scale);
        context.stats.addTime("shade", total.shadeSeconds * scale);

        RenderStats& stats = context.stats;
        const double numPixels = double(settings.width) * settings.height;
        const double numSamples = (refinement ? refinement->numSamples(numPixels, fullPattern) : numPixels * fullPattern.count()) +
                                  double(total.lineSampleSurplus);
        if (refinement) refinement->record(stats, settings.adaptiveThreshold);
        budget.record(stats, budgetTotal, kBytesPerFragment);
        stats.setCounter("motion_paths", double(frame.paths.size()));
        stats.setCounter("path_faces_rasterized", double(total.pathFaces));
        stats.setCounter("path_faces_snapped_away", double(total.snappedAwayFaces));  // (those that gave a fragment)
        stats.setCounter("backfacing_paths_skipped", double(frame.segmented.numBackFacing()));
        stats.setCounter("fragments", double(total.fragments));
        stats.setCounter("fragments_per_sample_mean", double(total.fragments) / numSamples);
        stats.setCounter("fragment_overflow_samples", double(total.fragmentOverflowSamples));
        stats.setCounter("intervals", double(total.intervals));
        stats.setCounter("segment_intervals_merged", double(total.mergedIntervals));
        stats.setCounter("merge_segments", m_options.mergeSegments && m_options.exactWeights ? 1 : 0);
        stats.setCounter("intervals_per_sample_mean", double(total.intervals) / numSamples);
        stats.setCounter("intervals_per_sample_max", double(total.maxIntervals));
        stats.setCounter("interval_overflow_samples", double(total.intervalOverflowSamples));
        stats.setCounter("interval_splits", double(total.splits));
        stats.setCounter("sort_cycles", double(total.cycles));
        stats.setCounter("backface_intervals_culled", double(total.culledIntervals));
        stats.setCounter("samples_hidden_before_solving", double(total.samplesHidden));
        exposure::recordPixelShadingStats(stats, total.shading, refinement ? refinement->numPixelRenders(numPixels) : numPixels, options.shading);
        stats.setCounter("max_fragments", m_options.maxFragments);
        stats.setCounter("max_intervals", m_options.maxIntervals);
        stats.setCounter("mask_bits", m_options.maskBits);
        stats.setCounter("exact_weights", m_options.exactWeights ? 1 : 0);
        exposure::recordSpanShadingSettings(stats, m_options.spanShading);
        exposure::recordSegments(stats, frame.segmented);
        stats.setCounter("sort_enabled", m_options.sortIntervals ? 1 : 0);

        if (frame.passes) frame.passes->writeTo(image, context.stats);
        return image;
    }

    bool writesPasses() const override { return true; }
    bool refinesAdaptively() const override { return true; }

private:
    // The scene's motion paths, set up for rasterization: one per triangle and linear segment
    // (the shared exposure::SegmentedGeometry), paths indexed like the segments.
    struct Frame {
        Frame(const Scene& scene, const RenderSettings& settings, const Options& options)
            : scene(scene), settings(settings), options(options), viewport{settings.width, settings.height},
              pattern(raster::samplePatternFor(settings.aa, settings.isGridPattern)),
              segmented(scene, raster::Viewport{settings.width, settings.height}, options.curveSegments,
                        exposure::SegmentedGeometry::kMergeTolerancePixels, options.closedCull),
              geometry(segmented.flat()), paths(segmented.segments()), spanShading(options.spanShading) {}

        // Paths are binned by their screen boxes and built into faces tile by tile, so memory
        // stays one box per path however many triangles the scene has.
        void generate() {
            bounds = segmented.screenBounds(viewport);
            occluderDepths = exposure::EarlyCull::occluderDepths(segmented, viewport);
        }

        // The exact time spans in which the sample lies inside the path's triangle, appended to
        // `events` as start/end shutter times.
        void exactSpans(const exposure::TriangleSegment& p, const raster::MovingTriangle& moving, const glm::dvec2& ndc,
                        std::vector<float>& events) const {
            std::array<double, 8> bounds;
            // Depth on the triangle is a convex combination of its corners' depths, so only a
            // path reaching nearer than the near plane needs the depth check.
            const bool checkNearPlane = !(p.isInFront() && p.nearness <= 1.0f / scene.camera.zNear);
            const int n = moving.insideSpans(ndc, scene.camera.zNear, checkNearPlane, bounds);
            // Exact in double: u = 0 and 1 give t0 and t1 to the bit, so pieces abut across segments.
            for (int i = 0; i < n; ++i) events.push_back(float(p.t0 + bounds[i] * (double(p.t1) - double(p.t0))));
        }

        // A span's colour at a site (its point and footprint), in the row's shutter window.
        ShadedColor shade(std::uint32_t triangle, float t0, float t1, const exposure::ShadingSite& site, const ShutterWindow& window,
                          exposure::MovingTriangleCache& cache) const {
            exposure::SpanShadingSettings rowShading = spanShading;
            rowShading.window = window;
            return exposure::shadeTriangleSpan(segmented, viewport, settings.shading, rowShading, triangle, t0, t1, site, cache);
        }

        const Scene& scene;
        const RenderSettings& settings;
        const Options& options;
        raster::Viewport viewport;
        raster::SamplePattern pattern;
        exposure::FirstPassGeometry* firstPass = nullptr;  ///< adaptive sampling's first pass: what its samples show and miss
        bool canLineSample = false;  ///< line-samples=1 where the frame allows it (render)
        raster::SamplePattern linePattern;  ///< a line tile's rows (line-rows; else the pass's pattern)

        // The pass's sample pattern (exposure::renderAdaptively), with the line tiles' rows that
        // follow from it, and what its first pass tells (null in any other).
        void usePass(const raster::SamplePattern& passPattern, exposure::FirstPassGeometry* geometry) {
            pattern = passPattern, firstPass = geometry;
            linePattern = exposure::linePatternFor(pattern, options.lineRows);
        }

        // A path's surface and nearest depth, for the first pass's unseen paths.
        std::pair<std::uint64_t, float> unseenSurfaceOf(std::uint32_t path) const {
            return exposure::unseenSurface(geometry.triangles()[paths[path].triangle], paths[path].nearness);
        }
        exposure::SegmentedGeometry segmented;
        const FlatGeometry& geometry;
        std::span<const exposure::TriangleSegment> paths;  ///< one per segment
        exposure::SpanShadingSettings spanShading;
        LargeBuffer<raster::PixelBounds> bounds;          ///< per path: the pixels it may cover
        LargeBuffer<float> occluderDepths;                ///< per path: EarlyCull::occluderDepths
        mutable std::optional<exposure::PassFrame> passes;  ///< when settings.passes asks for any (tiles write their own pixels)
    };

    // Adds to the pixel's passes what shows in sample i (its sorted intervals begin to end):
    // with exact opaque weights, each span where an interval is the nearest; else each interval
    // with a share. Each at its depth in the middle, and the nearest and farthest its polyline
    // gets in it (its ends and the corners between).
    static void addShownSurfaces(const Frame& frame, TileScratch& scratch, std::uint32_t begin, std::uint32_t end, std::size_t i,
                                 bool hasVisibleSpans) {
        auto add = [&](const Interval& interval, float share, float t0, float t1) {
            const std::uint32_t triangle = frame.paths[interval.source].triangle;
            const FlatTriangle& t = frame.geometry.triangles()[triangle];
            const float d0 = motion_path::depthAt(interval, scratch.knots, t0), d1 = motion_path::depthAt(interval, scratch.knots, t1);
            float nearest = std::min(d0, d1), farthest = std::max(d0, d1);
            for (std::uint32_t k = interval.firstKnot; k < interval.firstKnot + interval.numKnots; ++k)
                if (scratch.knots[k].t > t0 && scratch.knots[k].t < t1)
                    nearest = std::min(nearest, scratch.knots[k].depth), farthest = std::max(farthest, scratch.knots[k].depth);
            scratch.passes.add({triangle, t.mesh, t.material, share, motion_path::depthAt(interval, scratch.knots, 0.5f * (t0 + t1)), nearest, farthest});
        };
        if (hasVisibleSpans) {
            for (std::uint32_t v = scratch.visibleRuns[i]; v < scratch.visibleRuns[i + 1]; ++v) {
                const exposure::VisibleSpan& shown = scratch.visible[v];
                add(scratch.sorted[shown.interval], shown.weight, shown.t0, shown.t1);
            }
            return;
        }
        for (std::uint32_t k = begin; k < end; ++k)
            if (scratch.weights[k] > 0.0f) add(scratch.sorted[k], scratch.weights[k], scratch.sorted[k].t0, scratch.sorted[k].t1);
    }

    // The interval of a path's span [t0, t1] at the sample at ndc (its times and the depths at
    // its ends); false where the span is not seen (an end behind the eye, or the triangle facing
    // away and single-sided).
    static bool intervalOf(const exposure::TriangleSegment& path, const raster::MovingTriangle& moving, const FlatTriangle& tri,
                           const glm::dvec2& ndc, float t0, float t1, Interval& interval) {
        const double u0 = path.localTime(t0), u1 = path.localTime(t1);
        // (A still triangle is the same at both ends.)
        const raster::HomogeneousSample s0 = moving.sample(u0, ndc), s1 = moving.isStill() ? s0 : moving.sample(u1, ndc);
        // The triangle cannot turn over inside a span (its edges would have to pass the sample),
        // so its facing at mid-span is its facing throughout.
        const bool isFrontFacing = moving.isFrontFacing(0.5 * (u0 + u1));
        if (!s0.isValid || !s1.isValid || (!tri.isDoubleSided && !isFrontFacing)) return false;
        interval.t0 = t0, interval.t1 = t1;
        interval.depth0 = float(s0.viewDepth), interval.depth1 = float(s1.viewDepth);
        return true;
    }

    // Builds the intervals of one sample from its fragments (sorted by path), appending them to
    // `out`. Depth and facing are all the resolve needs; opaque intervals are shaded later, and
    // only if visible. Translucent ones are shaded now, since their opacity (texture alpha)
    // decides what shows behind them. Spans the sample's row does not expose are dropped.
    void buildIntervals(const Frame& frame, std::span<const Fragment> fragments, const glm::dvec2& ndc, const ShutterWindow& window,
                        TileScratch& scratch, std::vector<Interval>& out) const {
        for (std::size_t i = 0; i < fragments.size(); ++i) {
            if (i > 0 && fragments[i].path == fragments[i - 1].path) continue;
            if (!std::isnan(fragments[i].stillDepth)) {
                // What coverByStillPath found: the loop below would find [0, 1] at this depth
                // again (an opaque path, in every row's window).
                Interval interval;
                interval.t0 = 0.0f, interval.t1 = 1.0f, interval.depth0 = interval.depth1 = fragments[i].stillDepth;
                interval.source = fragments[i].path;
                out.push_back(interval);
                continue;
            }
            const exposure::TriangleSegment& path = frame.paths[fragments[i].path];
            const FlatTriangle& tri = frame.geometry.triangles()[path.triangle];
            const Material& material = frame.scene.materials[tri.material];
            const raster::MovingTriangle& moving = scratch.movingTriangles.get(frame.segmented, fragments[i].path);
            if (scratch.isLineTile) {
                buildLineInterval(frame, fragments[i].path, moving, ndc, scratch, out);
                continue;
            }
            scratch.events.clear();
            frame.exactSpans(path, moving, ndc, scratch.events);
            for (std::size_t e = 0; e + 1 < scratch.events.size(); e += 2) {
                const float t0 = scratch.events[e], t1 = scratch.events[e + 1];
                if (!window.isIdentity() && !(window.measure(t0, t1) > 0.0f)) continue;
                Interval interval;
                if (!intervalOf(path, moving, tri, ndc, t0, t1, interval)) {
                    ++scratch.counters.culledIntervals;
                    continue;
                }
                interval.source = fragments[i].path;
                if (material.isTranslucent()) {
                    const ShadedColor shaded = frame.shade(path.triangle, t0, t1, exposure::sampleSite(ndc, frame.settings.aa), window, scratch.movingTriangles);
                    interval.color = shaded.color, interval.alpha = shaded.alpha;
                }
                out.push_back(interval);
            }
        }
    }

    // A still path's interval at a line sample (a line tile's, exposure/line_samples.h): the
    // stretch of the line through ndc that it covers, its times the ends' shares of the pixel.
    static void buildLineInterval(const Frame& frame, std::uint32_t index, const raster::MovingTriangle& still, const glm::dvec2& ndc,
                                  TileScratch& scratch, std::vector<Interval>& out) {
        const exposure::TriangleSegment& path = frame.paths[index];
        const FlatTriangle& tri = frame.geometry.triangles()[path.triangle];
        exposure::LineStretch stretch;
        if (path.orientation == 0 || !exposure::lineStretchAt(still, path.orientation, ndc, frame.viewport.width, stretch)) return;
        if (!tri.isDoubleSided && !still.isFrontFacing(0.5)) {
            ++scratch.counters.culledIntervals;
            return;
        }
        Interval interval;
        interval.t0 = stretch.u0, interval.t1 = stretch.u1;
        interval.depth0 = stretch.depth0, interval.depth1 = stretch.depth1;
        interval.source = index;
        if (frame.scene.materials[tri.material].isTranslucent()) {
            const exposure::ShadingSite site = exposure::lineSite(exposure::sampleSite(ndc, frame.settings.aa), stretch.u0, stretch.u1, frame.viewport.width);
            const ShadedColor shaded = frame.shade(path.triangle, 0.0f, 1.0f, site, ShutterWindow(), scratch.movingTriangles);
            interval.color = shaded.color, interval.alpha = shaded.alpha;
        }
        out.push_back(interval);
    }

    // The shutter window of sample i's row.
    static ShutterWindow sampleWindow(const Frame& frame, const raster::SamplePattern& pattern, const raster::PixelBounds& rect, std::size_t i) {
        const int tileWidth = rect.x1 - rect.x0 + 1;
        return frame.scene.shutter.rowWindow(rect.y0 + int(i / std::size_t(pattern.count())) / tileWidth, frame.viewport.height);
    }

    // Keeps each sample's paths once, in path order (a path's faces overlap, so a sample can
    // hold several of its fragments); returns how many remain at the front of `fragments`.
    static std::size_t uniquePaths(std::span<Fragment> fragments) {
        std::sort(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) { return a.path < b.path; });
        return std::size_t(std::unique(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) { return a.path == b.path; }) -
                           fragments.begin());
    }

    // The pixels `bounds` of a tile (the tile, or a run of its pixels that adaptive sampling
    // refines), in halves while its fragments would pass shareFragments
    // (exposure::renderWithinShare). The tile's cache of edge equations is the caller's to empty.
    void renderPixels(const Frame& frame, const raster::TileGrid& grid, int tile, const raster::PixelBounds& bounds, std::size_t shareFragments,
                      TileScratch& scratch, Image& image) const {
        exposure::renderWithinShare(bounds, scratch.budget, [&](const raster::PixelBounds& rect, bool isPixel) {
            return renderRect(frame, grid.items(tile), rect, isPixel, shareFragments, scratch, image);
        });
    }

    // After each path rasterized into rect (numSamples in it; `done` of its `total` paths): false
    // once the fragments pass shareFragments (exposure::renderWithinShare cuts the rectangle). A
    // single pixel instead keeps each sample's nearest paths, once each, down to half its share
    // (so the cut is not repeated at every path), and goes on.
    static bool keepFragmentsWithinShare(TileScratch& scratch, std::size_t shareFragments, bool isPixel, std::size_t numSamples,
                                         std::size_t done, std::size_t total) {
        scratch.budget.see(scratch.fragments.size());
        if (scratch.fragments.size() <= shareFragments) return true;
        if (!isPixel) {
            scratch.budget.refuse(scratch.fragments.size(), shareFragments, done, total);
            return false;
        }
        scratch.budget.dropped += std::int64_t(exposure::keepNearestPerSample(
            scratch.fragments, numSamples, shareFragments / (2 * numSamples), scratch.fragmentRuns, scratch.bySample, scratch.nearness,
            uniquePaths, [](const Fragment& f) { return f.nearness; }));
        return true;
    }

    // Marks `sample` of rect (EarlyCull) where the still path covers it all the shutter: its
    // exact spans there are [0, 1] and seen. The fragment just added for it keeps the depth, so
    // the build makes that interval without finding it again.
    static void coverByStillPath(const Frame& frame, const exposure::TriangleSegment& path, const raster::MovingTriangle& moving,
                                 const FlatTriangle& tri, std::uint32_t sample, TileScratch& scratch) {
        const glm::dvec2 ndc = scratch.sampleNdc[sample];
        scratch.events.clear();
        frame.exactSpans(path, moving, ndc, scratch.events);
        Interval interval;
        if (scratch.events.size() == 2 && scratch.events[0] == 0.0f && scratch.events[1] == 1.0f &&
            intervalOf(path, moving, tri, ndc, 0.0f, 1.0f, interval)) {
            scratch.earlyCull.cover(sample, std::max(interval.depth0, interval.depth1));
            scratch.fragments.back().stillDepth = interval.depth0;  // (depth1 is the same: the path is still)
        }
    }

    // The pixels of rect, within a tile whose paths are `items`; false, with the image left
    // alone, once its fragments pass shareFragments (a single pixel cuts them instead).
    bool renderRect(const Frame& frame, std::span<const std::uint32_t> items, const raster::PixelBounds& rect, bool isPixel,
                    std::size_t shareFragments, TileScratch& scratch, Image& image) const {
        using Clock = std::chrono::steady_clock;
        const int tileWidth = rect.x1 - rect.x0 + 1, tileHeight = rect.y1 - rect.y0 + 1;
        // Line samples (exposure/line_samples.h) where every path of the tile is still; not in
        // adaptive sampling's first pass, one point per pixel. A line tile takes its own rows.
        scratch.isLineTile = frame.canLineSample && !frame.firstPass && exposure::isLineTile(items, frame.paths, frame.scene.camera.zNear);
        const raster::SamplePattern& pattern = scratch.isLineTile ? frame.linePattern : frame.pattern;
        // (A table per tile: a sample's NDC takes four divisions, and each sample asks for it at
        // its build and its shading, and a still path's at its early cover too.)
        exposure::tileSampleNdc(rect, pattern, frame.viewport.width, frame.viewport.height, scratch.sampleNdc);
        const int spp = pattern.count();
        const std::size_t numSamples = std::size_t(tileWidth) * tileHeight * spp;
        const Options& options = frame.options;
        Counters& counters = scratch.counters;

        // Rasterize: every face of every path reaching the tile adds a fragment to each sample
        // it covers.
        auto start = Clock::now();
        scratch.fragments.clear();
        // The early cull (exposure::EarlyCull): paths go nearest first, a still opaque path that
        // covers a sample all the shutter marks it, and a later path's fragment there is dropped
        // where the mark lies nearer than the path's nearest corner (as are the paths whose every
        // pixel is so covered): the resolve would give its intervals no share. The build puts
        // each sample's fragments in path order again (uniquePaths), so the order changes
        // nothing after. It is off in adaptive sampling's first pass (its unseen-path rule counts
        // intervals), without exact opaque weights or the sort, where no path spans the shutter,
        // and in a tile where no path may hide another (EarlyCull::mayHideAny: a dense mesh's
        // tiny triangles under a camera move), which then keeps its order.
        const bool isCullingEarly = options.earlyCull && options.exactWeights && options.sortIntervals && !frame.firstPass &&
                                    frame.segmented.hasWholeShutterSegments() && exposure::EarlyCull::mayHideAny(items, frame.paths, frame.occluderDepths);
        exposure::EarlyCull& earlyCull = scratch.earlyCull;
        if (isCullingEarly) items = earlyCull.begin(numSamples, spp, tileWidth, items, frame.paths);
        for (std::size_t k = 0; k < items.size(); ++k) {
            if (!keepFragmentsWithinShare(scratch, shareFragments, isPixel, numSamples, k, items.size())) {
                counters.rasterSeconds += secondsSince(start);
                return false;
            }
            const std::uint32_t index = items[k];
            // Only the samples within the path's pixel bounds: a conservative face reaches past
            // them, but a sample beyond gets no interval from it (analytic visits the same box),
            // and its fragments would only count against the caps. A rectangle the bounds miss
            // (a cut tile's half, a run of pixels adaptive sampling refines) builds no faces.
            const raster::PixelBounds& box = frame.bounds[index];
            const raster::PixelBounds scan{std::max(box.x0, rect.x0), std::max(box.y0, rect.y0), std::min(box.x1, rect.x1),
                                           std::min(box.y1, rect.y1)};
            if (scan.empty()) continue;
            const exposure::TriangleSegment& segment = frame.paths[index];
            const float nearest = isCullingEarly ? exposure::EarlyCull::nearestOf(segment.nearness) : -std::numeric_limits<float>::infinity();
            if (isCullingEarly && earlyCull.isRegionHidden(scan, rect.x0, rect.y0, nearest)) {
                counters.samplesHidden += std::int64_t(scan.x1 - scan.x0 + 1) * (scan.y1 - scan.y0 + 1) * spp;
                continue;
            }
            // A still opaque path marks the samples it covers all the shutter, as the build
            // would find its interval there.
            const FlatTriangle& tri = frame.geometry.triangles()[segment.triangle];
            if (scratch.isLineTile) {
                // A still path's fragments are the samples whose lines it covers (no faces;
                // exposure/line_samples.h); seen from behind and single-sided, none.
                std::int64_t missed = 0;
                exposure::forEachTileLineStretch(scratch.movingTriangles.get(frame.segmented, index), segment, tri.isDoubleSided, rect, scan,
                                                 pattern, frame.viewport, isCullingEarly ? &earlyCull : nullptr, nearest,
                                                 isCullingEarly && !frame.scene.materials[tri.material].isTranslucent(), counters.samplesHidden,
                                                 missed, [&](std::uint32_t sample, const exposure::LineStretch&) {
                    scratch.fragments.push_back({sample, index, segment.nearness});
                });
                continue;
            }
            const raster::MovingTriangle* still = nullptr;
            if (isCullingEarly && !frame.scene.materials[tri.material].isTranslucent()) {
                const raster::MovingTriangle& moving = scratch.movingTriangles.get(frame.segmented, index);
                if (moving.isStill()) still = &moving;
            }
            motion_path::buildMotionPath(segment.clip0, segment.clip1, scratch.path);
            counters.pathFaces += scratch.path.count;
            for (int f = 0; f < scratch.path.count; ++f) {
                // Faces come projected, at w = 1: the camera's near plane (which may lie beyond
                // w = 1 in a large scene) must not cut them.
                raster::setupTriangle(scratch.path.faces[f].clip, index, motion_path::kProjectedFaceNear, frame.viewport,
                                      raster::CullMode::None, scratch.setup);
                auto addFragment = [&](int px, int py, int s) {
                    const std::uint32_t sample = std::uint32_t((std::size_t(py - rect.y0) * tileWidth + (px - rect.x0)) * spp + s);
                    if (isCullingEarly && earlyCull.isHidden(sample, nearest)) {
                        ++counters.samplesHidden;
                        return;
                    }
                    scratch.fragments.push_back({sample, index, segment.nearness});
                    if (still) coverByStillPath(frame, segment, *still, tri, sample, scratch);
                };
                for (int k = 0; k < scratch.setup.count; ++k) {
                    raster::ScreenTriangle& face = scratch.setup.triangles[k].screen;
                    raster::makeConservative(face, frame.viewport);
                    raster::scanTriangle(face, scan, pattern, [&](int px, int py, int s, const raster::EdgeValues&) { addFragment(px, py, s); });
                }
                // A face thinner than the grid is not set up: its own cover then (a sub-pixel sliver
                // on a dense sphere's silhouette showed the back face through the hole).
                if (scratch.setup.count == 0 && scratch.snappedAway.setup(scratch.path.faces[f].clip, frame.viewport)) {
                    const raster::PixelBounds& b = scratch.snappedAway.bounds();
                    bool isSeen = false;
                    for (int py = std::max(b.y0, scan.y0); py <= std::min(b.y1, scan.y1); ++py)
                        for (int px = std::max(b.x0, scan.x0); px <= std::min(b.x1, scan.x1); ++px)
                            for (int s = 0; s < spp; ++s)
                                if (scratch.snappedAway.covers(pattern.rasterOf(px, py, s))) addFragment(px, py, s), isSeen = true;
                    counters.snappedAwayFaces += isSeen;
                }
            }
        }
        if (!keepFragmentsWithinShare(scratch, shareFragments, isPixel, numSamples, items.size(), items.size())) {
            counters.rasterSeconds += secondsSince(start);
            return false;
        }
        counters.fragments += std::int64_t(scratch.fragments.size());
        raster::groupBySample(std::span<const Fragment>(scratch.fragments), numSamples, scratch.fragmentRuns, scratch.bySample);
        const std::vector<std::uint32_t>& runs = scratch.fragmentRuns;
        auto now = Clock::now();
        counters.rasterSeconds += std::chrono::duration<double>(now - start).count();

        // Build: each sample's paths, once each, into exact-time intervals.
        start = now;
        scratch.built.clear();
        scratch.knots.clear();
        scratch.builtRuns.assign(numSamples + 1, 0);
        const bool isMerging = options.mergeSegments && options.exactWeights;
        const int segmentsPerTriangle = frame.segmented.numSegments();
        auto isOpaqueSurface = [&](std::uint32_t path) {
            return !frame.scene.materials[frame.geometry.triangles()[frame.paths[path].triangle].material].isTranslucent();
        };
        // Paths are segments, triangle-major: one triangle's segments are consecutive.
        auto sameSurface = [&](std::uint32_t a, std::uint32_t b) {
            return a / std::uint32_t(segmentsPerTriangle) == b / std::uint32_t(segmentsPerTriangle) && isOpaqueSurface(a);
        };
        // The row's shutter window, found once a row (it is the same for the row's samples).
        const std::size_t samplesPerRow = std::size_t(tileWidth) * std::size_t(spp);
        ShutterWindow rowWindow;
        for (std::size_t i = 0, nextRow = 0; i < numSamples; ++i) {
            if (i == nextRow) rowWindow = sampleWindow(frame, pattern, rect, i), nextRow += samplesPerRow;
            std::span<Fragment> fragments(scratch.bySample.data() + runs[i], runs[i + 1] - runs[i]);
            if (!fragments.empty()) {
                fragments = fragments.first(uniquePaths(fragments));
                if (int(fragments.size()) > options.maxFragments) {
                    // Over budget: keep the nearest paths.
                    ++counters.fragmentOverflowSamples;
                    std::nth_element(fragments.begin(), fragments.begin() + options.maxFragments, fragments.end(),
                                     [](const Fragment& a, const Fragment& b) { return a.nearness > b.nearness; });
                    fragments = fragments.first(std::size_t(options.maxFragments));
                    std::sort(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) { return a.path < b.path; });
                }
                const std::size_t first = scratch.built.size();
                buildIntervals(frame, fragments, scratch.sampleNdc[i], rowWindow, scratch, scratch.built);
                if (isMerging) counters.mergedIntervals += motion_path::mergeAbuttingIntervals(scratch.built, first, scratch.knots, sameSurface);
                if (scratch.built.size() - first > std::size_t(options.maxIntervals)) {
                    // Over budget: keep the nearest intervals.
                    ++counters.intervalOverflowSamples;
                    const auto begin = scratch.built.begin() + std::ptrdiff_t(first);
                    std::nth_element(begin, begin + options.maxIntervals, scratch.built.end(),
                                     [](const Interval& a, const Interval& b) { return a.minDepth() < b.minDepth(); });
                    scratch.built.resize(first + std::size_t(options.maxIntervals));
                }
                const std::int64_t count = std::int64_t(scratch.built.size() - first);
                counters.intervals += count;
                counters.maxIntervals = std::max(counters.maxIntervals, count);
            }
            scratch.builtRuns[i + 1] = std::uint32_t(scratch.built.size());
        }
        now = Clock::now();
        counters.buildSeconds += std::chrono::duration<double>(now - start).count();
        if (frame.firstPass)
            for (const Interval& interval : scratch.built) scratch.seenPaths.push_back(interval.source);

        // Sort: front to back in depth-time; splits may lengthen a list.
        start = now;
        scratch.sorted.clear();
        scratch.sortedRuns.assign(numSamples + 1, 0);
        for (std::size_t i = 0; i < numSamples; ++i) {
            const std::uint32_t begin = scratch.builtRuns[i], end = scratch.builtRuns[i + 1];
            if (end - begin > 1) {
                std::vector<Interval>& work = scratch.work;
                work.assign(scratch.built.begin() + begin, scratch.built.begin() + end);
                if (options.sortIntervals) {
                    motion_path::SortCounters sortCounters;
                    motion_path::sortDepthTime(work, options.maxIntervals, sortCounters, scratch.knots);
                    counters.splits += sortCounters.splits;
                    counters.cycles += sortCounters.cycles;
                    counters.intervalOverflowSamples += sortCounters.overflow > 0;
                } else {
                    std::sort(work.begin(), work.end(), [](const Interval& a, const Interval& b) { return a.minDepth() < b.minDepth(); });
                }
                scratch.sorted.insert(scratch.sorted.end(), work.begin(), work.end());
            } else if (end > begin) {
                scratch.sorted.push_back(scratch.built[begin]);
            }
            scratch.sortedRuns[i + 1] = std::uint32_t(scratch.sorted.size());
        }
        now = Clock::now();
        counters.sortSeconds += std::chrono::duration<double>(now - start).count();

        // Resolve: each interval's visible share of its sample.
        start = now;
        scratch.weights.resize(scratch.sorted.size());
        scratch.backgroundWeights.assign(numSamples, 1.0f);
        scratch.visible.clear();
        scratch.visibleRuns.assign(numSamples + 1, 0);
        scratch.hasVisibleSpans.assign(numSamples, 0);
        for (std::size_t i = 0, nextRow = 0; i < numSamples; ++i) {
            if (i == nextRow) rowWindow = sampleWindow(frame, pattern, rect, i), nextRow += samplesPerRow;
            const std::uint32_t begin = scratch.sortedRuns[i], end = scratch.sortedRuns[i + 1];
            scratch.visibleRuns[i + 1] = scratch.visibleRuns[i];
            if (end == begin) continue;
            const std::span<const Interval> list = std::span<const Interval>(scratch.sorted).subspan(begin, end - begin);
            if (options.exactWeights && !motion_path::hasTranslucentInterval(list)) {
                // Exact opaque weights also say where each interval shows: a partly hidden one
                // is shaded over the time it shows.
                const std::size_t firstSpan = scratch.visible.size();
                scratch.backgroundWeights[i] = motion_path::resolveOpaqueSpans(list, std::span(scratch.weights).subspan(begin, end - begin),
                                                                               rowWindow, scratch.visible);
                for (std::size_t v = firstSpan; v < scratch.visible.size(); ++v) scratch.visible[v].interval += begin;
                scratch.visibleRuns[i + 1] = std::uint32_t(scratch.visible.size());
                scratch.hasVisibleSpans[i] = 1;
                continue;
            }
            scratch.backgroundWeights[i] =
                motion_path::resolveWeights(std::span(scratch.sorted).subspan(begin, end - begin), options.maskBits,
                                            std::span(scratch.weights).subspan(begin, end - begin),
                                            options.exactWeights ? motion_path::OpaqueWeights::Exact : motion_path::OpaqueWeights::Slices,
                                            rowWindow);
        }
        now = Clock::now();
        counters.resolveSeconds += std::chrono::duration<double>(now - start).count();

        // Shade: only what shows, pixel by pixel (exposure::PixelShading). Translucent intervals
        // were shaded when built; with exact opaque weights the pieces are the visible spans
        // from the resolve, else whole intervals; abutting wholly visible pieces of a triangle
        // are one span (exposure::mergeAbuttingPieces).
        start = now;
        scratch.color.resize(numSamples);
        for (std::size_t first = 0; first < numSamples; first += std::size_t(spp)) {
            const ShutterWindow window = sampleWindow(frame, pattern, rect, first);
            // Every line spans its pixel, so cells across x divide nothing: a line tile's samples
            // share their shadings over the pixel.
            scratch.pixelShading.begin(pattern, glm::dvec2(2.0 / frame.viewport.width, 2.0 / frame.viewport.height),
                                       scratch.isLineTile ? 1 : options.shading.cellsFor(pattern.samplesPerAxis()));
            if (frame.passes) scratch.passes.begin(*frame.passes);
            for (int s = 0; s < spp; ++s) {
                const std::size_t i = first + std::size_t(s);
                glm::vec3 sum = frame.scene.background * scratch.backgroundWeights[i];
                const std::uint32_t begin = scratch.sortedRuns[i], end = scratch.sortedRuns[i + 1];
                std::vector<exposure::VisiblePiece>& spans = scratch.spans;
                spans.clear();
                const bool hasVisibleSpans = scratch.hasVisibleSpans[i] != 0;
                for (std::uint32_t k = begin; k < end; ++k) {
                    if (scratch.weights[k] <= 0.0f) continue;
                    const Interval& interval = scratch.sorted[k];
                    const std::uint32_t triangle = frame.paths[interval.source].triangle;
                    if (frame.scene.materials[frame.geometry.triangles()[triangle].material].isTranslucent()) {
                        sum += interval.color * scratch.weights[k];
                        if (frame.passes) scratch.passes.addColor(triangle, interval.color * scratch.weights[k]);
                    } else if (!hasVisibleSpans) {
                        bool isWhole;
                        if (options.exactWeights) {
                            isWhole = scratch.weights[k] >= window.measure(interval.t0, interval.t1) * (1.0f - 1e-5f);
                        } else {
                            const int bits = motion_path::TimeMask::exposed(interval.t0, interval.t1, window, options.maskBits).count();
                            isWhole = scratch.weights[k] * float(options.maskBits) >= float(bits) - 0.5f;
                        }
                        spans.push_back({triangle, interval.t0, interval.t1, scratch.weights[k], isWhole});
                    }
                }
                if (hasVisibleSpans)
                    for (std::uint32_t v = scratch.visibleRuns[i]; v < scratch.visibleRuns[i + 1]; ++v) {
                        const exposure::VisibleSpan& shown = scratch.visible[v];
                        const std::uint32_t triangle = frame.paths[scratch.sorted[shown.interval].source].triangle;
                        if (!frame.scene.materials[frame.geometry.triangles()[triangle].material].isTranslucent())
                            spans.push_back({triangle, shown.t0, shown.t1, shown.weight, true});
                    }
                scratch.color[i] = sum;
                if (frame.passes) addShownSurfaces(frame, scratch, begin, end, i, hasVisibleSpans);
                if (spans.empty()) continue;
                if (frame.firstPass) {
                    const int pixel = int(first / std::size_t(spp)), px = rect.x0 + pixel % tileWidth, py = rect.y0 + pixel / tileWidth;
                    // How deep it saw: opaque all the shutter, nothing beyond its intervals.
                    bool isOpaque = scratch.backgroundWeights[i] <= 1e-5f;
                    float farthest = 0.0f;
                    for (std::uint32_t k = begin; k < end && isOpaque; ++k) {
                        if (scratch.weights[k] <= 0.0f) continue;
                        const Interval& interval = scratch.sorted[k];
                        isOpaque = !frame.scene.materials[frame.geometry.triangles()[frame.paths[interval.source].triangle].material].isTranslucent();
                        farthest = std::max(farthest, interval.maxDepth());
                    }
                    exposure::tellFirstPass(*frame.firstPass, px, py, spans, frame.geometry.triangles(), isOpaque, farthest);
                }
                exposure::mergeAbuttingPieces(spans);
                scratch.pixelShading.add(s, scratch.sampleNdc[i], std::span<const exposure::VisiblePiece>(spans), [&](std::uint32_t triangle) {
                    const FlatTriangle& t = frame.geometry.triangles()[triangle];
                    return exposure::sharingOf(frame.scene.materials[t.material], t, options.shading.isUnlit,
                                               !scratch.isLineTile && frame.segmented.isStillAllShutter(triangle));
                });
            }
            scratch.pixelShading.finish(
                options.shading,
                [&](std::uint32_t triangle, float t0, float t1, const exposure::ShadingSite& site) {
                    if (scratch.isLineTile)  // a still triangle, at the middle of the line's stretch
                        return frame.shade(triangle, 0.0f, 1.0f, exposure::lineSite(site, t0, t1, frame.viewport.width), window, scratch.movingTriangles);
                    return frame.shade(triangle, t0, t1, site, window, scratch.movingTriangles);
                },
                std::span<glm::vec3>(scratch.color).subspan(first, std::size_t(spp)), counters.shading,
                [&](std::uint32_t triangle, const glm::vec3& added) {
                    if (frame.passes) scratch.passes.addColor(triangle, added);
                });
            if (frame.passes) {
                const int pixel = int(first / std::size_t(spp)), tileWidth = rect.x1 - rect.x0 + 1;
                scratch.passes.finish(*frame.passes, rect.x0 + pixel % tileWidth, rect.y0 + pixel / tileWidth, 1.0f / float(spp));
            }
        }
        counters.shadeSeconds += secondsSince(start);

        // Each tile pixel is the mean of its samples; coverage is what the background does not take.
        scratch.coverage.resize(numSamples);
        for (std::size_t i = 0; i < numSamples; ++i) scratch.coverage[i] = 1.0f - scratch.backgroundWeights[i];
        exposure::setTilePixels(rect, spp, scratch.color, scratch.coverage, image);
        if (scratch.isLineTile) counters.lineSampleSurplus += std::int64_t(numSamples / std::size_t(spp)) * (spp - frame.pattern.count());
        return true;
    }

    Options m_options;
};

}  // namespace

std::unique_ptr<Renderer> createMotionPathRenderer(OptionMap& options) {
    Options o;
    o.maxFragments = options.getInt("max-fragments", kLosslessFragments, 2, 1 << 16);
    o.maxIntervals = options.getInt("max-intervals", kLosslessIntervals, 1, 1 << 16);
    o.maskBits = options.getInt("mask-bits", 128, 32, 256);
    o.exactWeights = options.getInt("exact-weights", 1, 0, 1) != 0;
    o.mergeSegments = options.getInt("merge-segments", 1, 0, 1) != 0;
    if (o.maskBits != 32 && o.maskBits != 64 && o.maskBits != 128 && o.maskBits != 256)
        throw Error("method 'motion-path': mask-bits must be 32, 64, 128 or 256, got " + std::to_string(o.maskBits));
    o.sortIntervals = options.getInt("sort", 1, 0, 1) != 0;
    o.earlyCull = options.getInt("early-cull", 1, 0, 1) != 0;
    o.closedCull = options.getInt("closed-cull", 1, 0, 1) != 0;
    o.lineSamples = options.getInt("line-samples", 0, 0, 1) != 0;
    o.lineRows = options.getInt("line-rows", 0, 0, exposure::kMaxLineRows);
    if (o.lineRows > 0 && !o.lineSamples) throw Error("method 'motion-path': line-rows sets the rows of line samples, and needs line-samples=1");
    o.curveSegments = options.getInt("curve-segments", o.curveSegments, 0, exposure::SegmentedGeometry::kMaxCurveSegments);
    o.spanShading = exposure::spanShadingSettings(options, "motion-path");
    o.shading = exposure::pixelShadingOptions(options, "motion-path");
    return std::make_unique<MotionPathRenderer>(o);
}

}  // namespace streak
