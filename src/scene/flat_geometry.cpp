#include "scene/flat_geometry.h"

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace streak {

FlatGeometry::FlatGeometry(const Scene& scene) : m_scene(scene) {
    std::size_t numTriangles = 0;
    for (const Mesh& mesh : scene.meshes) numTriangles += mesh.triangles.size();
    m_triangles.reserve(numTriangles);
    std::uint32_t offset = 0;
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        m_meshVertexOffset.push_back(offset);
        const bool isDoubleSided = scene.materials[mesh.material].doubleSided;
        for (const glm::uvec3& tri : mesh.triangles) {
            const bool isOneColour = !mesh.hasColors() || (mesh.colors[tri.x] == mesh.colors[tri.y] && mesh.colors[tri.x] == mesh.colors[tri.z]);
            m_triangles.push_back({tri + glm::uvec3(offset), m, mesh.material, isDoubleSided, isOneColour});
        }
        offset += std::uint32_t(mesh.numVertices());
        m_vertexMesh.resize(offset, m);
    }
}

namespace {

template <class Eval>
void evaluateAllVertices(const Scene& scene, const std::vector<std::uint32_t>& offsets, std::size_t numVertices,
                         VertexArray& out, Eval&& eval) {
    out.resize(numVertices);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, scene.meshes.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t m = r.begin(); m != r.end(); ++m) {
            const Mesh& mesh = scene.meshes[m];
            tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(mesh.numVertices()), 4096),
                              [&](const tbb::blocked_range<std::uint32_t>& vr) {
                                  for (std::uint32_t v = vr.begin(); v != vr.end(); ++v) constructAt(out, offsets[m] + v) = eval(mesh, v);
                              });
        }
    });
}

}  // namespace

void FlatGeometry::positionsAt(float t, VertexArray& positions) const {
    evaluateAllVertices(m_scene, m_meshVertexOffset, numVertices(), positions,
                        [t](const Mesh& mesh, std::uint32_t v) { return mesh.positionAt(v, mesh.weightsAt(t)); });
}

void FlatGeometry::normalsAt(float t, VertexArray& normals) const {
    evaluateAllVertices(m_scene, m_meshVertexOffset, numVertices(), normals, [t](const Mesh& mesh, std::uint32_t v) {
        return mesh.hasNormals() ? mesh.normalAt(v, mesh.weightsAt(t)) : glm::vec3(0.0f);
    });
}

std::array<glm::vec3, 3> FlatGeometry::cornersAt(const FlatTriangle& tri, float t) const {
    const Mesh& mesh = meshOf(tri);
    const MotionWeights w = mesh.weightsAt(t);
    const std::uint32_t base = m_meshVertexOffset[tri.mesh];
    return {mesh.positionAt(tri.vertices.x - base, w), mesh.positionAt(tri.vertices.y - base, w),
            mesh.positionAt(tri.vertices.z - base, w)};
}

std::array<glm::vec3, 3> FlatGeometry::cornerNormalsAt(const FlatTriangle& tri, float t) const {
    const Mesh& mesh = meshOf(tri);
    if (!mesh.hasNormals()) return {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    const MotionWeights w = mesh.weightsAt(t);
    const std::uint32_t base = m_meshVertexOffset[tri.mesh];
    return {mesh.normalAt(tri.vertices.x - base, w), mesh.normalAt(tri.vertices.y - base, w),
            mesh.normalAt(tri.vertices.z - base, w)};
}

std::array<glm::vec2, 3> FlatGeometry::cornerUvs(const FlatTriangle& tri) const {
    const Mesh& mesh = meshOf(tri);
    const std::uint32_t base = m_meshVertexOffset[tri.mesh];
    return {mesh.uv(tri.vertices.x - base), mesh.uv(tri.vertices.y - base), mesh.uv(tri.vertices.z - base)};
}

glm::vec4 FlatGeometry::vertexColorAt(const FlatTriangle& tri, const glm::vec3& bary) const {
    const Mesh& mesh = meshOf(tri);
    if (!mesh.hasColors()) return glm::vec4(1.0f);
    const std::uint32_t base = m_meshVertexOffset[tri.mesh];
    return bary.x * mesh.colors[tri.vertices.x - base] + bary.y * mesh.colors[tri.vertices.y - base] +
           bary.z * mesh.colors[tri.vertices.z - base];
}

SurfacePoint FlatGeometry::surfacePoint(const FlatTriangle& tri, const std::array<glm::vec3, 3>& corners,
                                        const std::array<glm::vec3, 3>& cornerNormals, const glm::vec3& bary,
                                        const glm::vec3& baryRight, const glm::vec3& baryDown, bool isFrontFacing) const {
    const Mesh& mesh = meshOf(tri);
    const std::array<glm::vec2, 3> uv = cornerUvs(tri);
    auto uvAt = [&](const glm::vec3& b) { return b.x * uv[0] + b.y * uv[1] + b.z * uv[2]; };
    SurfacePoint p;
    p.position = bary.x * corners[0] + bary.y * corners[1] + bary.z * corners[2];
    p.normal = bary.x * cornerNormals[0] + bary.y * cornerNormals[1] + bary.z * cornerNormals[2];
    if (!mesh.hasNormals()) p.normal = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    p.uv = uvAt(bary);
    p.duvdx = uvAt(baryRight) - p.uv;
    p.duvdy = uvAt(baryDown) - p.uv;
    p.vertexColor = vertexColorAt(tri, bary);
    p.material = tri.material;
    p.isFrontFacing = isFrontFacing;
    if (m_scene.frameMotion && !mesh.framePositions[0].empty()) p.frameMotion = frameMotionAt(tri, bary);
    return p;
}

glm::vec4 FlatGeometry::frameMotionAt(const FlatTriangle& tri, const glm::vec3& bary) const {
    const Mesh& mesh = meshOf(tri);
    const std::uint32_t base = m_meshVertexOffset[tri.mesh];
    std::array<glm::vec2, 3> ndc{};
    for (std::size_t k = 0; k < 3; ++k) {
        const std::vector<glm::vec3>& at = mesh.framePositions[k];
        const glm::vec3 position = bary.x * at[tri.vertices.x - base] + bary.y * at[tri.vertices.y - base] + bary.z * at[tri.vertices.z - base];
        const glm::vec4 clip = m_scene.frameMotion->clipFromWorld[k] * glm::vec4(position, 1.0f);
        if (!(clip.w > 0.0f)) return glm::vec4(0.0f);  // behind that frame's camera: no vector, as Cycles gives none
        ndc[k] = glm::vec2(clip) / clip.w;
    }
    return glm::vec4(ndc[0] - ndc[1], ndc[1] - ndc[2]);
}

}  // namespace streak
