#include "scene/shading.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace streak {

ShadedColor materialAlbedo(const Scene& scene, std::uint32_t materialIndex, const glm::vec2& uv, float lod) {
    const Material& material = scene.materials[materialIndex];
    ShadedColor result{material.baseColor, 1.0f};
    float textureAlpha = 1.0f;
    if (material.baseColorTexture >= 0) {
        const glm::vec4 texel = scene.textures[std::size_t(material.baseColorTexture)].sample(uv, lod);
        result.color *= glm::vec3(texel);
        textureAlpha = texel.w;
    }
    if (material.isTranslucent()) result.alpha = material.opacity * textureAlpha;
    return result;
}

glm::vec3 lightPhong(const Scene& scene, const Material& material, const glm::vec3& albedo,
                     const glm::vec3& position, glm::vec3 normal, bool isFrontFacing, const glm::vec3& eye) {
    const float length = glm::length(normal);
    if (!(length > 0.0f)) return albedo * scene.light.ambient;
    normal /= length;
    if (!isFrontFacing) normal = -normal;
    const DirectionalLight& light = scene.light;
    const float diffuse = std::max(0.0f, glm::dot(normal, light.toLight));
    glm::vec3 color = albedo * (light.ambient + light.color * diffuse);
    if (diffuse > 0.0f && material.specular > 0.0f) {
        const glm::vec3 toEye = glm::normalize(eye - position);
        const glm::vec3 reflected = glm::reflect(-light.toLight, normal);
        const float highlight = std::pow(std::max(0.0f, glm::dot(reflected, toEye)), material.shininess);
        color += light.color * (material.specular * highlight);
    }
    return color;
}

ShadedColor shadeSurface(const Scene& scene, ShadingMode mode, const SurfacePoint& point, const glm::vec3& eye) {
    const Material& material = scene.materials[point.material];
    float lod = 0.0f;
    if (material.baseColorTexture >= 0)
        lod = scene.textures[std::size_t(material.baseColorTexture)].lodFromFootprint(point.duvdx, point.duvdy);
    ShadedColor result = materialAlbedo(scene, point.material, point.uv, lod);
    if (mode == ShadingMode::Phong)
        result.color = lightPhong(scene, material, result.color, point.position, point.normal, point.isFrontFacing, eye);
    return result;
}

}  // namespace streak
