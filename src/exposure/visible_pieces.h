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

// Where interval `interval` of a sample's list shows, from an exact resolve: a time span in
// which it is the nearest, and the span's share of the sample (its exposure). A partly hidden
// interval is shaded over these spans alone, so its share is the integral of its colour over
// the time it shows, not its whole span's mean times that share.
struct VisibleSpan {
    std::uint32_t interval = 0;  ///< index in the resolved list
    float t0 = 0.0f, t1 = 0.0f;
    float weight = 0.0f;
};

// Appends [t0, t1] of interval `interval` to `spans`, joined to the last span when that is the
// same interval's and ends at t0 (consecutive pieces of the shutter).
inline void appendVisibleSpan(std::vector<VisibleSpan>& spans, std::uint32_t interval, float t0, float t1, float weight) {
    if (!spans.empty() && spans.back().interval == interval && spans.back().t1 == t0) {
        spans.back().t1 = t1, spans.back().weight += weight;
        return;
    }
    spans.push_back({interval, t0, t1, weight});
}

// Merges wholly visible pieces of one triangle that abut in time (the same triangle over
// consecutive linear segments, or the two halves of a split) into one span with the summed
// weight, so it is shaded once: its colour is the mean over the span, as an interval's colour
// is the mean over the interval. A partly hidden piece stays alone, so its colour stays the
// mean over its own time. Reorders `pieces` (by triangle, then time).
void mergeAbuttingPieces(std::vector<VisiblePiece>& pieces);

}  // namespace streak::exposure
