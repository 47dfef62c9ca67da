#pragma once

#include "scene/scene.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>

namespace streak {

enum class ShadingMode : std::uint8_t {
    Unlit,   ///< base colour times texture: the time-averaged albedo
    Phong,   ///< one directional light plus ambient, as in the papers
    Normal,  ///< the unit world-space normal as the colour (the normal pass), with Unlit's alpha; GL: shading.glsl's isNormalPass
    // The vector pass: the point's screen motion (NDC, SurfacePoint::frameMotion) from the frame
    // to the frame before (x, y) or from the frame after to the frame (x, y), as the colour,
    // with Unlit's alpha. CPU methods only (Scene::frameMotion).
    VectorPrevious,
    VectorNext,
};

inline bool isVectorPass(ShadingMode mode) { return mode == ShadingMode::VectorPrevious || mode == ShadingMode::VectorNext; }

// SurfacePoint is what a renderer knows about a visible point at one time: enough to shade it.
struct SurfacePoint {
    glm::vec3 position{0.0f};  ///< world space
    glm::vec3 normal{0.0f};    ///< world space, any length; geometric normal if the mesh has none
    glm::vec2 uv{0.0f};
    glm::vec2 duvdx{0.0f};     ///< uv change over one sample spacing to the right (texture footprint)
    glm::vec2 duvdy{0.0f};     ///< uv change over one sample spacing down
    glm::vec4 vertexColor{1.0f}; ///< interpolated linear vertex colour; multiplies albedo and alpha
    std::uint32_t material = 0;
    bool isFrontFacing = true; ///< back faces of double-sided materials are lit from their side
    // With Scene::frameMotion: the NDC motion of this point of the surface (its barycentrics)
    // from its place at frame F to F - 1 (x, y), and from F + 1 to F (z, w), as Cycles writes
    // the Vector pass (pre - centre, centre - post); 0 without, or behind a frame's camera.
    glm::vec4 frameMotion{0.0f};
};

struct ShadedColor {
    glm::vec3 color{0.0f};  ///< linear, not premultiplied
    float alpha = 1.0f;     ///< Material::alphaOf(texture alpha times vertex alpha): 1 when opaque
};

// The unit normal a point is shaded with, turned towards the viewer on a back face (as Phong
// lights it); 0 for a degenerate normal. The normal pass's value.
glm::vec3 shadingNormal(const SurfacePoint& point);

// The vector pass's colour of a point: its frameMotion's half for the mode, z 0.
glm::vec3 vectorOf(ShadingMode mode, const SurfacePoint& point);

// The one shading function every CPU method calls, so methods differ only in visibility.
ShadedColor shadeSurface(const Scene& scene, ShadingMode mode, const SurfacePoint& point, const glm::vec3& eye);
// The same with the point's albedo and alpha (materialAlbedo) given: where a shading filters
// the texture itself (a still point's samples' lookups, exposure/span_shading.cpp).
ShadedColor shadeSurfaceWithAlbedo(const Scene& scene, ShadingMode mode, const SurfacePoint& point, const ShadedColor& albedo, const glm::vec3& eye);

// Albedo and alpha only (base colour times texture times vertex colour), the texture filtered
// over an explicit footprint (default: a level-0 tap). A Mask material's alpha is already cut
// to 0 or 1 here, so averages of it are coverage.
ShadedColor materialAlbedo(const Scene& scene, std::uint32_t material, const glm::vec2& uv, const TextureFootprint& footprint = {},
                           const glm::vec4& vertexColor = glm::vec4(1.0f));
// The same with the lookup of the material's texture planned already (Texture::lookupOf of the
// footprint), for points that share one footprint.
ShadedColor materialAlbedoWith(const Scene& scene, std::uint32_t material, const glm::vec2& uv, const Texture::Lookup& lookup,
                               const glm::vec4& vertexColor);

// Phong lighting split by what multiplies the albedo: colour = albedo * diffuse + specular.
// Methods that average lighting and texture at different rates combine the two themselves.
struct PhongTerms {
    glm::vec3 diffuse{0.0f};   ///< ambient plus diffuse, times the albedo
    glm::vec3 specular{0.0f};  ///< added as is
};
PhongTerms phongTerms(const Scene& scene, const Material& material, const glm::vec3& position, glm::vec3 normal,
                      bool isFrontFacing, const glm::vec3& eye);

// Phong lighting of an albedo at a point; normal need not be unit length.
glm::vec3 lightPhong(const Scene& scene, const Material& material, const glm::vec3& albedo,
                     const glm::vec3& position, glm::vec3 normal, bool isFrontFacing, const glm::vec3& eye);

}  // namespace streak
