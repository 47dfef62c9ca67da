#pragma once

#include "exposure/exposure_interval.h"
#include "util/sort_keys.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace streak::exposure {

// The shutter cut at every interval end and wherever two intervals' depth lines cross inside
// their common time, so that within a piece the depth order is fixed: f(a, b, covering) for
// each piece [a, b] in time order, with the intervals covering it (t0 <= a and t1 >= b) in
// index order. The exact resolves (resolveOpaque, resolveTranslucent) are sums over these
// pieces. Two ways find the same pieces and coverings, to the bit:
//
// - by pairs: every pair of intervals is tested for a crossing, and every piece scans every
//   interval for its covering. O(n^2) for n intervals, with nothing to set up: a sample's list
//   is usually short, and up to kOnStack intervals it stays off the heap (two allocations were
//   a tenth of an --aa 1 frame's resolve).
// - by a sweep: the intervals are taken in order of their start, and each entering one is tested
//   only against those still open; pieces keep the open set. O(n log n + n k) for k intervals
//   open at once. A dense model under a camera move has a hundred or more intervals at a
//   sample, each open for a sliver of the shutter (k about 10), where the pairs took a fifth of
//   the frame.
//
// forEachPiece takes the sweep past kSweepFrom intervals (where the pairs would allocate) when
// every interval lies inside the shutter (0 <= t0 <= t1 <= 1: crossings then fall inside it
// too); anything else keeps the pairs. f must not resolve another list: the sweep's lists are
// the thread's.

namespace pieces {

constexpr std::size_t kOnStack = 8;
constexpr std::size_t kSweepFrom = kOnStack;  // past the stack, the sweep's lists are warm and the pairs' are not

// Where a and b's depth lines cross strictly inside their common time, if they do (the one
// formula both ways use, so their cuts are the same floats).
inline bool crossing(const ExposureInterval& a, const ExposureInterval& b, float& at) {
    const float lo = std::max(a.t0, b.t0), hi = std::min(a.t1, b.t1);
    if (!(hi > lo)) return false;
    const float dLo = a.depthAt(lo) - b.depthAt(lo), dHi = a.depthAt(hi) - b.depthAt(hi);
    if (!((dLo < 0.0f && dHi > 0.0f) || (dLo > 0.0f && dHi < 0.0f))) return false;
    at = lo + (hi - lo) * dLo / (dLo - dHi);
    return true;
}

template <class F>
void byPairs(std::span<const ExposureInterval> intervals, F&& f) {
    constexpr std::size_t kCutsOnStack = 2 + 2 * kOnStack + kOnStack * (kOnStack - 1) / 2;
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
            for (std::size_t j = i + 1; j < n; ++j)
                if (float at; crossing(intervals[i], intervals[j], at)) cuts[numCuts++] = at;
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

// Whether the sweep may take the list: every interval a finite span inside the shutter.
inline bool isInsideShutter(std::span<const ExposureInterval> intervals) {
    for (const ExposureInterval& i : intervals)
        if (!(i.t0 >= 0.0f && i.t0 <= i.t1 && i.t1 <= 1.0f)) return false;
    return true;
}

// The sweep's lists, kept per thread so a sample's resolve allocates nothing once warm. Reached
// by a call, so the sweep looks the thread's storage up once (a thread_local used in a loop is
// looked up at every use in a shared library).
struct SweepScratch {
    std::vector<std::uint32_t> byStart, byEnd, open;
    std::vector<std::uint64_t> keys;
    std::vector<float> cuts;
    std::vector<std::size_t> covering;
};

[[gnu::noinline]] inline SweepScratch& sweepScratch() {
    thread_local SweepScratch scratch;
    return scratch;
}

// Requires isInsideShutter(intervals).
template <class F>
void bySweep(std::span<const ExposureInterval> intervals, F&& f) {
    const std::uint32_t n = std::uint32_t(intervals.size());
    SweepScratch& s = sweepScratch();
    // The starts and ends in order, as sorted keys (sortKey: by time, then index; the order of
    // equal times changes nothing below).
    auto sortedBy = [&](float ExposureInterval::*time, std::vector<std::uint32_t>& order) {
        s.keys.resize(n);
        for (std::uint32_t i = 0; i < n; ++i) s.keys[i] = sortKey(intervals[i].*time, i);
        sortedIndices(s.keys, order);
    };
    sortedBy(&ExposureInterval::t0, s.byStart);
    sortedBy(&ExposureInterval::t1, s.byEnd);

    // The cuts: the shutter's ends, every interval's ends and the crossings. A pair that shares
    // time (max t0 < min t1) is tested when its later start enters: the earlier one is still
    // open then, since it ends after that start. Each pair is tested once, in index order as
    // the pairs are.
    s.cuts.clear();
    s.cuts.push_back(0.0f), s.cuts.push_back(1.0f);
    for (const ExposureInterval& i : intervals) s.cuts.push_back(i.t0), s.cuts.push_back(i.t1);
    s.open.clear();
    for (const std::uint32_t j : s.byStart) {
        const float start = intervals[j].t0;
        std::erase_if(s.open, [&](std::uint32_t i) { return intervals[i].t1 <= start; });
        for (const std::uint32_t i : s.open)
            if (float at; crossing(intervals[std::min(i, j)], intervals[std::max(i, j)], at)) s.cuts.push_back(at);
        s.open.push_back(j);
    }
    std::sort(s.cuts.begin(), s.cuts.end());
    s.cuts.erase(std::unique(s.cuts.begin(), s.cuts.end()), s.cuts.end());

    // The pieces, each with the intervals open over it: started by its start and not ended by
    // it (an end is a cut, so one that ends after a piece's start covers the whole piece). The
    // open set is kept in index order, the order the pairs list a covering in.
    s.open.clear();
    s.covering.resize(n);
    std::size_t nextStart = 0, nextEnd = 0;
    for (std::size_t c = 0; c + 1 < s.cuts.size(); ++c) {
        const float a = s.cuts[c], b = s.cuts[c + 1];
        for (; nextStart < n && intervals[s.byStart[nextStart]].t0 <= a; ++nextStart)
            s.open.insert(std::lower_bound(s.open.begin(), s.open.end(), s.byStart[nextStart]), s.byStart[nextStart]);
        for (; nextEnd < n && intervals[s.byEnd[nextEnd]].t1 <= a; ++nextEnd) {
            const auto it = std::lower_bound(s.open.begin(), s.open.end(), s.byEnd[nextEnd]);
            if (it != s.open.end() && *it == s.byEnd[nextEnd]) s.open.erase(it);
        }
        std::size_t numCovering = 0;
        for (const std::uint32_t i : s.open)
            if (intervals[i].t0 <= a && intervals[i].t1 >= b) s.covering[numCovering++] = i;
        f(a, b, std::span<std::size_t>(s.covering.data(), numCovering));
    }
}

}  // namespace pieces

template <class F>
void forEachPiece(std::span<const ExposureInterval> intervals, F&& f) {
    if (intervals.size() > pieces::kSweepFrom && pieces::isInsideShutter(intervals)) pieces::bySweep(intervals, f);
    else pieces::byPairs(intervals, f);
}

}  // namespace streak::exposure
