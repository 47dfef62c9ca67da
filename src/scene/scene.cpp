#include "scene/scene.h"

#include "util/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace streak {

std::size_t Scene::numTriangles() const {
    std::size_t n = 0;
    for (const Mesh& mesh : meshes) n += mesh.triangles.size();
    return n;
}

bool Scene::hasTranslucency() const {
    return std::any_of(materials.begin(), materials.end(), [](const Material& m) { return m.isTranslucent(); });
}

bool Mesh::isStatic() const {
    const std::size_t n = numVertices();
    for (std::size_t i = n; i < positions.size(); ++i)
        if (positions[i] != positions[i % n]) return false;
    return true;
}

namespace {

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void checkMesh(const Mesh& mesh, std::size_t index, const Scene& scene) {
    const std::string where = "mesh " + std::to_string(index) + (mesh.name.empty() ? "" : " '" + mesh.name + "'");
    if (mesh.numKeys < 2) throw Error(where + ": needs at least 2 key poses, has " + std::to_string(mesh.numKeys));
    if (mesh.interpolation == MotionInterpolation::Bezier) {
        if (mesh.bezierPieces < 1 || (mesh.numKeys - 1) % mesh.bezierPieces != 0)
            throw Error(where + ": " + std::to_string(mesh.numKeys) + " Bezier keys do not make " + std::to_string(mesh.bezierPieces) +
                        " pieces of one degree");
        if (mesh.bezierOrder() >= MotionWeights::kMaxKeys)
            throw Error(where + ": Bezier motion supports at most degree " + std::to_string(MotionWeights::kMaxKeys - 1) + " per piece");
    }
    if (mesh.positions.size() % std::size_t(mesh.numKeys) != 0)
        throw Error(where + ": positions are not a whole number of key poses");
    const std::size_t n = mesh.numVertices();
    if (mesh.hasNormals() && mesh.normals.size() != mesh.positions.size())
        throw Error(where + ": normals do not match positions");
    if (mesh.hasUvs() && mesh.uvs.size() != n) throw Error(where + ": uvs do not match vertices");
    if (mesh.hasColors() && mesh.colors.size() != n) throw Error(where + ": colors do not match vertices");
    if (mesh.material >= scene.materials.size())
        throw Error(where + ": material " + std::to_string(mesh.material) + " does not exist");
    for (const glm::uvec3& tri : mesh.triangles)
        if (tri.x >= n || tri.y >= n || tri.z >= n) throw Error(where + ": triangle vertex index out of range");
}

}  // namespace

SceneCleanup validateScene(Scene& scene) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& material = scene.materials[i];
        const int tex = material.baseColorTexture;
        if (tex >= int(scene.textures.size()))
            throw Error("material " + std::to_string(i) + ": texture " + std::to_string(tex) + " does not exist");
        if (!(material.opacity >= 0.0f && material.opacity <= 1.0f) || !(material.alphaCutoff >= 0.0f && material.alphaCutoff <= 1.0f))
            throw Error("material " + std::to_string(i) + ": opacity and alphaCutoff must be in [0, 1]");
    }
    SceneCleanup cleanup;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        Mesh& mesh = scene.meshes[m];
        checkMesh(mesh, m, scene);
        const std::size_t n = mesh.numVertices();
        auto isInvalid = [&](const glm::uvec3& tri) {
            bool hasArea = false;
            for (int k = 0; k < mesh.numKeys; ++k) {
                const glm::vec3* p = mesh.positions.data() + std::size_t(k) * n;
                const glm::vec3 a = p[tri.x], b = p[tri.y], c = p[tri.z];
                if (!isFinite(a) || !isFinite(b) || !isFinite(c)) {
                    ++cleanup.numNonFinite;
                    return true;
                }
                // Relative test: the cross product against the edge lengths, so scale does not matter.
                const glm::vec3 e1 = b - a, e2 = c - a;
                const float area2 = glm::length(glm::cross(e1, e2));
                hasArea = hasArea || area2 > 1e-12f * glm::dot(e1, e1) + 1e-12f * glm::dot(e2, e2) + 1e-30f;
            }
            if (!hasArea) ++cleanup.numDegenerate;
            return !hasArea;
        };
        std::erase_if(mesh.triangles, isInvalid);
    }
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        if (!scene.meshes[m].triangles.empty()) cleanup.keptMeshes.push_back(m);
    std::erase_if(scene.meshes, [](const Mesh& mesh) { return mesh.triangles.empty(); });
    return cleanup;
}

}  // namespace streak
