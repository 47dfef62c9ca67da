#include "methods/motion_path/interval.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace streak::motion_path {

namespace {

std::span<const DepthKnot> knotsOf(const Interval& i, std::span<const DepthKnot> knots) {
    return i.numKnots == 0 ? std::span<const DepthKnot>() : knots.subspan(i.firstKnot, i.numKnots);
}

// Calls visit(t) at ts, at every corner of a's or b's polyline inside (ts, te), and at te, in
// time order, until visit returns false. Between two consecutive calls both depths are linear.
template <class Visit>
void forEachCorner(const Interval& a, const Interval& b, std::span<const DepthKnot> knots, float ts, float te, Visit&& visit) {
    if (!visit(ts)) return;
    const std::span<const DepthKnot> ka = knotsOf(a, knots), kb = knotsOf(b, knots);
    auto after = [ts](std::span<const DepthKnot> k) {
        return std::size_t(std::upper_bound(k.begin(), k.end(), ts, [](float t, const DepthKnot& x) { return t < x.t; }) - k.begin());
    };
    std::size_t i = after(ka), j = after(kb);
    for (;;) {
        const float ta = i < ka.size() ? ka[i].t : te, tb = j < kb.size() ? kb[j].t : te;
        const float t = std::min(ta, tb);
        if (!(t < te)) break;
        if (!visit(t)) return;
        i += ta == t, j += tb == t;
    }
    visit(te);
}

// Restricts an interval's corners to those inside its (new) [t0, t1].
void clipKnots(Interval& i, std::span<const DepthKnot> knots) {
    if (i.numKnots == 0) return;
    const std::span<const DepthKnot> k = knots.subspan(i.firstKnot, i.numKnots);
    const auto begin = std::upper_bound(k.begin(), k.end(), i.t0, [](float t, const DepthKnot& x) { return t < x.t; });
    const auto end = std::lower_bound(begin, k.end(), i.t1, [](const DepthKnot& x, float t) { return x.t < t; });
    i.firstKnot += std::uint32_t(begin - k.begin());
    i.numKnots = std::uint32_t(end - begin);
    i.knotNear = std::numeric_limits<float>::infinity(), i.knotFar = -std::numeric_limits<float>::infinity();
    for (auto it = begin; it != end; ++it) i.knotNear = std::min(i.knotNear, it->depth), i.knotFar = std::max(i.knotFar, it->depth);
}

// An interval's depth range and time span, packed for sortDepthTime's scan of pairs.
struct Reach {
    float near, far, t0, t1;
};

// sortDepthTime's lists, kept per thread (it runs once per pixel sample) and reached by a call:
// a thread_local read in a loop is looked up again at every use in a shared library
// (__tls_get_addr), which took a third of the scan of pairs.
struct SortScratch {
    std::vector<Reach> reach;
    std::vector<std::uint32_t> order, byDepth;
    std::vector<char> isPlaced;
    std::vector<Interval> sorted;
    std::vector<float> nearAtStart;
};

[[gnu::noinline]] SortScratch& sortScratch() {
    thread_local SortScratch scratch;
    return scratch;
}

}  // namespace

float depthAt(const Interval& interval, std::span<const DepthKnot> knots, float t) {
    if (interval.numKnots == 0) return interval.depthAt(t);
    const std::span<const DepthKnot> k = knots.subspan(interval.firstKnot, interval.numKnots);
    // The corners around t: the interval's ends stand before the first knot and after the last.
    const std::size_t next = std::size_t(std::upper_bound(k.begin(), k.end(), t, [](float x, const DepthKnot& c) { return x < c.t; }) - k.begin());
    const float ta = next == 0 ? interval.t0 : k[next - 1].t, da = next == 0 ? interval.depth0 : k[next - 1].depth;
    const float tb = next == k.size() ? interval.t1 : k[next].t, db = next == k.size() ? interval.depth1 : k[next].depth;
    return tb > ta ? da + (db - da) * (t - ta) / (tb - ta) : da;
}

bool splitAtCrossing(Interval& a, Interval& b, Interval& aTail, Interval& bTail, std::span<const DepthKnot> knots) {
    const float ts = std::max(a.t0, b.t0), te = std::min(a.t1, b.t1);
    if (!(ts < te)) return false;
    const float eps = depthTolerance(a, b);
    float t = 0.0f;
    if (a.numKnots == 0 && b.numKnots == 0) {
        const float ds = a.depthAt(ts) - b.depthAt(ts);
        const float de = a.depthAt(te) - b.depthAt(te);
        if (!((ds > eps && de < -eps) || (ds < -eps && de > eps))) return false;
        t = ts + (te - ts) * ds / (ds - de);
    } else {
        // The first change of side beyond the tolerance: between the last corner where the
        // difference had the old side's sign and the first beyond it on the other side, the
        // last pair of corners where it goes from that sign to zero or past holds a root.
        int side = 0;
        bool isCrossed = false;
        float previousT = ts, previousD = 0.0f;
        forEachCorner(a, b, knots, ts, te, [&](float c) {
            const float d = depthAt(a, knots, c) - depthAt(b, knots, c);
            // (side is 0 until a corner beyond the tolerance, so the first corner never pairs.)
            if (side != 0 && float(side) * previousD > 0.0f && float(side) * d <= 0.0f)
                t = previousT + (c - previousT) * previousD / (previousD - d);
            previousT = c, previousD = d;
            const int s = d > eps ? 1 : d < -eps ? -1 : 0;
            if (s == 0) return true;
            if (side == 0) {
                side = s;
                return true;
            }
            if (s == side) return true;
            isCrossed = true;
            return false;
        });
        if (!isCrossed) return false;
    }
    if (!(t > a.t0 && t < a.t1 && t > b.t0 && t < b.t1)) return false;
    const float depthA = depthAt(a, knots, t), depthB = depthAt(b, knots, t);
    aTail = a, bTail = b;
    a.t1 = t, a.depth1 = depthA;
    aTail.t0 = t, aTail.depth0 = depthA;
    b.t1 = t, b.depth1 = depthB;
    bTail.t0 = t, bTail.depth0 = depthB;
    clipKnots(a, knots), clipKnots(aTail, knots), clipKnots(b, knots), clipKnots(bTail, knots);
    return true;
}

bool canStayBefore(const Interval& h, const Interval& k, std::span<const DepthKnot> knots) {
    const float eps = depthTolerance(h, k);
    if (h.maxDepth() <= k.minDepth() + eps) return true;  // (1) no depth overlap
    const float ts = std::max(h.t0, k.t0), te = std::min(h.t1, k.t1);
    if (!(ts < te)) return true;  // (2) no time overlap
    if (h.numKnots > 0 || k.numKnots > 0) {
        // (3) and (4) at every corner: each says h's depth <= k's + eps there.
        bool isBefore = true;
        forEachCorner(h, k, knots, ts, te, [&](float t) { return isBefore = depthAt(h, knots, t) <= depthAt(k, knots, t) + eps; });
        return isBefore;
    }
    // (3) k behind h's line at both ends of the common span.
    if (k.depthAt(ts) >= h.depthAt(ts) - eps && k.depthAt(te) >= h.depthAt(te) - eps) return true;
    // (4) h in front of k's line at both ends.
    return h.depthAt(ts) <= k.depthAt(ts) + eps && h.depthAt(te) <= k.depthAt(te) + eps;
}

void sortDepthTime(std::vector<Interval>& intervals, int maxIntervals, SortCounters& counters, std::span<const DepthKnot> knots) {
    std::sort(intervals.begin(), intervals.end(), [](const Interval& a, const Interval& b) { return a.minDepth() < b.minDepth(); });
    // Split every crossing pair. Pieces of a segment cannot cross what the whole did not, and
    // the inner loop runs over the growing list, so every pair is seen once it exists. The scan
    // reads each interval's depth range and time span packed (a dense sample's hundreds of
    // intervals make it quadratic), and passes over pairs with disjoint ranges or no common
    // time, which splitAtCrossing would refuse, before the copies.
    //
    // The scan of i's partners also stops early in the list sorted above: a split piece lies
    // within its interval's depth range (its new end's depth is interpolated between corners of
    // it), so nears only grow, and past the first partner whose near at the start lies beyond
    // i's far every one's does, now too. Pieces appended by splits are scanned whole. (A dense
    // sample's 161 sliver intervals each overlap a few others in depth: the scan of pairs was
    // 30% of motion-path's dense move. Non-finite depths sort in no order: no stop there.)
    SortScratch& scratch = sortScratch();
    auto reachOf = [](const Interval& x) { return Reach{x.minDepth(), x.maxDepth(), x.t0, x.t1}; };
    std::vector<Reach>& reach = scratch.reach;
    reach.clear();
    for (const Interval& x : intervals) reach.push_back(reachOf(x));
    const std::size_t sortedCount = intervals.size();
    const bool canStop = std::all_of(reach.begin(), reach.end(), [](const Reach& r) { return std::isfinite(r.near) && std::isfinite(r.far); });
    std::vector<float>& nearAtStart = scratch.nearAtStart;
    nearAtStart.clear();
    for (const Reach& r : reach) nearAtStart.push_back(r.near);
    for (std::size_t i = 0; i < intervals.size(); ++i) {
        for (std::size_t j = i + 1; j < intervals.size(); ++j) {
            if (canStop && j < sortedCount && nearAtStart[j] > reach[i].far) {
                j = sortedCount - 1;  // on to the appended pieces
                continue;
            }
            const Reach& r = reach[j];
            const Reach& ri = reach[i];
            if (r.near > ri.far || ri.near > r.far || !(r.t0 < ri.t1 && ri.t0 < r.t1)) continue;
            Interval aTail, bTail;
            Interval a = intervals[i], b = intervals[j];
            if (!splitAtCrossing(a, b, aTail, bTail, knots)) continue;
            if (int(intervals.size()) + 2 > maxIntervals) {
                ++counters.overflow;
                continue;
            }
            intervals[i] = a;
            intervals[j] = b;
            intervals.push_back(aTail);
            intervals.push_back(bTail);
            reach[i] = reachOf(a), reach[j] = reachOf(b);
            reach.push_back(reachOf(aTail)), reach.push_back(reachOf(bTail));
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
    std::vector<std::uint32_t>&order = scratch.order, &byDepth = scratch.byDepth;
    std::vector<char>& isPlaced = scratch.isPlaced;
    std::vector<Interval>& sorted = scratch.sorted;
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
                if (order[k] != c && !canStayBefore(intervals[c], intervals[order[k]], knots)) return false;
            return true;
        }
        const float farthest = intervals[c].maxDepth();
        for (std::size_t d = firstUnplaced; d < n; ++d) {
            const std::uint32_t k = byDepth[d];
            if (isPlaced[k]) continue;
            if (intervals[k].minDepth() >= farthest) break;
            if (k != c && !canStayBefore(intervals[c], intervals[k], knots)) return false;
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
