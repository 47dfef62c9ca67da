#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// Motion paths (Hong & Oh 2017), on the CPU. For each linear segment of its motion, every
// moving triangle becomes a motion path: the screen region it sweeps, as triangles (motion_path.h).
// The paths are rasterized with the shared rasterizer into per-sample lists. Each listed path
// yields the exact time spans in which the sample lies inside its triangle; these are solved
// from the three moving edge equations (Gribel et al. 2010), with no pairing of approximate
// fragments. Each span becomes an interval whose depth is taken at its ends. Intervals are
// sorted in depth-time (split at crossings, then Hong & Oh's four tests) and resolved with time
// masks; only the visible ones are then shaded, with the texture averaged along the interval
// (section 4.4) and the lighting averaged over it (exposure/span_shading.h).
//
// Beyond the paper:
// - The sides are conservative convex hulls rather than bilinear fans, so folding sides (fast
//   rotation) lose no coverage.
// - Interval times, depths, uvs and normals are exact; texture taps sit at exact times, as
//   many as the pixel footprint's mip level needs (at most k), and lighting follows turning
//   normals.
// - Shading is deferred to the visible pieces; abutting whole pieces of one triangle are shaded
//   once.
// - Single-sided triangles that face away for a whole segment are culled through a Bernstein
//   bound on their orientation.
// - K > 2 keys give one path per key segment; Bezier keys and a moving camera give
//   curve-segments per key segment.
// - Translucency uses per-slice transmittance.
// - --aa N is supported.
//
// Options:
// - max-fragments: paths per sample, default 4096 (the paper's GPU budget: 150). On overflow the
//   nearest are kept, and the samples counted.
// - max-intervals: default 2048 (the paper's: 90). On overflow the nearest are kept.
// - mask-bits: 32, 64, 128 or 256; default 128. With exact weights (the default) they time
//   translucent samples only.
// - exact-weights: 1 (default) measures each visible opaque piece in time; 0 counts mask slices
//   as the paper does (error up to 1/mask-bits per piece).
// - texture-samples: at most k texture taps per interval, default 32.
// - taps-per-texel: texture taps per texel of the footprint's mip level, default 2.
// - sort: 1, or 0 for minimum-depth order only; default 1.
// - curve-segments: linear pieces per key segment of curved screen motion, default 4.
std::unique_ptr<Renderer> createMotionPathRenderer(OptionMap& options);

}  // namespace streak
