#include "gpu/translucent_resolve.h"

#include "gpu/shader_library.h"

#include <algorithm>
#include <map>
#include <string>

namespace streak::gpu {

namespace {

constexpr std::size_t kNodeBytes = 32;  // TranslucentNode, std430
constexpr GLuint kNodeBinding = 7;      // translucent_node.glsl

// A sample holds at most `layers` fragments that matter, and the buffer at most gpu-memory.
std::size_t listCapacity(const SampleGrid& grid, bool hasTranslucent, int layers, int gpuMemoryMb) {
    if (!hasTranslucent) return 1;
    return std::max<std::size_t>(1, std::min(grid.numSamples() * std::size_t(layers), std::size_t(gpuMemoryMb) * (1u << 20) / kNodeBytes));
}

bool hasTranslucentMaterial(const FlatGeometry& geometry) {
    for (const FlatTriangle& tri : geometry.triangles())
        if (geometry.scene().materials[tri.material].isTranslucent()) return true;
    return false;
}

}  // namespace

TranslucentOptions TranslucentOptions::read(OptionMap& options) {
    TranslucentOptions o;
    o.layers = options.getInt("layers", o.layers, 1, 256);
    o.gpuMemoryMb = options.getInt("gpu-memory", o.gpuMemoryMb, 1, 1 << 20);
    return o;
}

TranslucentResolve::TranslucentResolve(const SampleGrid& grid, const SceneBuffers& buffers, const FlatGeometry& geometry,
                                       const TranslucentOptions& options)
    : m_grid(grid), m_buffers(buffers), m_hasTranslucent(hasTranslucentMaterial(geometry)),
      m_sampleBudget(std::uint32_t(options.layers) * 4u),
      m_lists(grid, kNodeBytes, listCapacity(grid, m_hasTranslucent, options.layers, options.gpuMemoryMb)) {
    std::map<std::string, std::string> defines = buffers.defines();
    defines["MAX_LAYERS"] = std::to_string(options.layers);
    m_program = &buildProgram(
        {{GL_COMPUTE_SHADER, {"scene.glsl", "fragment_list.glsl", "translucent_node.glsl", "translucent_resolve.comp.glsl"}}}, defines);
    m_lists.clear();
}

void TranslucentResolve::bindForAppending(GLuint program) const { m_lists.bind(program, kNodeBinding, m_sampleBudget); }

void TranslucentResolve::resolve(const GlTexture& opaque, const GlTexture& sum, glm::vec2 rowCell) {
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                    GL_ATOMIC_COUNTER_BARRIER_BIT);
    glUseProgram(m_program->id());
    m_buffers.bind(m_program->id());
    m_lists.bind(m_program->id(), kNodeBinding, m_sampleBudget);
    glProgramUniform2f(m_program->id(), glGetUniformLocation(m_program->id(), "u_rowCell"), rowCell.x, rowCell.y);
    glBindImageTexture(2, opaque.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(3, sum.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glDispatchCompute(GLuint((m_grid.samplesWide() + 7) / 8), GLuint((m_grid.samplesHigh() + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    if (!m_hasTranslucent) return;
    const FragmentLists::Counts counts = m_lists.counts();
    m_overflowSamples += counts.methodCounter;
    m_listOverflow += counts.asked > m_lists.capacity() ? counts.asked - m_lists.capacity() : 0;
    m_listOverflow += counts.budgetRefused;
}

void TranslucentResolve::report(RenderStats& stats) const {
    stats.setCounter("translucent_layer_overflow_samples", double(m_overflowSamples));
    stats.setCounter("translucent_list_overflow_fragments", double(m_listOverflow));
}

}  // namespace streak::gpu
