#include "methods/motion_path/motion_path.h"
#include "util/random.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <gtest/gtest.h>

namespace streak::motion_path {

namespace {

bool insideTriangle(const glm::dvec2& p, const std::array<glm::dvec2, 3>& t) {
    auto side = [](const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); };
    const double d0 = side(t[0], t[1], p), d1 = side(t[1], t[2], p), d2 = side(t[2], t[0], p);
    return (d0 >= -1e-9 && d1 >= -1e-9 && d2 >= -1e-9) || (d0 <= 1e-9 && d1 <= 1e-9 && d2 <= 1e-9);
}

glm::dvec2 ndc(const glm::vec4& c) { return {double(c.x) / c.w, double(c.y) / c.w}; }

}  // namespace

TEST(MotionPath, FacesOfATranslatingTriangle) {
    // Two caps and a side hull per edge: two triangles for the vertical and the diagonal edge,
    // none for the horizontal edge, which slides along itself and sweeps no area: 6 faces.
    const std::array<glm::vec4, 3> open{glm::vec4(0, 0, 0, 2), glm::vec4(1, 0, 0, 2), glm::vec4(0, 1, 0, 2)};
    std::array<glm::vec4, 3> close = open;
    for (glm::vec4& c : close) c.x += 0.5f;
    MotionPath path;
    buildMotionPath(open, close, path);
    EXPECT_EQ(path.count, 6);
    EXPECT_EQ(path.faces[0].kind, FaceKind::Cap);
    // A static triangle is one face; one behind the eye is a full-screen face pair.
    buildMotionPath(open, open, path);
    ASSERT_EQ(path.count, 1);
    EXPECT_EQ(path.faces[0].kind, FaceKind::Static);
    std::array<glm::vec4, 3> behind = close;
    behind[0].w = -1.0f;
    buildMotionPath(open, behind, path);
    EXPECT_EQ(path.count, 2);
    EXPECT_FLOAT_EQ(path.faces[0].clip[0].x, -1.0f);
}

TEST(MotionPath, RandomPathsContainEverythingTheTriangleSweeps) {
    // Random moving triangles, twisting and rotating ones included: every point the triangle
    // covers at some time lies in some face of its path (the property the renderer relies on,
    // which Hong & Oh's four-triangle sides lack when a side folds).
    Rng rng(17);
    int points = 0;
    for (int trial = 0; trial < 300; ++trial) {
        auto corner = [&] { return glm::vec4(rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0f, rng.uniform(0.5f, 3.0f)); };
        const std::array<glm::vec4, 3> open{corner(), corner(), corner()}, close{corner(), corner(), corner()};
        MotionPath path;
        buildMotionPath(open, close, path);
        for (int i = 0; i < 40; ++i) {
            const float u = rng.uniform();
            float b0 = rng.uniform(), b1 = rng.uniform();
            if (b0 + b1 > 1.0f) b0 = 1.0f - b0, b1 = 1.0f - b1;
            const glm::vec4 c0 = glm::mix(open[0], close[0], u), c1 = glm::mix(open[1], close[1], u), c2 = glm::mix(open[2], close[2], u);
            const glm::dvec2 p = ndc(b0 * c0 + b1 * c1 + (1.0f - b0 - b1) * c2);
            bool covered = false;
            for (int f = 0; f < path.count && !covered; ++f)
                covered = insideTriangle(p, {ndc(path.faces[f].clip[0]), ndc(path.faces[f].clip[1]), ndc(path.faces[f].clip[2])});
            EXPECT_TRUE(covered) << "trial " << trial << " u " << u;
            ++points;
        }
    }
    EXPECT_EQ(points, 12000);
}

}  // namespace streak::motion_path
