#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// The accumulation buffer on the GPU (OpenGL 4.5, headless EGL): S depth-tested passes of the
// whole scene at the CPU accumulation's times t_s = (s + 1/2) / S, averaged. Each pass shades
// opaque fragments in the fragment shader, appends translucent ones to per-sample lists, and a
// compute pass blends those front to back over the opaque surface into a running sum. The
// GPU twin of `accumulation`: same times, shading and blending, so the two agree.
// Options: samples (S, default 256); layers (translucent fragments blended per sample and
// pass, default 64: the nearest are kept, overflow counted); gpu-memory (MB for translucent
// lists, default 1024).
std::unique_ptr<Renderer> createAccumulationGlRenderer(OptionMap& options);

}  // namespace streak
