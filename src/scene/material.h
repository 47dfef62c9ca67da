#pragma once

#include <glm/vec3.hpp>

#include <string>

namespace streak {

// Material is what a surface looks like, constant over the shutter. Colours are linear.
struct Material {
    std::string name;
    glm::vec3 baseColor{1.0f};   ///< multiplies the texture
    int baseColorTexture = -1;   ///< index into Scene::textures, or -1
    float opacity = 1.0f;        ///< 1 = opaque; below 1 the surface is blended (times texture alpha)
    bool doubleSided = false;    ///< false: back faces are culled, as in glTF
    float specular = 0.2f;       ///< Phong specular weight
    float shininess = 32.0f;     ///< Phong exponent

    bool isTranslucent() const { return opacity < 1.0f; }
};

}  // namespace streak
