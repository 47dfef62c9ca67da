#pragma once

#include "scene/camera.h"
#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/shutter.h"
#include "scene/texture.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace streak {

// One directional light plus ambient: the lighting of the papers' Phong-shaded results.
struct DirectionalLight {
    glm::vec3 toLight{0.0f, 0.0f, 1.0f};  ///< unit vector from the surface towards the light
    glm::vec3 color{0.85f};               ///< linear radiance scale
    glm::vec3 ambient{0.2f};              ///< added to the diffuse term, times albedo
};

// Scene is everything a renderer needs for one frame: moving meshes, materials, textures, a
// possibly moving camera, a light, a background and the shutter. Meshes reference materials and materials
// reference textures by index; validateScene() checks those indices.
struct Scene {
    std::string name;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    Camera camera;
    DirectionalLight light;
    glm::vec3 background{0.0f};  ///< linear colour of pixels (and time spans) nothing covers
    Shutter shutter;             ///< how [0, 1] is exposed: box, global by default

    std::size_t numTriangles() const;
    bool hasTranslucency() const;
};

// What cleaning a scene removed: triangles with a NaN/Inf position in any key, and triangles
// that have zero area in every key. Renderers never see either; stats report both.
struct SceneCleanup {
    std::size_t numNonFinite = 0;
    std::size_t numDegenerate = 0;
    std::size_t numSkipped() const { return numNonFinite + numDegenerate; }
};

// Checks the structure (key counts, array sizes, vertex, material and texture indices) and
// throws Error naming the mesh and field on the first inconsistency; then drops invalid
// triangles (counted, not thrown) and empty meshes.
SceneCleanup validateScene(Scene& scene);

}  // namespace streak
