#pragma once

#include <glm/vec4.hpp>

#include <array>
#include <cstdint>

namespace streak::motion_path {

enum class FaceKind : std::uint8_t {
    Cap,     ///< the triangle itself at the segment's start or end
    Side,    ///< the screen-space convex hull of one edge at both ends: covers all it sweeps
    Static,  ///< a triangle that does not move in this segment: covered all through it
};

// One triangle of a motion path, in clip space.
struct PathFace {
    std::array<glm::vec4, 3> clip{};
    FaceKind kind = FaceKind::Cap;
};

// MotionPath is the region of the screen a triangle sweeps over one linear segment of the
// shutter, as triangles to rasterize (after Hong & Oh 2017, section 4.2): the triangle at the
// segment's start and end (the caps) and, per moving edge, a side surface.
//
// Hong & Oh split each side, a bilinear patch, into four triangles around its centre, or two
// through the point where the edge crosses its moved copy. That surface is exact only while the
// patch does not fold. A rotating edge folds it: the edge sweeps pixels beyond the four
// triangles (a ladder sliding down a wall sweeps a parabola-bounded region), and those pixels
// never see the triangle. streak instead emits each side as the convex hull of the edge's two
// end positions. Every point of the moving edge is a convex combination of those four points,
// so the hull contains everything the edge sweeps. The caps plus the three hulls then contain
// every point the triangle ever covers: a point it covers at time u is either in the start cap,
// or some edge crossed it before u. The exact time spans come from the edge equations at each
// sample (see motion_path_renderer.cpp). The paths are conservative, and a sample can meet one
// several times; the renderer counts each path once per sample.
struct MotionPath {
    static constexpr int kMaxFaces = 8;  ///< 2 caps + 3 hulls of up to 2 triangles each
    std::array<PathFace, kMaxFaces> faces{};
    int count = 0;
};

// The near plane to rasterize path faces with: below their w = 1, so none is cut, whatever
// the camera's own near plane.
constexpr float kProjectedFaceNear = 0.5f;

// Builds the motion path of the triangle with clip-space corners `open` at the segment's start
// and `close` at its end. A triangle with identical corners at both ends gives one Static face.
// Faces are emitted projected, at w = 1: they only say which samples a path may cover, so the
// near plane must not cut them (depth comes from the exact evaluation). When a corner lies at or
// behind the eye (w <= 0), the swept region is unbounded on screen and the path is one
// full-screen face.
void buildMotionPath(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, MotionPath& out);

}  // namespace streak::motion_path
