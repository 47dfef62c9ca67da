#include "gpu/gpu_frame.h"

#include "util/error.h"

namespace streak::gpu {

namespace {

SceneBuffers upload(const FlatGeometry& geometry, int width, int height, int aa, bool isGridPattern, ShadingMode shading, RenderStats& stats) {
    PhaseTimer timer(stats, "upload");
    return SceneBuffers(geometry, width, height, aa, isGridPattern, shading);
}

}  // namespace

GpuFrame::GpuFrame(const Scene& scene, int width, int height, int aa, bool isGridPattern, ShadingMode shading, RenderStats& stats)
    : gl(sharedContext()), geometry(scene), grid{width, height, aa}, buffers(upload(geometry, width, height, aa, isGridPattern, shading, stats)) {
    stats.setInfo("gl_renderer", gl.renderer());
    stats.setInfo("gl_version", gl.version());
}

SampleFramebuffer::SampleFramebuffer(const SampleGrid& grid)
    : color(GL_RGBA32F, grid.samplesWide(), grid.samplesHigh()), depth(GL_DEPTH_COMPONENT32F, grid.samplesWide(), grid.samplesHigh()) {
    glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
    glNamedFramebufferTexture(framebuffer.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    if (glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw RenderFailure("OpenGL: a sample framebuffer (RGBA32F colour, 32-bit float depth) is incomplete");
}

}  // namespace streak::gpu
