#include "methods/motion_path/resolve.h"

#include "methods/motion_path/time_mask.h"

#include <algorithm>
#include <array>
#include <vector>

namespace streak::motion_path {

namespace {

float resolveOpaque(std::span<const Interval> sorted, int numBits, std::span<float> weights) {
    const TimeMask full = TimeMask::full(numBits);
    const float scale = 1.0f / float(numBits);
    TimeMask accumulated;
    std::size_t i = 0;
    for (; i < sorted.size(); ++i) {
        const TimeMask current = TimeMask::span(sorted[i].t0, sorted[i].t1, numBits);
        weights[i] = float(current.minus(accumulated).count()) * scale;
        accumulated |= current;
        if (accumulated == full) break;
    }
    std::fill(weights.begin() + std::ptrdiff_t(std::min(i + 1, sorted.size())), weights.end(), 0.0f);
    return float(numBits - accumulated.count()) * scale;
}

float resolveTranslucent(std::span<const Interval> sorted, int numBits, std::span<float> weights) {
    std::array<float, TimeMask::kMaxBits> transmittance;
    std::fill_n(transmittance.begin(), numBits, 1.0f);
    TimeMask opaque;  // slices already fully covered
    for (std::size_t i = 0; i < sorted.size(); ++i) {
        const Interval& interval = sorted[i];
        weights[i] = 0.0f;
        const TimeMask open = TimeMask::span(interval.t0, interval.t1, numBits).minus(opaque);
        if (open.isEmpty()) continue;
        float sum = 0.0f;
        for (int b = 0; b < numBits; ++b) {
            if (!open.test(b)) continue;
            sum += transmittance[b];
            transmittance[b] *= 1.0f - interval.alpha;
            if (transmittance[b] <= 0.0f) opaque.set(b);
        }
        weights[i] = interval.alpha * sum / float(numBits);
    }
    float remaining = 0.0f;
    for (int b = 0; b < numBits; ++b) remaining += transmittance[b];
    return remaining / float(numBits);
}

}  // namespace

float resolveWeights(std::span<const Interval> sorted, int numBits, std::span<float> weights) {
    const bool isTranslucent = std::any_of(sorted.begin(), sorted.end(), [](const Interval& i) { return i.alpha < 1.0f; });
    return isTranslucent ? resolveTranslucent(sorted, numBits, weights) : resolveOpaque(sorted, numBits, weights);
}

glm::vec3 resolveIntervals(std::span<const Interval> sorted, int numBits, const glm::vec3& background) {
    std::vector<float> weights(sorted.size());
    glm::vec3 sum = background * resolveWeights(sorted, numBits, weights);
    for (std::size_t i = 0; i < sorted.size(); ++i) sum += sorted[i].color * weights[i];
    return sum;
}

}  // namespace streak::motion_path
