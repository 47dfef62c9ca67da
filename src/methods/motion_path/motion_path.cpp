#include "methods/motion_path/motion_path.h"

#include "raster/convex_hull.h"

#include <glm/vec2.hpp>

#include <algorithm>

namespace streak::motion_path {

namespace {

glm::vec4 projected(const glm::vec4& c) { return {c.x / c.w, c.y / c.w, 0.0f, 1.0f}; }

void addFace(MotionPath& out, const glm::vec4& a, const glm::vec4& b, const glm::vec4& c, FaceKind kind) {
    out.faces[out.count++] = {{projected(a), projected(b), projected(c)}, kind};
}

// The convex hull of four clip-space points (all w > 0) in screen space, as a fan of at most two
// triangles.
void addHull(MotionPath& out, const std::array<glm::vec4, 4>& points) {
    std::array<glm::dvec2, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = {double(points[i].x) / points[i].w, double(points[i].y) / points[i].w};
    const raster::ConvexHull hull = raster::convexHull(p);
    for (int i = 1; i + 1 < hull.count; ++i)
        addFace(out, points[hull.index[0]], points[hull.index[std::size_t(i)]], points[hull.index[std::size_t(i + 1)]], FaceKind::Side);
}

}  // namespace

void buildMotionPath(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, MotionPath& out) {
    out.count = 0;
    const bool isInFront = std::all_of(open.begin(), open.end(), [](const glm::vec4& c) { return c.w > 0.0f; }) &&
                           std::all_of(close.begin(), close.end(), [](const glm::vec4& c) { return c.w > 0.0f; });
    if (!isInFront) {
        const glm::vec4 a(-1, -1, 0, 1), b(1, -1, 0, 1), c(1, 1, 0, 1), d(-1, 1, 0, 1);
        addFace(out, a, b, c, FaceKind::Side);
        addFace(out, a, c, d, FaceKind::Side);
        return;
    }
    if (open == close) {
        addFace(out, open[0], open[1], open[2], FaceKind::Static);
        return;
    }
    addFace(out, open[0], open[1], open[2], FaceKind::Cap);
    addFace(out, close[0], close[1], close[2], FaceKind::Cap);
    for (int e = 0; e < 3; ++e) {
        const int f = (e + 1) % 3;
        addHull(out, {open[e], open[f], close[f], close[e]});
    }
}

}  // namespace streak::motion_path
