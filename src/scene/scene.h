#pragma once

#include "scene/camera.h"
#include "scene/material.h"
#include "scene/mesh.h"
#include "scene/shutter.h"
#include "scene/texture.h"

#include <glm/vec3.hpp>

#include <glm/mat4x4.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace streak {

// One directional light plus ambient: the lighting of the papers' Phong-shaded results.
struct DirectionalLight {
    glm::vec3 toLight{0.0f, 0.0f, 1.0f};  ///< unit vector from the surface towards the light
    glm::vec3 color{0.85f};               ///< linear radiance scale
    glm::vec3 ambient{0.2f};              ///< added to the diffuse term, times albedo
};

// How the surfaces move across frames, for the vector pass (Blender's Vector): with each
// mesh's Mesh::framePositions at the frames F - 1, F and F + 1 around the frame F the shutter
// sits at, the projection of each frame's camera. Only a scene with a clock has it (glTF, OBJ
// and PLY), and only the vector pass's renders.
struct FrameMotion {
    std::array<glm::mat4, 3> clipFromWorld;  ///< at F - 1, F, F + 1, for the image's aspect
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
    std::optional<FrameMotion> frameMotion;

    std::size_t numTriangles() const;
    bool hasTranslucency() const;
};

// What cleaning a scene removed: triangles with a NaN/Inf position in any key, and triangles
// that have zero area in every key. Renderers never see either; stats report both.
struct SceneCleanup {
    std::size_t numNonFinite = 0;
    std::size_t numDegenerate = 0;
    std::vector<std::size_t> keptMeshes;  ///< each kept mesh's index among the meshes given, in order
    std::size_t numSkipped() const { return numNonFinite + numDegenerate; }
};

// Checks the structure (key counts, array sizes, vertex, material and texture indices) and
// throws Error naming the mesh and field on the first inconsistency; then drops invalid
// triangles (counted, not thrown) and empty meshes.
SceneCleanup validateScene(Scene& scene);

}  // namespace streak
