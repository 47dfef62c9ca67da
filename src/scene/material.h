#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>

namespace streak {

// What a surface point's own alpha (texture alpha times vertex-colour alpha) does: the glTF
// alpha modes.
enum class AlphaMode : std::uint8_t {
    Opaque,  ///< the point's alpha is ignored
    Mask,    ///< opaque where opacity times the point's alpha >= alphaCutoff, else invisible
    Blend,   ///< opacity times the point's alpha blends over what is behind
};

// Material is what a surface looks like, constant over the shutter. Colours are linear.
struct Material {
    std::string name;
    glm::vec3 baseColor{1.0f};   ///< multiplies the texture and the vertex colour
    int baseColorTexture = -1;   ///< index into Scene::textures, or -1
    float opacity = 1.0f;        ///< 1 = opaque; below 1 the surface is blended in every alpha mode
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;    ///< Mask only, in [0, 1]
    bool doubleSided = false;    ///< false: back faces are culled, as in glTF
    float specular = 0.2f;       ///< Phong specular weight
    float shininess = 32.0f;     ///< Phong exponent

    // Mask and Blend go through every method's translucent path: a Mask point's alpha is 0 or
    // 1 per sample, and averaging those over time or texture samples gives partial coverage.
    bool isTranslucent() const { return alphaMode != AlphaMode::Opaque || opacity < 1.0f; }

    // The alpha a point gets whose texture alpha times vertex alpha is `pointAlpha`.
    float alphaOf(float pointAlpha) const {
        switch (alphaMode) {
        case AlphaMode::Mask: return opacity * pointAlpha >= alphaCutoff ? 1.0f : 0.0f;
        case AlphaMode::Blend: return opacity * pointAlpha;
        case AlphaMode::Opaque:
        default: return opacity;
        }
    }
};

}  // namespace streak
