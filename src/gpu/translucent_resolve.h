#pragma once

#include "gpu/fragment_lists.h"
#include "gpu/gl_object.h"
#include "gpu/sample_grid.h"
#include "gpu/scene_buffers.h"
#include "scene/flat_geometry.h"
#include "util/options.h"
#include "util/stats.h"

#include <cstdint>

namespace streak::gpu {

// The translucency options of the GL methods: layers (fragments blended per sample and pass,
// default 64: the nearest are kept, overflow counted) and gpu-memory (MB for the lists,
// default 1024).
struct TranslucentOptions {
    int layers = 64;
    int gpuMemoryMb = 1024;
    static TranslucentOptions read(OptionMap& options);
};

// TranslucentResolve is translucency for the GL methods, the twin of raster/translucency.cpp:
// per-sample lists that a pass fills with shaded fragments (shaders/translucent_node.glsl
// appended through fragment_list.glsl), and a compute pass that blends each sample's nearest
// `layers` fragments front to back over its opaque colour and adds the result to a running
// sum. The lists hold one pass: at most 4 x layers nodes per sample and gpu-memory MB in all;
// what does not fit is counted (report), never written out of bounds.
class TranslucentResolve {
public:
    // Without translucent materials in `geometry` the lists get one node, and resolve() only
    // adds the opaque colour (or the background) to the sum.
    TranslucentResolve(const SampleGrid& grid, const SceneBuffers& buffers, const FlatGeometry& geometry,
                       const TranslucentOptions& options);

    bool hasTranslucent() const { return m_hasTranslucent; }

    // Empties the lists, before each pass that appends to them.
    void clear() const { m_lists.clear(); }
    // Binds the lists for `program`, which appends TranslucentNodes.
    void bindForAppending(GLuint program) const;
    // Blends over `opaque` (rgb, 1/w; w = 0 where no opaque surface: the background) and adds
    // to `sum`, both RGBA32F sample textures; counts overflow when the scene has translucency.
    // A rowCell [c0, c1] with c1 > c0 weighs the addition in each row by the row's exposure of
    // that stretch of the shutter (a rolling shutter's accumulation, exposure::InstantSchedule).
    void resolve(const GlTexture& opaque, const GlTexture& sum, glm::vec2 rowCell = glm::vec2(0.0f));
    // translucent_layer_overflow_samples and translucent_list_overflow_fragments.
    void report(RenderStats& stats) const;

    std::size_t bytes() const { return m_lists.bytes(); }

private:
    SampleGrid m_grid;
    const SceneBuffers& m_buffers;
    bool m_hasTranslucent;
    std::uint32_t m_sampleBudget;
    FragmentLists m_lists;
    const GlProgram* m_program = nullptr;
    std::uint64_t m_overflowSamples = 0, m_listOverflow = 0;
};

}  // namespace streak::gpu
