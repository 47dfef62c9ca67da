#pragma once

#include "exposure/exposure_interval.h"
#include "exposure/occlusion_cull.h"
#include "exposure/pixel_shading.h"
#include "exposure/visible_pieces.h"
#include "scene/shading.h"
#include "util/stats.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace streak::exposure {

// What resolving samples from exposure intervals did, summed over samples (for --stats).
struct SampleResolveCounters {
    std::int64_t intervals = 0, maxIntervals = 0, compressedSamples = 0, merges = 0, maxResolved = 0, hiddenCulled = 0;
    double misorderedTime = 0.0, coveredPairTime = 0.0;
    double resolveSeconds = 0.0, shadeSeconds = 0.0;
    PixelShadingCounters shading;
    void add(const SampleResolveCounters& o) {
        intervals += o.intervals, maxIntervals = std::max(maxIntervals, o.maxIntervals), compressedSamples += o.compressedSamples;
        merges += o.merges, maxResolved = std::max(maxResolved, o.maxResolved), hiddenCulled += o.hiddenCulled;
        misorderedTime += o.misorderedTime, coveredPairTime += o.coveredPairTime;
        resolveSeconds += o.resolveSeconds, shadeSeconds += o.shadeSeconds;
        shading.add(o.shading);
    }
};

// Records what every exposure-interval method reports: the tiles' wall time split by thread time
// into intervals (finding them: intervalSeconds), resolve and shade; and the interval counters
// (per sample of numSamples, the budget, compression) and the shading's (per pixel of numPixels).
void recordResolveStats(RenderStats& stats, const SampleResolveCounters& counters, double intervalSeconds, double numSamples,
                        double numPixels, int budget, const PixelShadingOptions& shading);

// A resolved sample: the colour of what it has resolved, and its coverage (alpha).
struct ResolvedSample {
    glm::vec3 color{0.0f};
    float coverage = 0.0f;
};

struct SampleResolveScratch {
    float coverage = 0.0f;  ///< the last sample's: its exposure not left to the background
    bool wasTranslucent = false;  ///< the last sample was resolved with translucency (weights, not visible spans)
    std::vector<float> weights;
    std::vector<VisiblePiece> pieces;
    std::vector<VisibleSpan> visible;  ///< where the opaque intervals show
    OcclusionScratch occlusion;
};

// The colour of one pixel sample from its exposure intervals (Gribel et al. 2010), for every
// method that finds them: shade what must be known before the resolve (translucent opacity;
// every colour when compressing, for the oracle), compress to `budget` (0: never), resolve
// exactly over time (dropping first what is wholly hidden). Returns the colour of all but the
// visible opaque pieces, which it leaves in scratch.pieces (each opaque interval's spans where
// it shows, abutting ones of a triangle merged) for the pixel's shading (PixelShading), and its
// coverage, the exposure not left to the background, in scratch.coverage. The method supplies,
// per interval source:
// triangleOf(source), isTranslucent(triangle) and shade(triangle, t0, t1) -> ShadedColor;
// exactDepth, when given, measures the linear depths' misordering (resolveOpaque). Shares are
// of the sample row's exposure, `window`.
template <class TriangleOf, class IsTranslucent, class Shade>
glm::vec3 resolveSample(std::vector<ExposureInterval>& list, int budget, const OracleWeights& oracle, const ExactDepth* exactDepth,
                        bool cullHidden, const ShutterWindow& window, const glm::vec3& background, TriangleOf&& triangleOf, IsTranslucent&& isTranslucent, Shade&& shade,
                        SampleResolveScratch& scratch, SampleResolveCounters& counters) {
    counters.intervals += std::int64_t(list.size());
    counters.maxIntervals = std::max(counters.maxIntervals, std::int64_t(list.size()));
    const bool isCompressing = budget > 0 && int(list.size()) > budget;
    for (ExposureInterval& interval : list) {
        const std::uint32_t triangle = triangleOf(interval.source);
        if (isCompressing || isTranslucent(triangle)) {
            const ShadedColor c = shade(triangle, interval.t0, interval.t1);
            interval.color = c.color, interval.alpha = c.alpha, interval.isShaded = true;
        }
    }
    if (isCompressing) {
        ++counters.compressedSamples;
        counters.merges += compressIntervals(list, budget, oracle);
    }
    // Wholly hidden intervals get no share in any resolve; the measure of the linear depths'
    // misordering (exactDepth) sees them all.
    if (cullHidden && !exactDepth) counters.hiddenCulled += std::int64_t(cullHiddenIntervals(list, scratch.occlusion));
    counters.maxResolved = std::max(counters.maxResolved, std::int64_t(list.size()));
    scratch.weights.resize(list.size());
    scratch.visible.clear();
    const bool hasTranslucency = std::any_of(list.begin(), list.end(), [](const ExposureInterval& x) { return x.alpha < 1.0f; });
    float backgroundWeight = 0.0f;
    scratch.wasTranslucent = hasTranslucency;
    if (hasTranslucency) backgroundWeight = resolveTranslucent(list, scratch.weights, window);
    else
        backgroundWeight = resolveOpaque(list, scratch.weights, window, exactDepth, exactDepth ? &counters.misorderedTime : nullptr,
                                         exactDepth ? &counters.coveredPairTime : nullptr, &scratch.visible);

    scratch.coverage = 1.0f - backgroundWeight;
    glm::vec3 sum = background * backgroundWeight;
    scratch.pieces.clear();
    for (std::size_t k = 0; k < list.size(); ++k) {
        if (scratch.weights[k] <= 0.0f) continue;
        if (list[k].isShaded) {
            sum += list[k].color * scratch.weights[k];
            continue;
        }
        if (hasTranslucency) {
            const bool isWhole = scratch.weights[k] >= window.measure(list[k].t0, list[k].t1) * (1.0f - 1e-5f);
            scratch.pieces.push_back({triangleOf(list[k].source), list[k].t0, list[k].t1, scratch.weights[k], isWhole});
        }
    }
    // Opaque: each interval is shaded over the time it shows.
    if (!hasTranslucency)
        for (const VisibleSpan& shown : scratch.visible)
            if (!list[shown.interval].isShaded)
                scratch.pieces.push_back({triangleOf(list[shown.interval].source), shown.t0, shown.t1, shown.weight, true});
    mergeAbuttingPieces(scratch.pieces);
    return sum;
}

// Calls show(source, share, depth, nearest, farthest) for what shows in the sample
// resolveSample last resolved from `list`: each span where an opaque interval is the nearest,
// at its mean depth over the span (linear: the middle's) and its ends'; or, resolved with
// translucency, each interval with a share, at its mean depth and its ends' (the resolve keeps
// no spans there). The shares sum to the sample's coverage.
template <class Show>
void forEachShownSurface(const std::vector<ExposureInterval>& list, const SampleResolveScratch& scratch, Show&& show) {
    if (scratch.wasTranslucent) {
        for (std::size_t k = 0; k < list.size(); ++k)
            if (scratch.weights[k] > 0.0f)
                show(list[k].source, scratch.weights[k], list[k].meanDepth(), std::min(list[k].depth0, list[k].depth1),
                     std::max(list[k].depth0, list[k].depth1));
        return;
    }
    for (const VisibleSpan& shown : scratch.visible) {
        const ExposureInterval& interval = list[shown.interval];
        const float d0 = interval.depthAt(shown.t0), d1 = interval.depthAt(shown.t1);
        show(interval.source, shown.weight, interval.depthAt(0.5f * (shown.t0 + shown.t1)), std::min(d0, d1), std::max(d0, d1));
    }
}

// Calls add(source, color) for each interval resolveSample last resolved from `list` whose
// colour it added itself (shaded before the resolve: translucent, or compressed): its colour
// times its share. The rest of the sample's colour is its background's and its pieces'.
template <class Add>
void forEachResolvedColor(const std::vector<ExposureInterval>& list, const SampleResolveScratch& scratch, Add&& add) {
    for (std::size_t k = 0; k < list.size(); ++k)
        if (scratch.weights[k] > 0.0f && list[k].isShaded) add(list[k].source, list[k].color * scratch.weights[k]);
}

}  // namespace streak::exposure
