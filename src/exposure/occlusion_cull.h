#pragma once

#include "exposure/exposure_interval.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace streak::exposure {

struct OcclusionScratch {
    std::vector<std::size_t> byNearest, byFarthest;
    std::vector<std::uint64_t> keys;
    std::vector<std::pair<float, float>> covered;  ///< disjoint time spans, by start
    std::vector<char> isHidden;
};

// Drops the intervals that no resolve can show: those whose whole time span is covered by opaque
// intervals lying nearer over their whole spans (farthest depth below its nearest). Such an
// interval is never the nearest in any piece of the shutter, and an opaque one in front of it
// leaves it no transmittance, so resolveOpaque and resolveTranslucent give it no share; dense
// meshes leave most of a sample's intervals so (ToyCar under a camera move: docs/BENCHMARKS.md).
// The order of the rest is kept. Returns how many were dropped.
std::size_t cullHiddenIntervals(std::vector<ExposureInterval>& intervals, OcclusionScratch& scratch);

}  // namespace streak::exposure
