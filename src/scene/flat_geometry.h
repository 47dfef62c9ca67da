#pragma once

#include "scene/scene.h"
#include "scene/shading.h"
#include "util/memory.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace streak {

// A scene triangle with vertex indices into the flattened vertex array.
struct FlatTriangle {
    glm::uvec3 vertices{0u};       ///< global vertex indices
    std::uint32_t mesh = 0;
    std::uint32_t material = 0;
    bool isDoubleSided = false;
    // Its vertex colours are one colour (its mesh has none, or its three corners' are equal):
    // untextured and unlit, it is that one colour everywhere (exposure::Sharing::OneColour).
    bool isOneColour = true;
};

// A frame's per-triangle and per-vertex arrays: large on a dense scene, so in huge pages
// where the system has them (LargeVector).
using FlatTriangles = LargeVector<FlatTriangle>;
using VertexArray = LargeBuffer<glm::vec3>;  ///< FlatGeometry::positionsAt and normalsAt construct every vertex

// FlatGeometry views all triangles of a scene as one array with global vertex indices, so that
// methods loop over triangles rather than meshes. It owns no positions: it evaluates the
// scene's key poses at a shutter time, and turns a hit into a SurfacePoint for shading.
class FlatGeometry {
public:
    explicit FlatGeometry(const Scene& scene);

    const Scene& scene() const { return m_scene; }
    const FlatTriangles& triangles() const { return m_triangles; }
    std::size_t numVertices() const { return m_vertexMesh.size(); }
    std::uint32_t meshVertexOffset(std::uint32_t mesh) const { return m_meshVertexOffset[mesh]; }
    const Mesh& meshOf(const FlatTriangle& tri) const { return m_scene.meshes[tri.mesh]; }

    // World-space positions (and normals, zero for meshes without) of all vertices at time t.
    void positionsAt(float t, VertexArray& positions) const;
    void normalsAt(float t, VertexArray& normals) const;
    // The three corners of one triangle at time t.
    std::array<glm::vec3, 3> cornersAt(const FlatTriangle& tri, float t) const;
    std::array<glm::vec3, 3> cornerNormalsAt(const FlatTriangle& tri, float t) const;

    std::array<glm::vec2, 3> cornerUvs(const FlatTriangle& tri) const;
    // The vertex colour at barycentrics `bary` (white for meshes without colours).
    glm::vec4 vertexColorAt(const FlatTriangle& tri, const glm::vec3& bary) const;

    // What shading needs at a point with barycentrics `bary` (and the barycentrics one pixel
    // right and down, for the texture footprint) given the triangle's corners at that time.
    // The NDC motion across frames (SurfacePoint::frameMotion) of the point at `bary` of a
    // triangle whose mesh has framePositions.
    glm::vec4 frameMotionAt(const FlatTriangle& tri, const glm::vec3& bary) const;
    SurfacePoint surfacePoint(const FlatTriangle& tri, const std::array<glm::vec3, 3>& corners,
                              const std::array<glm::vec3, 3>& cornerNormals, const glm::vec3& bary,
                              const glm::vec3& baryRight, const glm::vec3& baryDown, bool isFrontFacing) const;

private:
    const Scene& m_scene;
    FlatTriangles m_triangles;
    std::vector<std::uint32_t> m_meshVertexOffset;  ///< per mesh, into the global vertex array
    std::vector<std::uint32_t> m_vertexMesh;        ///< per global vertex
};

}  // namespace streak
