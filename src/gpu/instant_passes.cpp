#include "gpu/instant_passes.h"

#include "util/error.h"

#include <algorithm>
#include <map>
#include <string>

namespace streak::gpu {

namespace {

const GlProgram& instantProgram(const SceneBuffers& buffers, int translucentPass, int blendPass) {
    std::map<std::string, std::string> defines = buffers.defines();
    defines["TRANSLUCENT_PASS"] = std::to_string(translucentPass);
    defines["BLEND_PASS"] = std::to_string(blendPass);
    const ShaderStage vertex{GL_VERTEX_SHADER, {"scene.glsl", "instant.vert.glsl"}};
    if (!translucentPass)
        return buildProgram({vertex, {GL_FRAGMENT_SHADER, {"scene.glsl", "shading.glsl", "instant.frag.glsl"}}}, defines);
    defines["LIST_SKIP_HELPERS"] = "1";  // its fragment shader takes derivatives
    return buildProgram(
        {vertex, {GL_FRAGMENT_SHADER, {"scene.glsl", "shading.glsl", "fragment_list.glsl", "translucent_node.glsl", "instant.frag.glsl"}}},
        defines);
}

void setTime(const GlProgram& program, float t) { glProgramUniform1f(program.id(), glGetUniformLocation(program.id(), "u_time"), t); }

}  // namespace

InstantPasses::InstantPasses(const GpuFrame& frame, const TranslucentOptions& translucent)
    : m_frame(frame),
      m_opaque(instantProgram(frame.buffers, 0, 0)),
      m_translucent(instantProgram(frame.buffers, 1, 0)),
      m_blend(instantProgram(frame.buffers, 0, 1)),
      m_translucency(frame.grid, frame.buffers, frame.geometry, translucent),
      m_target(frame.grid),
      m_sum(GL_RGBA32F, frame.grid.samplesWide(), frame.grid.samplesHigh()) {
    glNamedFramebufferTexture(m_sumTarget.id(), GL_COLOR_ATTACHMENT0, m_sum.id(), 0);
    glNamedFramebufferTexture(m_sumTarget.id(), GL_DEPTH_ATTACHMENT, m_target.depth.id(), 0);
    if (glCheckNamedFramebufferStatus(m_sumTarget.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw RenderFailure("OpenGL: the blend target (RGBA32F sum, 32-bit float depth) is incomplete");
}

void InstantPasses::clearSum() const {
    const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(m_sum.id(), 0, GL_RGBA, GL_FLOAT, zero);
}

std::size_t InstantPasses::gpuBytes() const {
    return m_frame.buffers.uploadBytes() + m_translucency.bytes() + m_frame.grid.numSamples() * 16 * 3;
}

void InstantPasses::draw(float t, std::size_t firstInOrderTriangle, glm::vec2 rowCell) {
    const SceneBuffers& buffers = m_frame.buffers;
    const std::size_t numTriangles = buffers.numTriangles();
    const std::size_t numListed = std::min(numTriangles, firstInOrderTriangle);
    const float zero[4] = {0, 0, 0, 0};
    glBindFramebuffer(GL_FRAMEBUFFER, m_target.framebuffer.id());
    glViewport(0, 0, m_frame.grid.samplesWide(), m_frame.grid.samplesHigh());
    glBindVertexArray(m_vertexArray.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);  // single-sided triangles are culled per material in the shader
    glFrontFace(GL_CW);       // y is flipped to raster rows, which mirrors the winding
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glUseProgram(m_opaque.id());
    buffers.bind(m_opaque.id());
    setTime(m_opaque, t);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(numTriangles * 3));
    if (m_translucency.hasTranslucent() && numListed > 0) {
        m_translucency.clear();
        // The translucent pass writes only its lists: no depth, no colour (its fragment shader
        // has no output, and GL would store undefined values).
        glDepthMask(GL_FALSE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glUseProgram(m_translucent.id());
        buffers.bind(m_translucent.id());
        m_translucency.bindForAppending(m_translucent.id());
        setTime(m_translucent, t);
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(numListed * 3));
    }
    m_translucency.resolve(m_target.color, m_sum, rowCell);
    if (numListed < numTriangles) {
        // In submission order over the resolved colour: GL blends primitives in order. Coverage
        // (the sum's alpha) becomes a + (1 - a) coverage.
        glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindFramebuffer(GL_FRAMEBUFFER, m_sumTarget.id());
        glDepthMask(GL_FALSE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        glUseProgram(m_blend.id());
        buffers.bind(m_blend.id());
        setTime(m_blend, t);
        glDrawArrays(GL_TRIANGLES, GLint(numListed * 3), GLsizei((numTriangles - numListed) * 3));
        glDisable(GL_BLEND);
    }
    // Left as found: later passes of the caller write colour and depth.
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
}

}  // namespace streak::gpu
