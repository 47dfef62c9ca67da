#pragma once

#include "gpu/gl_object.h"
#include "gpu/sample_grid.h"

#include <cstdint>

namespace streak::gpu {

// FragmentLists owns the per-sample linked lists of shaders/fragment_list.glsl: the head and
// count images (one texel per sample), the node buffer and the counters (SSBO 8: asked, budget-refused, and one the method counts). A node is
// nodeBytes; the buffer holds `capacity` nodes.
class FragmentLists {
public:
    FragmentLists(const SampleGrid& grid, std::size_t nodeBytes, std::size_t capacity);

    // Empties every list and zeroes the counters (before each pass that fills them).
    void clear() const;
    // Binds images 0-1, the counters (SSBO 8), the node buffer as SSBO `nodeBinding`, and
    // sets the program's u_listCapacity and u_sampleBudget.
    void bind(GLuint program, GLuint nodeBinding, std::uint32_t sampleBudget) const;
    // Images and the node buffer only, for a pass that reads the lists.
    void bindForReading(GLuint nodeBinding) const;

    struct Counts {
        std::uint64_t asked = 0;          ///< nodes the pass asked for
        std::uint64_t budgetRefused = 0;  ///< refused by the per-sample budget
        std::uint64_t methodCounter = 0;  ///< listMethodCounter: the method's own
        bool isOverflowing(std::size_t capacity) const { return asked > capacity; }
    };
    Counts counts() const;

    std::size_t capacity() const { return m_capacity; }
    std::size_t nodeBytes() const { return m_nodeBytes; }
    std::size_t bytes() const { return m_nodes.size() + m_heads.width() * std::size_t(m_heads.height()) * 8; }

private:
    std::size_t m_nodeBytes, m_capacity;
    GlTexture m_heads, m_counts;
    GlBuffer m_counters;
    GlBuffer m_nodes;
};

}  // namespace streak::gpu
