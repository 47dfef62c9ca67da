#include "methods/motion_path/interval.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace streak::motion_path {

namespace {

// Relative tolerance for depth comparisons: intervals of one surface touching end to end, or
// meeting at a shared edge, must not count as crossing.
float tolerance(const Interval& a, const Interval& b) { return 1e-6f * (a.maxDepth() + b.maxDepth()); }

}  // namespace

bool splitAtCrossing(Interval& a, Interval& b, Interval& aTail, Interval& bTail) {
    const float ts = std::max(a.t0, b.t0), te = std::min(a.t1, b.t1);
    if (!(ts < te)) return false;
    const float ds = a.depthAt(ts) - b.depthAt(ts);
    const float de = a.depthAt(te) - b.depthAt(te);
    const float eps = tolerance(a, b);
    if (!((ds > eps && de < -eps) || (ds < -eps && de > eps))) return false;
    const float t = ts + (te - ts) * ds / (ds - de);
    if (!(t > a.t0 && t < a.t1 && t > b.t0 && t < b.t1)) return false;
    const float depthA = a.depthAt(t), depthB = b.depthAt(t);
    aTail = a, bTail = b;
    a.t1 = t, a.depth1 = depthA;
    aTail.t0 = t, aTail.depth0 = depthA;
    b.t1 = t, b.depth1 = depthB;
    bTail.t0 = t, bTail.depth0 = depthB;
    return true;
}

bool canStayBefore(const Interval& h, const Interval& k) {
    const float eps = tolerance(h, k);
    if (h.maxDepth() <= k.minDepth() + eps) return true;  // (1) no depth overlap
    const float ts = std::max(h.t0, k.t0), te = std::min(h.t1, k.t1);
    if (!(ts < te)) return true;  // (2) no time overlap
    // (3) k behind h's line at both ends of the common span.
    if (k.depthAt(ts) >= h.depthAt(ts) - eps && k.depthAt(te) >= h.depthAt(te) - eps) return true;
    // (4) h in front of k's line at both ends.
    return h.depthAt(ts) <= k.depthAt(ts) + eps && h.depthAt(te) <= k.depthAt(te) + eps;
}

void sortDepthTime(std::vector<Interval>& intervals, int maxIntervals, SortCounters& counters) {
    std::sort(intervals.begin(), intervals.end(), [](const Interval& a, const Interval& b) { return a.minDepth() < b.minDepth(); });
    // Split every crossing pair. Pieces of a segment cannot cross what the whole did not, and
    // the inner loop runs over the growing list, so every pair is seen once it exists.
    for (std::size_t i = 0; i < intervals.size(); ++i) {
        for (std::size_t j = i + 1; j < intervals.size(); ++j) {
            // Disjoint depth ranges cannot cross (a cheap test before the copies).
            if (intervals[j].minDepth() > intervals[i].maxDepth() || intervals[i].minDepth() > intervals[j].maxDepth()) continue;
            Interval aTail, bTail;
            Interval a = intervals[i], b = intervals[j];
            if (!splitAtCrossing(a, b, aTail, bTail)) continue;
            if (int(intervals.size()) + 2 > maxIntervals) {
                ++counters.overflow;
                continue;
            }
            intervals[i] = a;
            intervals[j] = b;
            intervals.push_back(aTail);
            intervals.push_back(bTail);
            ++counters.splits;
        }
    }
    // Selection sort: place at i the first remaining interval that every other remaining one
    // lets stay in front. The relation only binds intervals sharing time, so it is a partial
    // order; a cycle (possible with four or more intervals) falls back to the nearest. Only the
    // remaining intervals nearer than a candidate's farthest depth can keep it from going first
    // (test 1 passes for the rest), so they are scanned in order of nearest depth and the scan
    // stops there: the same choices as checking them all, without the quadratic scan of dense
    // lists. (Non-finite depths fall back to checking them all.)
    const std::size_t n = intervals.size();
    if (n < 2) return;
    const bool isFinite = std::all_of(intervals.begin(), intervals.end(), [](const Interval& x) {
        return std::isfinite(x.depth0) && std::isfinite(x.depth1);
    });
    // Per-thread scratch: this runs once per pixel sample.
    thread_local std::vector<std::uint32_t> order, byDepth;
    thread_local std::vector<char> isPlaced;
    thread_local std::vector<Interval> sorted;
    order.resize(n), byDepth.resize(n);
    std::iota(order.begin(), order.end(), 0u);
    std::iota(byDepth.begin(), byDepth.end(), 0u);
    if (isFinite)
        std::sort(byDepth.begin(), byDepth.end(),
                  [&](std::uint32_t a, std::uint32_t b) { return intervals[a].minDepth() < intervals[b].minDepth(); });
    isPlaced.assign(n, 0);
    std::size_t firstUnplaced = 0;  ///< in byDepth
    auto canGoFirst = [&](std::uint32_t c, std::size_t i) {
        if (!isFinite) {
            for (std::size_t k = i; k < n; ++k)
                if (order[k] != c && !canStayBefore(intervals[c], intervals[order[k]])) return false;
            return true;
        }
        const float farthest = intervals[c].maxDepth();
        for (std::size_t d = firstUnplaced; d < n; ++d) {
            const std::uint32_t k = byDepth[d];
            if (isPlaced[k]) continue;
            if (intervals[k].minDepth() >= farthest) break;
            if (k != c && !canStayBefore(intervals[c], intervals[k])) return false;
        }
        return true;
    };
    for (std::size_t i = 0; i + 1 < n; ++i) {
        std::size_t front = i;
        bool found = false;
        for (std::size_t c = i; c < n && !found; ++c)
            if (canGoFirst(order[c], i)) found = true, front = c;
        if (!found) ++counters.cycles;
        if (front != i) std::swap(order[i], order[front]);
        isPlaced[order[i]] = 1;
        while (firstUnplaced < n && isPlaced[byDepth[firstUnplaced]]) ++firstUnplaced;
    }
    sorted.clear();
    for (const std::uint32_t id : order) sorted.push_back(intervals[id]);
    intervals.swap(sorted);
}

}  // namespace streak::motion_path
