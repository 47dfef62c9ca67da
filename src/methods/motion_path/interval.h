#pragma once

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace streak::motion_path {

// A corner of a merged interval's depth: where two abutting linear pieces of one surface meet.
struct DepthKnot {
    float t = 0.0f;      ///< shutter time
    float depth = 0.0f;  ///< view depth there
};

// Interval is the time span over which one moving triangle covers a pixel sample (Hong & Oh
// 2017, section 3.3), a segment in the depth-time plane: view depth goes linearly from depth0
// at t0 to depth1 at t1. It carries the triangle's mean shaded colour over the span.
//
// Beyond the paper, abutting intervals of one triangle over consecutive linear segments of its
// motion may be merged into one (mergeAbuttingIntervals): its depth is then a polyline through
// numKnots interior corners, knots[firstKnot, firstKnot + numKnots) of the sample's knot list,
// in time order and strictly inside (t0, t1). A finely keyed motion then costs the sort one
// interval per triangle and sample, not one per key segment. The functions below that take the
// knot list follow the polyline; without knots an interval is the paper's straight segment.
struct Interval {
    float t0 = 0.0f;            ///< shutter time it starts (t0 < t1)
    float t1 = 0.0f;            ///< shutter time it ends
    float depth0 = 0.0f;        ///< view depth at t0
    float depth1 = 0.0f;        ///< view depth at t1
    glm::vec3 color{0.0f};      ///< linear, mean over the span
    float alpha = 1.0f;         ///< 1: opaque
    std::uint32_t source = 0;   ///< what it came from (the renderer's index: a motion path; merged: the first)
    std::uint32_t firstKnot = 0, numKnots = 0;  ///< interior corners of the depth, in the knot list
    float knotNear = std::numeric_limits<float>::infinity();    ///< nearest interior corner's depth
    float knotFar = -std::numeric_limits<float>::infinity();    ///< farthest interior corner's depth

    float minDepth() const { return std::min(depth0 < depth1 ? depth0 : depth1, knotNear); }
    float maxDepth() const { return std::max(depth0 < depth1 ? depth1 : depth0, knotFar); }
    // Depth on the straight line from (t0, depth0) to (t1, depth1), extended beyond [t0, t1]
    // when t lies outside; for a merged interval, depthAt(interval, knots, t) below.
    float depthAt(float t) const { return t1 > t0 ? depth0 + (depth1 - depth0) * (t - t0) / (t1 - t0) : depth0; }
};

// Depth of an interval at t on its polyline (the straight segment when it has no knots).
float depthAt(const Interval& interval, std::span<const DepthKnot> knots, float t);

// Merges, in list[first, end), each run of consecutive intervals of one surface (sameSurface(a,
// b) on their sources) that abut exactly in time (one's t1 is the next's t0) with the same
// depth at the joint (to the sort's tolerance), into one interval whose depth is the polyline
// through the joints, appended to `knots`. The runs must come in time order, as one triangle's
// segments do. Opaque intervals only: a translucent one's colour and opacity are its own
// span's. Returns how many intervals were absorbed.
template <class SameSurface>
int mergeAbuttingIntervals(std::vector<Interval>& list, std::size_t first, std::vector<DepthKnot>& knots, SameSurface&& sameSurface);

// If the depth-time segments of a and b cross strictly inside their common time span, splits
// both there: a and b keep their parts before the crossing, aTail and bTail get the parts after.
// With knots, the first crossing of their polylines inside the common span is split.
bool splitAtCrossing(Interval& a, Interval& b, Interval& aTail, Interval& bTail, std::span<const DepthKnot> knots = {});

// Hong & Oh's four tests: h may stay in front of k in the list when (1) h is wholly nearer in
// depth, (2) they share no time, (3) k lies behind h's line over their common time span, or (4)
// h lies in front of k's line there. Once crossings are split, (3) and (4) evaluate the same
// two times and agree; both are kept to follow the paper. With knots, (3) and (4) are checked
// at every corner of either polyline inside the common span as well.
bool canStayBefore(const Interval& h, const Interval& k, std::span<const DepthKnot> knots = {});

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
void sortDepthTime(std::vector<Interval>& intervals, int maxIntervals, SortCounters& counters, std::span<const DepthKnot> knots = {});

// Relative tolerance for depth comparisons: intervals of one surface touching end to end, or
// meeting at a shared edge, must not count as crossing.
inline float depthTolerance(const Interval& a, const Interval& b) { return 1e-6f * (a.maxDepth() + b.maxDepth()); }

template <class SameSurface>
int mergeAbuttingIntervals(std::vector<Interval>& list, std::size_t first, std::vector<DepthKnot>& knots, SameSurface&& sameSurface) {
    if (list.size() < first + 2) return 0;
    std::size_t last = first;  ///< the run being extended
    int merged = 0;
    for (std::size_t k = first + 1; k < list.size(); ++k) {
        Interval& run = list[last];
        const Interval& next = list[k];
        const bool isJoint = run.t1 == next.t0 && run.alpha >= 1.0f && next.alpha >= 1.0f && sameSurface(run.source, next.source) &&
                             std::abs(run.depth1 - next.depth0) <= depthTolerance(run, next);
        if (!isJoint) {
            list[++last] = next;
            continue;
        }
        const DepthKnot joint{run.t1, 0.5f * (run.depth1 + next.depth0)};
        // A corner where nothing bends (a still surface) is left out: the polyline is the same.
        const float before = run.numKnots > 0 ? knots.back().depth : run.depth0;
        if (!(joint.depth == before && joint.depth == next.depth1)) {
            if (run.numKnots == 0) run.firstKnot = std::uint32_t(knots.size());
            knots.push_back(joint);
            ++run.numKnots;
            run.knotNear = std::min(run.knotNear, joint.depth), run.knotFar = std::max(run.knotFar, joint.depth);
        }
        run.t1 = next.t1, run.depth1 = next.depth1;
        ++merged;
    }
    list.resize(last + 1);
    return merged;
}

}  // namespace streak::motion_path
