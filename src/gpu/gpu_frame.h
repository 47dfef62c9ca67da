#pragma once

#include "gpu/gl_context.h"
#include "gpu/gl_object.h"
#include "gpu/sample_grid.h"
#include "gpu/scene_buffers.h"
#include "scene/flat_geometry.h"
#include "scene/shading.h"
#include "util/stats.h"

namespace streak::gpu {

// GpuFrame is what every GL method sets up before its passes: the shared context, current on
// this thread; the scene flattened and uploaded (the "upload" phase); the grid of sample
// texels; and the GL renderer and version in the stats.
struct GpuFrame {
    GpuFrame(const Scene& scene, int width, int height, int aa, bool isGridPattern, ShadingMode shading, RenderStats& stats);

    GlContext& gl;
    FlatGeometry geometry;
    SampleGrid grid;
    SceneBuffers buffers;
};

// SampleFramebuffer is a framebuffer of one texel per sample: RGBA32F colour (the GL methods
// keep rgb and 1/w of the nearest opaque surface there) and 32-bit float depth.
struct SampleFramebuffer {
    explicit SampleFramebuffer(const SampleGrid& grid);

    GlTexture color, depth;
    GlFramebuffer framebuffer;
};

}  // namespace streak::gpu
