#pragma once

#include "gpu/gl_object.h"
#include "scene/flat_geometry.h"
#include "scene/scene.h"
#include "scene/shading.h"

#include <map>
#include <string>
#include <vector>

namespace streak::gpu {

// SceneBuffers is a scene on the GPU, in the layout src/gpu/shaders/scene.glsl reads: the
// triangles, every mesh's key poses (so shaders evaluate a vertex at any shutter time, as
// FlatGeometry does), per-vertex uvs and colours, materials, and each texture as a GL texture
// with the scene's own box-filtered mip chain (so GL taps match Texture::sample). The camera,
// light and image size go in one uniform block. The GL context must be current.
class SceneBuffers {
public:
    // samplesWide x samplesHigh: the grid of sample positions the shaders address (the image
    // times the --aa grid N).
    SceneBuffers(const FlatGeometry& geometry, int width, int height, int aa, bool isGridPattern, ShadingMode shading);

    // Binds the buffers (SSBO 0-6), the uniform block (0) and the textures (units 0..) for a
    // program built with defines(); sets its u_textures.
    void bind(GLuint program) const;
    // MAX_TEXTURES and MAX_KEYS for buildProgram.
    const std::map<std::string, std::string>& defines() const { return m_defines; }
    std::size_t numTriangles() const { return m_numTriangles; }
    std::size_t uploadBytes() const { return m_uploadBytes; }

private:
    std::size_t m_numTriangles = 0;
    std::size_t m_uploadBytes = 0;
    std::vector<GlBuffer> m_storage;  ///< in binding order
    GlBuffer m_uniforms;
    std::vector<GlTexture> m_textures;
    GlTexture m_emptyTexture;         ///< bound to unused units
    std::map<std::string, std::string> m_defines;
};

}  // namespace streak::gpu
