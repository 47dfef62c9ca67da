#pragma once

#include "scene/motion.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace streak {

// Mesh is a triangle mesh whose vertices move over the shutter as numKeys key poses in world
// space (instancing, node animation and skinning are baked into the keys by whoever builds the
// scene). Connectivity, uvs, vertex colours and material are fixed over the shutter. Per-key
// arrays are stored key-major: positions[k * numVertices() + v].
struct Mesh {
    std::string name;
    int numKeys = 2;
    MotionInterpolation interpolation = MotionInterpolation::PiecewiseLinear;
    int bezierPieces = 1;  ///< Bezier: the curves the keys make, each of degree bezierOrder()
    std::vector<glm::vec3> positions;    ///< world space, numKeys * numVertices
    std::vector<glm::vec3> normals;      ///< same layout as positions, or empty (flat shading)
    std::vector<glm::vec2> uvs;          ///< one per vertex, or empty (uv = 0)
    std::vector<glm::vec4> colors;       ///< linear RGBA, one per vertex, or empty (white); multiplies the albedo
    std::vector<glm::uvec3> triangles;   ///< counter-clockwise front faces
    std::uint32_t material = 0;          ///< index into Scene::materials
    // The vertices at the frames before, at and after the frame the shutter sits at (the vector
    // pass, Scene::frameMotion): empty, or numVertices() each.
    std::array<std::vector<glm::vec3>, 3> framePositions;

    std::size_t numVertices() const { return numKeys > 0 ? positions.size() / std::size_t(numKeys) : 0; }
    bool hasNormals() const { return !normals.empty(); }
    bool hasUvs() const { return !uvs.empty(); }
    bool hasColors() const { return !colors.empty(); }
    // True when every key equals the first: the mesh does not move.
    bool isStatic() const;

    std::span<const glm::vec3> keyPositions(int key) const {
        return {positions.data() + std::size_t(key) * numVertices(), numVertices()};
    }
    // The degree of each Bezier piece (1 for piecewise-linear keys).
    int bezierOrder() const { return interpolation == MotionInterpolation::Bezier ? (numKeys - 1) / bezierPieces : 1; }
    // True for Bezier pieces that curve (degree 2 or more).
    bool isCurved() const { return bezierOrder() > 1; }
    MotionWeights weightsAt(float t) const { return motionWeights(numKeys, interpolation, t, bezierPieces); }
    glm::vec3 positionAt(std::uint32_t vertex, const MotionWeights& w) const {
        return w.apply(positions.data() + vertex, numVertices());
    }
    glm::vec3 normalAt(std::uint32_t vertex, const MotionWeights& w) const {
        return w.apply(normals.data() + vertex, numVertices());
    }
    glm::vec2 uv(std::uint32_t vertex) const { return hasUvs() ? uvs[vertex] : glm::vec2(0.0f); }
    glm::vec4 color(std::uint32_t vertex) const { return hasColors() ? colors[vertex] : glm::vec4(1.0f); }
};

}  // namespace streak
