#pragma once

#include "scene/gltf_animation.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <vector>

// A glTF primitive's vertices at one pose: morph targets, then skinning or the node transform
// (glTF 2.0 sections 3.7.2.3 and 3.7.3). Plain data the loader has read and checked.
namespace streak::gltf {

// Skin is a glTF skin: its joints (node indices) and their inverse bind matrices (identity
// where the file gives none), one per joint.
struct Skin {
    std::vector<std::uint32_t> joints;
    std::vector<glm::mat4> inverseBindMatrices;
};

// jointMatrix[i] = worldFromNode[joints[i]] * inverseBindMatrices[i]. They take a vertex from
// the skinned mesh's bind space straight to world space: the transform of the node that
// instances the skinned mesh is ignored, as the specification requires.
std::vector<glm::mat4> jointMatrices(const Skin& skin, const NodePoses& poses);

// PrimitiveGeometry is a primitive's vertex data in its mesh's space.
struct PrimitiveGeometry {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;                       ///< one per vertex, or empty
    std::vector<std::vector<glm::vec3>> positionTargets;  ///< per morph target: a delta per vertex, or empty
    std::vector<std::vector<glm::vec3>> normalTargets;    ///< per morph target: a delta per vertex, or empty
    std::vector<glm::uvec4> joints;   ///< JOINTS_0, JOINTS_1, ... one set after another; indices into Skin::joints
    std::vector<glm::vec4> weights;   ///< WEIGHTS_n, the same layout as joints

    std::size_t numVertices() const { return positions.size(); }
    std::size_t numInfluenceSets() const { return positions.empty() ? 0 : joints.size() / positions.size(); }
    bool isSkinned() const { return !joints.empty(); }
};

// The world-space positions (and unit normals, if the primitive has normals) of `geometry`:
// base plus the morph target deltas times `morphWeights` (one per target), then moved by the
// weighted sum of `jointMatrices` when the primitive is skinned, else by `worldFromMesh`.
// Normals move by the inverse transpose. Skin weights are renormalized to sum to 1; a vertex
// whose weights are all zero takes worldFromMesh. Preconditions: outputs sized numVertices
// (normals may be empty when the primitive has none); every joint index < jointMatrices.size()
// for a skinned primitive.
void deformPrimitive(const PrimitiveGeometry& geometry, std::span<const float> morphWeights, const glm::mat4& worldFromMesh,
                     std::span<const glm::mat4> jointMatrices, std::span<glm::vec3> positions, std::span<glm::vec3> normals);

}  // namespace streak::gltf
