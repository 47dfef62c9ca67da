#include "scene/gltf_deform.h"

#include <glm/geometric.hpp>

#include <cassert>

namespace streak::gltf {

namespace {

// det(M) * inverse-transpose(M) of the upper 3x3, times the sign of det: it maps normals like
// the inverse transpose up to a positive scale (normalized afterwards), and stays finite for
// singular matrices.
glm::mat3 normalMatrix(const glm::mat4& m) {
    const glm::vec3 c0(m[0]), c1(m[1]), c2(m[2]);
    const glm::mat3 cofactor(glm::cross(c1, c2), glm::cross(c2, c0), glm::cross(c0, c1));
    return glm::dot(c0, glm::cross(c1, c2)) < 0.0f ? -cofactor : cofactor;
}

glm::vec3 unit(const glm::vec3& v) {
    const float length = glm::length(v);
    return length > 0.0f ? v / length : glm::vec3(0.0f);
}

}  // namespace

std::vector<glm::mat4> jointMatrices(const Skin& skin, const NodePoses& poses) {
    std::vector<glm::mat4> matrices(skin.joints.size());
    for (std::size_t i = 0; i < skin.joints.size(); ++i) matrices[i] = poses.worldFromNode[skin.joints[i]] * skin.inverseBindMatrices[i];
    return matrices;
}

void deformPrimitive(const PrimitiveGeometry& geometry, std::span<const float> morphWeights, const glm::mat4& worldFromMesh,
                     std::span<const glm::mat4> jointMatrices, std::span<glm::vec3> positions, std::span<glm::vec3> normals) {
    const std::size_t n = geometry.numVertices();
    const bool hasNormals = !geometry.normals.empty() && !normals.empty();
    assert(positions.size() == n && (!hasNormals || normals.size() == n));
    const std::size_t numSets = geometry.numInfluenceSets();
    const bool isSkinned = geometry.isSkinned() && !jointMatrices.empty();
    const glm::mat3 rigidNormals = normalMatrix(worldFromMesh);

    for (std::size_t v = 0; v < n; ++v) {
        glm::vec3 p = geometry.positions[v];
        glm::vec3 nrm = hasNormals ? geometry.normals[v] : glm::vec3(0.0f);
        for (std::size_t t = 0; t < morphWeights.size(); ++t) {
            const float w = morphWeights[t];
            if (w == 0.0f) continue;
            if (t < geometry.positionTargets.size() && !geometry.positionTargets[t].empty()) p += w * geometry.positionTargets[t][v];
            if (hasNormals && t < geometry.normalTargets.size() && !geometry.normalTargets[t].empty()) nrm += w * geometry.normalTargets[t][v];
        }

        glm::mat4 worldFromVertex = worldFromMesh;
        if (isSkinned) {
            glm::mat4 sum(0.0f);
            float total = 0.0f;
            for (std::size_t s = 0; s < numSets; ++s) {
                const glm::uvec4& joint = geometry.joints[s * n + v];
                const glm::vec4& weight = geometry.weights[s * n + v];
                for (int c = 0; c < 4; ++c) {
                    if (weight[c] == 0.0f) continue;
                    assert(joint[c] < jointMatrices.size());
                    sum += weight[c] * jointMatrices[joint[c]];
                    total += weight[c];
                }
            }
            if (total > 0.0f) worldFromVertex = sum / total;
        }
        positions[v] = glm::vec3(worldFromVertex * glm::vec4(p, 1.0f));
        if (hasNormals) normals[v] = unit((isSkinned ? normalMatrix(worldFromVertex) : rigidNormals) * nrm);
    }
}

}  // namespace streak::gltf
