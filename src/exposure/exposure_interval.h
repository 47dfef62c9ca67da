#pragma once

#include "exposure/visible_pieces.h"
#include "scene/shutter.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace streak::exposure {

// ExposureInterval is a time span over which one triangle covers a pixel sample exactly (Gribel
// et al. 2010): its ends are roots of the moving edge equations. Depth over it is taken as
// linear between its ends, as in the paper.
struct ExposureInterval {
    float t0 = 0.0f, t1 = 0.0f;          ///< shutter times, t0 < t1
    float depth0 = 0.0f, depth1 = 0.0f;  ///< view depth at t0 and t1
    glm::vec3 color{0.0f};               ///< linear, mean over the span (valid once shaded)
    float alpha = 1.0f;                  ///< 1: opaque
    std::uint32_t source = 0;            ///< the renderer's index (a triangle segment)
    bool isShaded = false;
    bool isMerged = false;               ///< made by compression: covers [t0, t1] only approximately

    float duration() const { return t1 - t0; }
    float meanDepth() const { return 0.5f * (depth0 + depth1); }
    float depthSlope() const { return t1 > t0 ? (depth1 - depth0) / (t1 - t0) : 0.0f; }
    float depthAt(float t) const { return t1 > t0 ? depth0 + (depth1 - depth0) * (t - t0) / (t1 - t0) : depth0; }
};

// Gribel et al.'s compression oracle weights: O(i, j) = h1 max(ts_j - te_i, 0) + h2 |z_i - z_j|
// + h3 |k_i - k_j| + h4 (d_i + d_j) + h5 |c_i - c_j|, with i the earlier-starting interval,
// z mean depth and k depth slope (both relative to the larger mean depth, so the weights do not
// depend on the scene's scale), d durations and c colours (sum of absolute RGB differences).
struct OracleWeights {
    float gap = 20.0f, depth = 1.0f, slope = 0.25f, duration = 0.25f, color = 1.0f;  // bench/analytic_bench.py
};

float oracle(const ExposureInterval& a, const ExposureInterval& b, const OracleWeights& h);

// One interval standing for both: it covers from the earlier start to the later end (a gap
// between them is covered too: compression's error), its depth runs from the earlier one's
// start depth to the later one's end depth, and colour and opacity are duration-weighted means.
ExposureInterval mergeIntervals(const ExposureInterval& a, const ExposureInterval& b);

// Merges the pair with the lowest oracle value until at most `budget` intervals remain; every
// interval must be shaded (the oracle compares colours). Returns the number of merges.
int compressIntervals(std::vector<ExposureInterval>& intervals, int budget, const OracleWeights& h);

// Exact resolves over time, without time slices: the shutter is cut at every interval end, and
// in each piece the intervals covering it are ordered by their (linear) depth at its middle.
// Opaque: the nearest takes the piece. Translucent: each is blended front to back,
// weight += piece * T * alpha, T *= 1 - alpha. weights[i] receives interval i's share of the
// sample; the background's share is returned.
//
// exactDepth, when given, is the true depth of interval i at time t: the opaque resolve then
// also adds to *misorderedTime the covered time in which the linear depths pick a different
// nearest interval than the true depths would (the cost of the paper's linearisation), and to
// *overlapTime, when given, the time two or more intervals cover (where order matters at all).
//
// Shares are measured by the sample row's exposure (window.measure): a piece's time under a box
// shutter, its integral of the curve otherwise, 0 outside a rolling row's window.
//
// visible, when given, receives where each interval shows: the pieces it takes, joined where
// consecutive (in time order).
using ExactDepth = std::function<double(std::size_t, float)>;
float resolveOpaque(std::span<const ExposureInterval> intervals, std::span<float> weights, const ShutterWindow& window = {},
                    const ExactDepth* exactDepth = nullptr, double* misorderedTime = nullptr, double* overlapTime = nullptr,
                    std::vector<VisibleSpan>* visible = nullptr);
float resolveTranslucent(std::span<const ExposureInterval> intervals, std::span<float> weights, const ShutterWindow& window = {});

}  // namespace streak::exposure
