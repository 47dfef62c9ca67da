#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace streak {

// One frame of a mesh sequence, or a mesh on its own: an OBJ file (Debian's tinyobjloader) or a
// PLY file (ASCII or binary, either byte order). Positions are in the file's order, which point
// caches and the sequence's interpolation follow; faces are fanned into triangles. A PLY file's
// vertex properties vx, vy, vz are velocities (fluids and remeshers write them); an OBJ's are in
// a sidecar beside it, NAME.vel for NAME.obj: "vx vy vz" per vertex, one to a line, in its
// vertex order ('#' lines are comments). Uvs, normals and materials are not read: the mesh
// takes streak's default material.
struct MeshFile {
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    std::vector<glm::vec3> velocities;  ///< one per vertex, or empty
};

// Reads a .obj or .ply file of at most maxBytes and maxTriangles. Throws Error naming the file
// and the problem.
MeshFile readMeshFile(const std::string& path, std::uint64_t maxBytes, std::size_t maxTriangles = std::size_t(1) << 26);

// Whether the path names a mesh file streak reads (.obj, .ply, in any case).
bool isMeshFilePath(const std::string& path);

}  // namespace streak
