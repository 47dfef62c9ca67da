// Per-sample linked lists (Yang et al. 2010): a head index per sample texel, nodes in one
// storage buffer shared by all samples, allocated with an atomic counter. Bounded twice: the
// buffer's capacity (u_listCapacity nodes) and a per-sample budget (u_sampleBudget); a node
// refused by either is counted, never written out of bounds.

layout(r32ui, binding = 0) uniform coherent uimage2D u_heads;    // 0xffffffff: empty
layout(r32ui, binding = 1) uniform coherent uimage2D u_counts;   // nodes per sample, refused ones included
layout(std430, binding = 8) coherent buffer ListCounterBuffer {
    uint listAllocated;      // nodes asked for (may exceed capacity)
    uint listBudgetRefused;  // nodes over a sample's budget
    uint listMethodCounter;  // the method's own count
};
uniform uint u_listCapacity;
uniform uint u_sampleBudget;

const uint kEndOfList = 0xffffffffu;

// Reserves a node for sample s; false when the sample's budget or the buffer is exhausted.
// On success the caller writes node `index` with `next` as its successor.
bool appendNode(ivec2 s, out uint index, out uint next) {
#if defined(LIST_SKIP_HELPERS) && defined(STAGE_FRAGMENT)
    // Helper invocations (kept alive for derivatives) must append nothing. Only for shaders
    // that take derivatives: llvmpipe flags some real fragments as helpers too.
    if (gl_HelperInvocation) return false;
#endif
    if (imageAtomicAdd(u_counts, s, 1u) >= u_sampleBudget) {
        atomicAdd(listBudgetRefused, 1u);
        return false;
    }
    index = atomicAdd(listAllocated, 1u);
    if (index >= u_listCapacity) return false;
    next = imageAtomicExchange(u_heads, s, index);
    return true;
}
