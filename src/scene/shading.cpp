#include "scene/shading.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace streak {

namespace {

ShadedColor albedoOf(const Material& material, const glm::vec4& texel, const glm::vec4& vertexColor) {
    return {material.baseColor * glm::vec3(texel) * glm::vec3(vertexColor), material.alphaOf(texel.w * vertexColor.w)};
}

}  // namespace

ShadedColor materialAlbedo(const Scene& scene, std::uint32_t materialIndex, const glm::vec2& uv, const TextureFootprint& footprint,
                           const glm::vec4& vertexColor) {
    const Material& material = scene.materials[materialIndex];
    glm::vec4 texel(1.0f);
    if (material.baseColorTexture >= 0) texel = scene.textures[std::size_t(material.baseColorTexture)].sample(uv, footprint);
    return albedoOf(material, texel, vertexColor);
}

ShadedColor materialAlbedoWith(const Scene& scene, std::uint32_t materialIndex, const glm::vec2& uv, const Texture::Lookup& lookup,
                           const glm::vec4& vertexColor) {
    const Material& material = scene.materials[materialIndex];
    glm::vec4 texel(1.0f);
    if (material.baseColorTexture >= 0) texel = scene.textures[std::size_t(material.baseColorTexture)].sample(uv, lookup);
    return albedoOf(material, texel, vertexColor);
}

PhongTerms phongTerms(const Scene& scene, const Material& material, const glm::vec3& position, glm::vec3 normal,
                      bool isFrontFacing, const glm::vec3& eye) {
    const DirectionalLight& light = scene.light;
    const float length = glm::length(normal);
    if (!(length > 0.0f)) return {light.ambient, glm::vec3(0.0f)};
    normal /= length;
    if (!isFrontFacing) normal = -normal;
    const float diffuse = std::max(0.0f, glm::dot(normal, light.toLight));
    PhongTerms terms{light.ambient + light.color * diffuse, glm::vec3(0.0f)};
    if (diffuse > 0.0f && material.specular > 0.0f) {
        const glm::vec3 toEye = glm::normalize(eye - position);
        const glm::vec3 reflected = glm::reflect(-light.toLight, normal);
        const float highlight = std::pow(std::max(0.0f, glm::dot(reflected, toEye)), material.shininess);
        terms.specular = light.color * (material.specular * highlight);
    }
    return terms;
}

glm::vec3 lightPhong(const Scene& scene, const Material& material, const glm::vec3& albedo,
                     const glm::vec3& position, glm::vec3 normal, bool isFrontFacing, const glm::vec3& eye) {
    const PhongTerms terms = phongTerms(scene, material, position, normal, isFrontFacing, eye);
    return albedo * terms.diffuse + terms.specular;
}

glm::vec3 shadingNormal(const SurfacePoint& point) {
    const float length = glm::length(point.normal);
    if (!(length > 0.0f)) return glm::vec3(0.0f);
    return (point.isFrontFacing ? 1.0f : -1.0f) * point.normal / length;
}

glm::vec3 vectorOf(ShadingMode mode, const SurfacePoint& point) {
    const glm::vec4& m = point.frameMotion;
    return mode == ShadingMode::VectorPrevious ? glm::vec3(m.x, m.y, 0.0f) : glm::vec3(m.z, m.w, 0.0f);
}

ShadedColor shadeSurface(const Scene& scene, ShadingMode mode, const SurfacePoint& point, const glm::vec3& eye) {
    return shadeSurfaceWithAlbedo(scene, mode, point, materialAlbedo(scene, point.material, point.uv, {point.duvdx, point.duvdy}, point.vertexColor),
                                  eye);
}

ShadedColor shadeSurfaceWithAlbedo(const Scene& scene, ShadingMode mode, const SurfacePoint& point, const ShadedColor& albedo, const glm::vec3& eye) {
    const Material& material = scene.materials[point.material];
    ShadedColor result = albedo;
    if (mode == ShadingMode::Phong)
        result.color = lightPhong(scene, material, result.color, point.position, point.normal, point.isFrontFacing, eye);
    else if (mode == ShadingMode::Normal)
        result.color = shadingNormal(point);
    else if (isVectorPass(mode))
        result.color = vectorOf(mode, point);
    return result;
}

}  // namespace streak
