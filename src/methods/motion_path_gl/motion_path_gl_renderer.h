#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// Motion paths (Hong & Oh 2017) on the graphics pipeline: OpenGL 4.5 core through headless EGL.
// The GPU twin of `motion-path`: same paths, intervals, sort, masks and span shading, so the
// two agree.
//
// Pass 1 (rasterize paths), one draw per linear segment: the vertex shader evaluates each
// vertex's key poses at both ends of the segment and transforms them; the geometry shader
// emits the triangle's motion path (the convex hull of its six projected corners, as on the
// CPU; a full-screen quad for a path reaching behind the eye; nothing for a single-sided
// triangle facing away throughout); the fragment shader solves the three edge quadratics at
// its sample (double precision) and appends each exact inside span, with its depth at both
// ends, to the sample's linked list (r32ui head image, node SSBO, atomic counter).
// Pass 2 (resolve), a compute shader per sample: gathers the nearest max-intervals intervals,
// shades translucent ones, sorts in depth-time (crossing splits, Hong & Oh's four tests),
// resolves with n-bit time masks (per-slice transmittance when translucent) and shades only
// the visible pieces: texture taps along the exact uv path with the CPU's mip level choice,
// GL textures with the scene's own mip chain.
//
// Overflow: the node buffer starts small; when a frame asks for more nodes than it holds, the
// frame is rendered again with a buffer large enough, up to gpu-memory MB. Past that cap the
// per-sample budget shrinks so the buffer cannot overflow, and the refused spans are counted.
//
// Options: max-fragments (spans per sample, 150), max-intervals (90), mask-bits (32, 64, 128,
// 256; 128), texture-samples (32), taps-per-texel (2), sort (1), curve-segments (4), gpu-memory
// (MB for the lists, 1024).
std::unique_ptr<Renderer> createMotionPathGlRenderer(OptionMap& options);

}  // namespace streak
