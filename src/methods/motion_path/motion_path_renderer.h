#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// Motion paths (Hong & Oh 2017), on the CPU. Each moving triangle is extruded, per linear
// segment of its motion, into a closed motion path. The paths are rasterized into per-sample
// fragment lists, and the fragments of each path are paired into time intervals. Intervals are
// sorted in depth-time and resolved with time masks. Each interval's colour is the mean of k
// texture samples along its uv path, lit with its normals.
//
// Beyond the paper:
// - Each side fragment's time is made exact by solving the moving edge's quadratic edge
//   equation at the sample (Gribel et al. 2010), and its depth, uv and normal come from the
//   triangle evaluated at that time. The paper interpolates them across the path instead.
// - Pairing is by time, not by depth.
// - K > 2 keys give one motion path per linear segment.
// - Translucency uses per-slice transmittance.
// - --aa N is supported.
//
// Options:
// - max-fragments: per sample, default 150. On overflow the nearest fragments are kept.
// - max-intervals: default 90.
// - mask-bits: 32, 64, 128 or 256; default 128.
// - texture-samples: default 16.
// - sort: 1, or 0 to skip the depth-time sort; default 1.
std::unique_ptr<Renderer> createMotionPathRenderer(OptionMap& options);

}  // namespace streak
