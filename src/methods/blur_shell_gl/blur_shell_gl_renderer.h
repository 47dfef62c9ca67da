#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// blur-shell on the GPU (OpenGL 4.5, headless EGL): the shell is built on the CPU (the thesis'
// split; the SoM updates are a small share of the frame, bench/blur_shell_bench.py), uploaded
// with the scene at T, and drawn by gpu::InstantPasses: the mesh opaque, then the shell blended
// in submission order by the fixed-function blender (blend=ordered) or listed with the
// translucent surfaces and blended front to back per sample (blend=sorted). Same options and
// counters as blur-shell, plus layers and gpu-memory for the translucent lists.
std::unique_ptr<Renderer> createBlurShellGlRenderer(OptionMap& options);

}  // namespace streak
