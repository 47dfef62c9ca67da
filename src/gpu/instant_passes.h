#pragma once

#include "gpu/gpu_frame.h"
#include "gpu/shader_library.h"
#include "gpu/translucent_resolve.h"

#include <cstddef>
#include <limits>

namespace streak::gpu {

// InstantPasses draws the scene at one shutter time on the GPU, the twin of
// exposure::InstantFrame + drawInstantTile: an opaque depth-tested pass, a pass that lists the
// translucent fragments in front of it, and the resolve that blends them front to back over the
// opaque colour and adds the result to a running sum (accumulation-gl draws S of these). The
// triangles from firstInOrderTriangle on are left out of the lists and instead blended by the
// fixed-function blender in submission order over the resolved colour in the sum, depth tested
// against the opaque surface without writing depth (blur-shell-gl: the shell as Jones draws it;
// meaningful when the sum holds one instant).
class InstantPasses {
public:
    InstantPasses(const GpuFrame& frame, const TranslucentOptions& translucent);

    // Clears the running sum (RGBA32F, one texel per sample).
    void clearSum() const;
    // Draws the scene at time t and adds it to the sum (weighted by each row's exposure of
    // rowCell when that is a stretch of the shutter: TranslucentResolve::resolve).
    void draw(float t, std::size_t firstInOrderTriangle = std::numeric_limits<std::size_t>::max(), glm::vec2 rowCell = glm::vec2(0.0f));

    const GlTexture& sum() const { return m_sum; }
    const TranslucentResolve& translucency() const { return m_translucency; }
    // Scene upload, lists and the targets.
    std::size_t gpuBytes() const;

private:
    const GpuFrame& m_frame;
    const GlProgram& m_opaque;
    const GlProgram& m_translucent;
    const GlProgram& m_blend;
    TranslucentResolve m_translucency;
    SampleFramebuffer m_target;
    GlTexture m_sum;
    GlFramebuffer m_sumTarget;  ///< the sum, with the opaque depth: where the in-order pass blends
    GlVertexArray m_vertexArray;  ///< empty: vertices are pulled from storage buffers
};

}  // namespace streak::gpu
