#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace streak::motion_path {

// Interval is the time span over which one moving triangle covers a pixel sample (Hong & Oh
// 2017, section 3.3), a segment in the depth-time plane: view depth goes linearly from depth0
// at t0 to depth1 at t1. It carries the triangle's mean shaded colour over the span.
struct Interval {
    float t0 = 0.0f;            ///< shutter time it starts (t0 < t1)
    float t1 = 0.0f;            ///< shutter time it ends
    float depth0 = 0.0f;        ///< view depth at t0
    float depth1 = 0.0f;        ///< view depth at t1
    glm::vec3 color{0.0f};      ///< linear, mean over the span
    float alpha = 1.0f;         ///< 1: opaque
    std::uint32_t source = 0;   ///< what it came from (the renderer's index: a motion path)

    float minDepth() const { return depth0 < depth1 ? depth0 : depth1; }
    float maxDepth() const { return depth0 < depth1 ? depth1 : depth0; }
    // Depth on the interval's line (extended beyond [t0, t1] when t lies outside).
    float depthAt(float t) const { return t1 > t0 ? depth0 + (depth1 - depth0) * (t - t0) / (t1 - t0) : depth0; }
};

// If the depth-time segments of a and b cross strictly inside their common time span, splits
// both there: a and b keep their parts before the crossing, aTail and bTail get the parts after.
bool splitAtCrossing(Interval& a, Interval& b, Interval& aTail, Interval& bTail);

// Hong & Oh's four tests: h may stay in front of k in the list when (1) h is wholly nearer in
// depth, (2) they share no time, (3) k lies behind h's line over their common time span, or (4)
// h lies in front of k's line there. Once crossings are split, (3) and (4) evaluate the same
// two times and agree; both are kept to follow the paper.
bool canStayBefore(const Interval& h, const Interval& k);

struct SortCounters {
    int splits = 0;    ///< crossings split
    int overflow = 0;  ///< splits skipped because the list reached its budget
    int cycles = 0;    ///< positions where no interval could go first (a cycle in depth-time order)
};

// Orders intervals front to back in depth-time: sort by minimum depth, split crossing pairs
// (the list grows by two per split, up to maxIntervals), then selection sort with
// canStayBefore (the paper prefers selection sort: a swap costs more than a comparison). The
// selection checks a candidate against all remaining intervals, since the relation binds only
// intervals that share time; that is O(n^2) per place in the worst case, O(n) when the
// minimum-depth order already holds, which is typical.
void sortDepthTime(std::vector<Interval>& intervals, int maxIntervals, SortCounters& counters);

}  // namespace streak::motion_path
