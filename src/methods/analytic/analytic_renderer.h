#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// Analytic motion blur rasterization (Gribel, Doggett & Akenine-Moller 2010), on the CPU. Every
// triangle, per linear segment of its motion, visits the samples in its screen box over the
// segment (tiles it provably misses over the whole segment are culled against its moving edges)
// and solves its three time-dependent edge equations there: the exact time spans in which the
// sample is inside. Each span is an interval with linear depth between its ends. A sample's
// intervals are resolved exactly over time, without time slices: opaque, the nearest interval
// wins every instant; translucent, every instant is blended front to back. Only what shows is
// shaded (texture and lighting averaged over the span, shared with motion-path).
//
// Options:
// - max-intervals: per-sample budget K, 0 (default) for unlimited. Over budget, the pair with
//   the lowest oracle value is merged until K remain (Gribel's compression).
// - oracle-weights: h1,h2,h3,h4,h5 of the oracle (gap, depth, slope, duration, colour).
// - tile-cull: 1 (default) or 0.
// - check-depth-order: 1 to measure how often the linear depths order overlapping intervals
//   differently from the true depths (stats depth_misordered_fraction).
// - texture-samples, taps-per-texel, curve-segments: as for motion-path.
std::unique_ptr<Renderer> createAnalyticRenderer(OptionMap& options);

}  // namespace streak
