#include "exposure/exposure_interval.h"

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace streak::exposure {

namespace {

// The shutter cut at every interval end and wherever two intervals' depth lines cross inside
// their common time, so that within a piece the depth order is fixed; f(a, b, covering) for
// each piece [a, b] with the intervals covering it. A sample's list is short and its resolve
// quick: up to kOnStack intervals the cuts and the covering stay off the heap (two allocations
// were a tenth of an --aa 1 frame's resolve).
template <class F>
void forEachPiece(std::span<const ExposureInterval> intervals, F&& f) {
    constexpr std::size_t kOnStack = 8, kCutsOnStack = 2 + 2 * kOnStack + kOnStack * (kOnStack - 1) / 2;
    const std::size_t n = intervals.size();
    std::array<float, kCutsOnStack> stackCuts;
    std::array<std::size_t, kOnStack> stackCovering;
    std::vector<float> heapCuts;
    std::vector<std::size_t> heapCovering;
    float* cuts = stackCuts.data();
    std::size_t* covering = stackCovering.data();
    if (n > kOnStack) {
        heapCuts.resize(2 + 2 * n + n * (n - 1) / 2), heapCovering.resize(n);
        cuts = heapCuts.data(), covering = heapCovering.data();
    }
    std::size_t numCuts = 0;
    const float lone0 = n == 1 ? std::clamp(intervals[0].t0, 0.0f, 1.0f) : 0.0f, lone1 = n == 1 ? std::clamp(intervals[0].t1, 0.0f, 1.0f) : 0.0f;
    if (n == 1 && lone0 < lone1) {
        // A lone interval (most samples of a still scene: [0, 1]) crosses nothing: its ends are
        // the only cuts, written in order, so nothing is sorted. (Empty or not a number: below.)
        cuts[numCuts++] = 0.0f;
        if (lone0 > 0.0f) cuts[numCuts++] = lone0;
        if (lone1 < 1.0f) cuts[numCuts++] = lone1;
        cuts[numCuts++] = 1.0f;
    } else {
        cuts[numCuts++] = 0.0f, cuts[numCuts++] = 1.0f;
        for (const ExposureInterval& i : intervals) cuts[numCuts++] = std::clamp(i.t0, 0.0f, 1.0f), cuts[numCuts++] = std::clamp(i.t1, 0.0f, 1.0f);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j) {
                const ExposureInterval &a = intervals[i], &b = intervals[j];
                const float lo = std::max(a.t0, b.t0), hi = std::min(a.t1, b.t1);
                if (!(hi > lo)) continue;
                const float dLo = a.depthAt(lo) - b.depthAt(lo), dHi = a.depthAt(hi) - b.depthAt(hi);
                if ((dLo < 0.0f && dHi > 0.0f) || (dLo > 0.0f && dHi < 0.0f)) cuts[numCuts++] = lo + (hi - lo) * dLo / (dLo - dHi);
            }
        std::sort(cuts, cuts + numCuts);
        numCuts = std::size_t(std::unique(cuts, cuts + numCuts) - cuts);
    }
    for (std::size_t c = 0; c + 1 < numCuts; ++c) {
        const float a = cuts[c], b = cuts[c + 1];
        std::size_t numCovering = 0;
        for (std::size_t i = 0; i < n; ++i)
            if (intervals[i].t0 <= a && intervals[i].t1 >= b) covering[numCovering++] = i;
        f(a, b, std::span<std::size_t>(covering, numCovering));
    }
}

}  // namespace

float oracle(const ExposureInterval& a, const ExposureInterval& b, const OracleWeights& h) {
    const ExposureInterval& first = a.t0 <= b.t0 ? a : b;
    const ExposureInterval& second = a.t0 <= b.t0 ? b : a;
    const float scale = std::max({std::abs(a.meanDepth()), std::abs(b.meanDepth()), 1e-6f});
    const glm::vec3 dc = glm::abs(a.color - b.color);
    return h.gap * std::max(second.t0 - first.t1, 0.0f) + h.depth * std::abs(a.meanDepth() - b.meanDepth()) / scale +
           h.slope * std::abs(a.depthSlope() - b.depthSlope()) / scale + h.duration * (a.duration() + b.duration()) +
           h.color * (dc.x + dc.y + dc.z);
}

ExposureInterval mergeIntervals(const ExposureInterval& a, const ExposureInterval& b) {
    const ExposureInterval& first = a.t0 <= b.t0 ? a : b;
    const ExposureInterval& last = a.t1 >= b.t1 ? a : b;
    ExposureInterval m;
    m.t0 = first.t0, m.t1 = last.t1;
    m.depth0 = first.depth0, m.depth1 = last.depth1;
    const float wa = a.duration(), wb = b.duration(), sum = wa + wb;
    const float fa = sum > 0.0f ? wa / sum : 0.5f;
    m.color = fa * a.color + (1.0f - fa) * b.color;
    m.alpha = fa * a.alpha + (1.0f - fa) * b.alpha;
    m.source = wa >= wb ? a.source : b.source;
    m.isShaded = a.isShaded && b.isShaded;
    m.isMerged = true;
    return m;
}

int compressIntervals(std::vector<ExposureInterval>& intervals, int budget, const OracleWeights& h) {
    int merges = 0;
    while (budget > 0 && int(intervals.size()) > budget) {
        std::size_t bestI = 0, bestJ = 1;
        float best = std::numeric_limits<float>::infinity();
        for (std::size_t i = 0; i < intervals.size(); ++i)
            for (std::size_t j = i + 1; j < intervals.size(); ++j) {
                const float o = oracle(intervals[i], intervals[j], h);
                if (o < best) best = o, bestI = i, bestJ = j;
            }
        intervals[bestI] = mergeIntervals(intervals[bestI], intervals[bestJ]);
        intervals.erase(intervals.begin() + std::ptrdiff_t(bestJ));
        ++merges;
    }
    return merges;
}

float resolveOpaque(std::span<const ExposureInterval> intervals, std::span<float> weights, const ShutterWindow& window,
                    const ExactDepth* exactDepth, double* misorderedTime, double* overlapTime, std::vector<VisibleSpan>* visible) {
    std::fill(weights.begin(), weights.end(), 0.0f);
    float background = 0.0f;
    forEachPiece(intervals, [&](float a, float b, std::span<std::size_t> covering) {
        const float share = window.measure(a, b);
        if (covering.empty()) {
            background += share;
            return;
        }
        const float tm = 0.5f * (a + b);
        std::size_t nearest = covering[0];
        for (std::size_t i : covering.subspan(1))  // (the first against itself never wins)
            if (intervals[i].depthAt(tm) < intervals[nearest].depthAt(tm)) nearest = i;
        weights[nearest] += share;
        if (visible && share > 0.0f) appendVisibleSpan(*visible, std::uint32_t(nearest), a, b, share);
        if (exactDepth && misorderedTime && covering.size() > 1) {
            if (overlapTime) *overlapTime += b - a;
            std::size_t trueNearest = covering[0];
            double trueDepth = (*exactDepth)(covering[0], tm);
            for (std::size_t i : covering) {
                const double d = (*exactDepth)(i, tm);
                if (d < trueDepth) trueDepth = d, trueNearest = i;
            }
            if (trueNearest != nearest) *misorderedTime += b - a;
        }
    });
    return background;
}

float resolveTranslucent(std::span<const ExposureInterval> intervals, std::span<float> weights, const ShutterWindow& window) {
    std::fill(weights.begin(), weights.end(), 0.0f);
    float background = 0.0f;
    forEachPiece(intervals, [&](float a, float b, std::span<std::size_t> covering) {
        const float tm = 0.5f * (a + b), share = window.measure(a, b);
        std::sort(covering.begin(), covering.end(),
                  [&](std::size_t i, std::size_t j) { return intervals[i].depthAt(tm) < intervals[j].depthAt(tm); });
        float transmittance = 1.0f;
        for (std::size_t i : covering) {
            weights[i] += share * transmittance * intervals[i].alpha;
            transmittance *= 1.0f - intervals[i].alpha;
            if (transmittance <= 0.0f) break;
        }
        background += share * transmittance;
    });
    return background;
}

}  // namespace streak::exposure
