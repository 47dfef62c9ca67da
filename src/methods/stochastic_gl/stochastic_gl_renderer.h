#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// Stochastic rasterization on the GPU (OpenGL 4.5, headless EGL), the twin of `stochastic`:
// every pixel sample has its own shutter time, the CPU's to the bit, in S stratified draws.
// Per draw, a geometry shader bounds each triangle's motion over the stratum with a screen
// quad (the CPU's space-time bounds), and the fragment shader tests the triangle at its
// sample's time as the CPU does (clipping, snapping, fill rule), keeps the nearest opaque hit
// through the depth test and appends translucent hits to per-sample lists, blended front to
// back in a compute pass. Same samples, tests and shading, so the two agree to rounding.
// Options: samples (S time samples per sub-pixel position, default 8); layers (translucent
// fragments blended per sample and stratum, default 64: the nearest are kept, overflow
// counted); gpu-memory (MB for translucent lists, default 1024).
std::unique_ptr<Renderer> createStochasticGlRenderer(OptionMap& options);

}  // namespace streak
