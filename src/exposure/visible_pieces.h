#pragma once

#include <cstdint>
#include <vector>

namespace streak::exposure {

// A visible piece of one triangle at one pixel sample, after visibility is resolved: what
// remains to be shaded, and its share of the sample.
struct VisiblePiece {
    std::uint32_t triangle = 0;
    float t0 = 0.0f, t1 = 0.0f;
    float weight = 0.0f;   ///< its share of the sample's colour
    bool isWhole = false;  ///< visible all through [t0, t1]: may merge with its neighbours
};

// Merges wholly visible pieces of one triangle that abut in time (the same triangle over
// consecutive linear segments, or the two halves of a split) into one span with the summed
// weight, so it is shaded once: its colour is the mean over the span, as an interval's colour
// is the mean over the interval. A partly hidden piece stays alone, so its colour stays the
// mean over its own time. Reorders `pieces` (by triangle, then time).
void mergeAbuttingPieces(std::vector<VisiblePiece>& pieces);

}  // namespace streak::exposure
