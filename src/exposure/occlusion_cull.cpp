#include "exposure/occlusion_cull.h"

#include "util/sort_keys.h"

#include <algorithm>

namespace streak::exposure {

namespace {

float nearestDepth(const ExposureInterval& x) { return std::min(x.depth0, x.depth1); }
float farthestDepth(const ExposureInterval& x) { return std::max(x.depth0, x.depth1); }

// Adds [t0, t1] to the disjoint spans, merging those it overlaps or touches.
void addSpan(std::vector<std::pair<float, float>>& spans, float t0, float t1) {
    auto first = std::lower_bound(spans.begin(), spans.end(), t0, [](const std::pair<float, float>& s, float t) { return s.second < t; });
    auto last = first;
    while (last != spans.end() && last->first <= t1) {
        t0 = std::min(t0, last->first), t1 = std::max(t1, last->second);
        ++last;
    }
    first = spans.erase(first, last);
    spans.insert(first, {t0, t1});
}

bool isCovered(const std::vector<std::pair<float, float>>& spans, float t0, float t1) {
    auto s = std::upper_bound(spans.begin(), spans.end(), t0, [](float t, const std::pair<float, float>& x) { return t < x.first; });
    if (s == spans.begin()) return false;
    --s;
    return s->first <= t0 && s->second >= t1;
}

}  // namespace

std::size_t cullHiddenIntervals(std::vector<ExposureInterval>& intervals, OcclusionScratch& scratch) {
    const std::size_t n = intervals.size();
    if (n < 2) return 0;
    // Both orders as sorted keys (sortKey: by depth, then index). Which of equal depths comes
    // first changes nothing below: an interval is tested against the occluders wholly nearer
    // than it, whatever their order.
    auto sortedBy = [&](auto&& depthOf, auto&& isIncluded, std::vector<std::size_t>& order) {
        scratch.keys.clear();
        for (std::size_t i = 0; i < n; ++i)
            if (isIncluded(intervals[i])) scratch.keys.push_back(sortKey(depthOf(intervals[i]), std::uint32_t(i)));
        sortedIndices(scratch.keys, order);
    };
    sortedBy(nearestDepth, [](const ExposureInterval&) { return true; }, scratch.byNearest);
    sortedBy(farthestDepth, [](const ExposureInterval& x) { return x.alpha >= 1.0f; }, scratch.byFarthest);
    // Sweep by nearest depth; the occluders of an interval are the opaque ones wholly nearer
    // (farthest depth below its nearest), added to the covered spans as the sweep deepens.
    scratch.covered.clear();
    scratch.isHidden.assign(n, 0);
    std::size_t next = 0, hidden = 0;
    for (const std::size_t q : scratch.byNearest) {
        const float depth = nearestDepth(intervals[q]);
        for (; next < scratch.byFarthest.size() && farthestDepth(intervals[scratch.byFarthest[next]]) < depth; ++next)
            addSpan(scratch.covered, intervals[scratch.byFarthest[next]].t0, intervals[scratch.byFarthest[next]].t1);
        if (!scratch.covered.empty() && isCovered(scratch.covered, intervals[q].t0, intervals[q].t1)) scratch.isHidden[q] = 1, ++hidden;
    }
    if (hidden == 0) return 0;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (!scratch.isHidden[i]) intervals[kept++] = intervals[i];
    intervals.resize(kept);
    return hidden;
}

}  // namespace streak::exposure
