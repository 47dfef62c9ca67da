#include "exposure/exposure_interval.h"

#include "exposure/shutter_pieces.h"

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace streak::exposure {

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
