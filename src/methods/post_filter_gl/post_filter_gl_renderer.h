#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// post-filter on the GPU (OpenGL 4.5): the centre frame by gpu::InstantPasses, a velocity pass
// (each fragment's clip positions at shutter open and close), then compute passes for the
// per-pixel resolve, TileMax, NeighborMax and the gather (exposure/reconstruction_filter's,
// with the CPU's per-pixel jitter). The same options and, on the grid, the same images as
// post-filter.
std::unique_ptr<Renderer> createPostFilterGlRenderer(OptionMap& options);

}  // namespace streak
