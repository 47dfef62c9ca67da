#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// Higher-order motion blur rasterization (Gribel, Munkberg, Hasselgren & Akenine-Moller 2013),
// semi-analytical, on the CPU. Vertex paths are Bezier curves of order n <= 3 in clip space
// (exposure::CurvedGeometry: Bezier keys exactly, linear keys as order 1, a moving camera
// fitted), so each edge equation at a sample is a Bernstein polynomial of degree 2n whose roots
// bound the exact time spans in which the sample is inside. Each span is an exposure interval
// with linear depth, split where linear depth strays from the true depth at mid-span (refined
// depth; a depth curve crossing its chord at mid-span is not split);
// resolve and shading are analytic's (exposure::resolveSample), the shading along the curved
// uv path.
//
// Options:
// - traversal: bbox (the box of every control point), interval (default: the boxes of
//   `intervals` equal sub-intervals of the shutter, each from its subdivided control points;
//   a sample is tested only inside one of them) or tile (the box, in blocks of `tile` pixels,
//   each culled when, on every eighth of the shutter, the Triangle-Tile test (slefes of the
//   corners' distances to the block's frustum planes) or the Edge-Tile test (slefes of the
//   padded edge equations) proves it missed). Each skips only samples the triangle never
//   covers: the spans, and so the image, are the same.
// - intervals: sub-intervals of generalized INTERVAL, 1 to 64 (8).
// - tile: TILE's block side in pixels, 1, 2 or 4 (2). Stats tiles_culled (of them
//   tiles_culled_by_triangle_test by the Triangle-Tile test alone), and
//   tile_time_culled_fraction: the share of the blocks' eighths of the shutter proved missed
//   (tile_time_culled_by_triangle_test: by the Triangle-Tile test).
// - solver: closed-form (default; Ferrari for quartics) or clipping (Bezier clipping).
// - camera-order: order of the clip-space curves fitted to a moving camera's paths (3).
// - depth-tolerance: refined depth splits an interval while its linear depth at mid-span is
//   off the true depth by more than this share of it (0.001; 0: never split).
// - max-intervals: per-sample budget, 0 (default) for unlimited (Gribel 2010's compression).
// - check-visibility: N in [1, 20000] compares, at N seeded random (sample, time) pairs, the resolved
//   nearest triangle with the one found at that exact time by brute force from the scene's
//   own poses (stats visibility_accuracy, over the pairs where either sees a triangle).
// - texture-samples, taps-per-texel: as for analytic.
std::unique_ptr<Renderer> createHigherOrderRenderer(OptionMap& options);

}  // namespace streak
