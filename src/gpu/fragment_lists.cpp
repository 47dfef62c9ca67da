#include "gpu/fragment_lists.h"

#include <array>

namespace streak::gpu {

FragmentLists::FragmentLists(const SampleGrid& grid, std::size_t nodeBytes, std::size_t capacity)
    : m_nodeBytes(nodeBytes), m_capacity(capacity), m_heads(GL_R32UI, grid.samplesWide(), grid.samplesHigh()),
      m_counts(GL_R32UI, grid.samplesWide(), grid.samplesHigh()), m_counters(4 * sizeof(std::uint32_t)),
      m_nodes(nodeBytes * capacity, nullptr, 0) {}

void FragmentLists::clear() const {
    const GLuint empty = 0xffffffffu, zero = 0u;
    glClearTexImage(m_heads.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
    glClearTexImage(m_counts.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    const std::array<std::uint32_t, 4> counters{};
    m_counters.upload(counters.data(), sizeof counters);
}

void FragmentLists::bindForReading(GLuint nodeBinding) const {
    glBindImageTexture(0, m_heads.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(1, m_counts.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    m_nodes.bindStorage(nodeBinding);
}

void FragmentLists::bind(GLuint program, GLuint nodeBinding, std::uint32_t sampleBudget) const {
    bindForReading(nodeBinding);
    m_counters.bindStorage(8);
    glProgramUniform1ui(program, glGetUniformLocation(program, "u_listCapacity"), GLuint(m_capacity));
    glProgramUniform1ui(program, glGetUniformLocation(program, "u_sampleBudget"), sampleBudget);
}

FragmentLists::Counts FragmentLists::counts() const {
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::array<std::uint32_t, 4> values{};
    m_counters.download(values.data(), sizeof values);
    return {values[0], values[1], values[2]};
}

}  // namespace streak::gpu
