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
// masks. An interval's colour is the mean of k texture samples along it (section 4.4), lit by
// Simpson's rule over its normals.
//
// Beyond the paper:
// - The sides are conservative convex hulls rather than bilinear fans, so folding sides (fast
//   rotation) lose no coverage.
// - Interval times, depths, uvs and normals are exact.
// - uv paths that bend are sampled at exact times, and slow intervals take fewer texture
//   samples.
// - Single-sided triangles that face away for a whole segment are culled through a Bernstein
//   bound on their orientation.
// - K > 2 keys give one path per key segment; Bezier keys and a moving camera give four per key
//   segment.
// - Translucency uses per-slice transmittance.
// - --aa N is supported.
//
// Options:
// - max-fragments: paths per sample, default 150. On overflow the nearest are kept.
// - max-intervals: default 90. On overflow the nearest are kept.
// - mask-bits: 32, 64, 128 or 256; default 128.
// - texture-samples: at most k, default 16.
// - sort: 1, or 0 for minimum-depth order only; default 1.
std::unique_ptr<Renderer> createMotionPathRenderer(OptionMap& options);

}  // namespace streak
