#pragma once

#include "exposure/visible_pieces.h"
#include "methods/motion_path/interval.h"
#include "scene/shutter.h"

#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace streak::motion_path {

// How much each interval of a pixel sample shows over the shutter, from its intervals sorted
// front to back (Hong & Oh 2017, section 3.4), with numBits time slices. The sample's colour is
// sum(weights[i] * colour[i]) + returned * background, so colours are needed only where a
// weight is non-zero: the renderer shades visible intervals alone.
//
// Opaque intervals: visible = current & ~accumulated; weight = |visible| / n; accumulated |=
// current; stop when full; the background gets the slices nothing covers. When some interval is
// translucent, each slice keeps a transmittance instead of a bit (beyond the paper): weight =
// alpha * sum(T) / n over its slices, then T *= 1 - alpha. Opacity must be known up front.
// `weights` has one entry per interval. Returns the background's weight.
//
// OpaqueWeights::Exact (beyond the paper) measures opaque intervals in time instead of in
// slices: each shows its span minus the union of the spans before it, which the depth-time
// sort has put in front. Masks quantise each visible piece to whole slices (error up to 1/n per
// piece); exact weights have none, at the cost of a short list of time spans per sample.
//
// Under a shutter curve or a rolling row (`window`) the slices are slices of the row's exposure
// (TimeMask::exposed) and exact weights its measure of the spans: each still sums to 1.
enum class OpaqueWeights { Slices, Exact };
float resolveWeights(std::span<const Interval> sorted, int numBits, std::span<float> weights,
                     OpaqueWeights opaque = OpaqueWeights::Slices, const ShutterWindow& window = {});

// True when some interval is translucent (alpha < 1): resolveWeights then keeps a transmittance
// per slice, whatever the opaque weights.
bool hasTranslucentInterval(std::span<const Interval> sorted);

// resolveWeights(sorted, -, weights, OpaqueWeights::Exact, window) for a list of opaque
// intervals, also appending where each shows to `visible` (in list order): its span minus the
// union of the spans before it, as disjoint time spans in time order, each with its exposure.
float resolveOpaqueSpans(std::span<const Interval> sorted, std::span<float> weights, const ShutterWindow& window,
                         std::vector<exposure::VisibleSpan>& visible);

// The resolved colour, from the intervals' own colours.
glm::vec3 resolveIntervals(std::span<const Interval> sorted, int numBits, const glm::vec3& background,
                           OpaqueWeights opaque = OpaqueWeights::Slices, const ShutterWindow& window = {});

}  // namespace streak::motion_path
