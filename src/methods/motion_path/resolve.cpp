#include "methods/motion_path/resolve.h"

#include "methods/motion_path/time_mask.h"

#include <algorithm>
#include <array>

namespace streak::motion_path {

namespace {

glm::vec3 resolveOpaque(std::span<const Interval> sorted, int numBits, const glm::vec3& background) {
    const TimeMask full = TimeMask::full(numBits);
    TimeMask accumulated;
    glm::vec3 sum(0.0f);
    for (const Interval& interval : sorted) {
        const TimeMask current = TimeMask::span(interval.t0, interval.t1, numBits);
        sum += interval.color * float(current.minus(accumulated).count());
        accumulated |= current;
        if (accumulated == full) break;
    }
    sum += background * float(numBits - accumulated.count());
    return sum / float(numBits);
}

glm::vec3 resolveTranslucent(std::span<const Interval> sorted, int numBits, const glm::vec3& background) {
    std::array<float, TimeMask::kMaxBits> transmittance;
    std::fill_n(transmittance.begin(), numBits, 1.0f);
    TimeMask opaque;  // slices already fully covered
    glm::vec3 sum(0.0f);
    for (const Interval& interval : sorted) {
        const TimeMask open = TimeMask::span(interval.t0, interval.t1, numBits).minus(opaque);
        if (open.isEmpty()) continue;
        float weight = 0.0f;
        for (int b = 0; b < numBits; ++b) {
            if (!open.test(b)) continue;
            weight += transmittance[b];
            transmittance[b] *= 1.0f - interval.alpha;
            if (transmittance[b] <= 0.0f) opaque.set(b);
        }
        sum += interval.color * (interval.alpha * weight);
    }
    float remaining = 0.0f;
    for (int b = 0; b < numBits; ++b) remaining += transmittance[b];
    return (sum + background * remaining) / float(numBits);
}

}  // namespace

glm::vec3 resolveIntervals(std::span<const Interval> sorted, int numBits, const glm::vec3& background) {
    const bool isTranslucent = std::any_of(sorted.begin(), sorted.end(), [](const Interval& i) { return i.alpha < 1.0f; });
    return isTranslucent ? resolveTranslucent(sorted, numBits, background) : resolveOpaque(sorted, numBits, background);
}

}  // namespace streak::motion_path
