#include "methods/motion_path/resolve.h"

#include "methods/motion_path/time_mask.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace streak::motion_path {

namespace {

// resolveOpaqueExact's union, kept per thread and reached by a call: a thread_local used in a
// loop is looked up again at every use in a shared library (__tls_get_addr).
[[gnu::noinline]] std::vector<std::pair<float, float>>& coveredSpans() {
    thread_local std::vector<std::pair<float, float>> covered;
    return covered;
}

float resolveOpaque(std::span<const Interval> sorted, int numBits, std::span<float> weights, const ShutterWindow& window) {
    const TimeMask full = TimeMask::full(numBits);
    const float scale = 1.0f / float(numBits);
    TimeMask accumulated;
    std::size_t i = 0;
    for (; i < sorted.size(); ++i) {
        const TimeMask current = TimeMask::exposed(sorted[i].t0, sorted[i].t1, window, numBits);
        weights[i] = float(current.minus(accumulated).count()) * scale;
        accumulated |= current;
        if (accumulated == full) break;
    }
    std::fill(weights.begin() + std::ptrdiff_t(std::min(i + 1, sorted.size())), weights.end(), 0.0f);
    return float(numBits - accumulated.count()) * scale;
}

float resolveOpaqueExact(std::span<const Interval> sorted, std::span<float> weights, const ShutterWindow& window,
                         std::vector<exposure::VisibleSpan>* visible) {
    // The union of the spans so far, disjoint and in time order.
    std::vector<std::pair<float, float>>& covered = coveredSpans();
    covered.clear();
    float coveredLength = 0.0f;
    std::size_t i = 0;
    for (; i < sorted.size() && coveredLength < 1.0f; ++i) {
        const float t0 = std::clamp(sorted[i].t0, 0.0f, 1.0f), t1 = std::clamp(sorted[i].t1, 0.0f, 1.0f);
        weights[i] = 0.0f;
        if (!(t1 > t0)) continue;
        // Spans overlapping [t0, t1] hide part of it and merge with it into one.
        float hidden = 0.0f, lo = t0, hi = t1;  // hidden: exposure
        auto first = std::lower_bound(covered.begin(), covered.end(), t0, [](const auto& span, float t) { return span.second <= t; });
        auto last = first;
        float shownFrom = t0;  ///< where the next visible span may start
        auto show = [&](float a, float b) {
            if (visible && a < b)
                if (const float w = window.measure(a, b); w > 0.0f) visible->push_back({std::uint32_t(i), a, b, w});
        };
        for (; last != covered.end() && last->first < t1; ++last) {
            hidden += window.measure(std::max(last->first, t0), std::min(last->second, t1));
            lo = std::min(lo, last->first), hi = std::max(hi, last->second);
            show(shownFrom, last->first);
            shownFrom = std::max(shownFrom, last->second);
        }
        show(shownFrom, t1);
        const float visible = std::max(0.0f, window.measure(t0, t1) - hidden);
        weights[i] = visible;
        coveredLength += visible;
        covered.insert(covered.erase(first, last), {lo, hi});
    }
    std::fill(weights.begin() + std::ptrdiff_t(i), weights.end(), 0.0f);
    return std::max(0.0f, 1.0f - coveredLength);
}

float resolveTranslucent(std::span<const Interval> sorted, int numBits, std::span<float> weights, const ShutterWindow& window) {
    std::array<float, TimeMask::kMaxBits> transmittance;
    std::fill_n(transmittance.begin(), numBits, 1.0f);
    TimeMask opaque;  // slices already fully covered
    for (std::size_t i = 0; i < sorted.size(); ++i) {
        const Interval& interval = sorted[i];
        weights[i] = 0.0f;
        const TimeMask open = TimeMask::exposed(interval.t0, interval.t1, window, numBits).minus(opaque);
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

bool hasTranslucentInterval(std::span<const Interval> sorted) {
    return std::any_of(sorted.begin(), sorted.end(), [](const Interval& i) { return i.alpha < 1.0f; });
}

float resolveWeights(std::span<const Interval> sorted, int numBits, std::span<float> weights, OpaqueWeights opaque,
                     const ShutterWindow& window) {
    if (hasTranslucentInterval(sorted)) return resolveTranslucent(sorted, numBits, weights, window);
    return opaque == OpaqueWeights::Exact ? resolveOpaqueExact(sorted, weights, window, nullptr) : resolveOpaque(sorted, numBits, weights, window);
}

float resolveOpaqueSpans(std::span<const Interval> sorted, std::span<float> weights, const ShutterWindow& window,
                         std::vector<exposure::VisibleSpan>& visible) {
    return resolveOpaqueExact(sorted, weights, window, &visible);
}

glm::vec3 resolveIntervals(std::span<const Interval> sorted, int numBits, const glm::vec3& background, OpaqueWeights opaque,
                           const ShutterWindow& window) {
    std::vector<float> weights(sorted.size());
    glm::vec3 sum = background * resolveWeights(sorted, numBits, weights, opaque, window);
    for (std::size_t i = 0; i < sorted.size(); ++i) sum += sorted[i].color * weights[i];
    return sum;
}

}  // namespace streak::motion_path
