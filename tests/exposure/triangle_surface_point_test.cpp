#include "exposure/triangle_surface_point.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

namespace streak::exposure {

TEST(TriangleSurfacePoint, TheVertexColourAloneIsTheColourOfThePointSeen) {
    // A quad in the plane z = -4 sliding 1 along x over the shutter, its vertex colours linear in
    // its own x and y (red 0.5 + x / 8, green 0.5 + y / 8). Through the 90-degree camera at 64x48
    // the sample at NDC (xn, yn) sees world x = xn * 16 / 3, y = yn * 4, and at time t the quad's
    // own x there is that x - t: the colour seen is linear in it, on either triangle (whose
    // barycentrics extrapolate the plane). vertexColorAt gives it, and at()'s colour to the bit,
    // held to the triangle or not.
    Scene scene = test::emptyScene();
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    const std::array<glm::vec3, 4> open{glm::vec3(-1, 1, -4), glm::vec3(-1, -1, -4), glm::vec3(1, -1, -4), glm::vec3(1, 1, -4)};
    std::array<glm::vec3, 4> close = open;
    for (glm::vec3& p : close) p.x += 1.0f;
    test::addMovingQuad(scene, m, open, close);
    for (const glm::vec3& p : open) scene.meshes[0].colors.push_back(glm::vec4(0.5f + p.x / 8.0f, 0.5f + p.y / 8.0f, 0.25f, 1.0f));
    validateScene(scene);
    const raster::Viewport viewport{64, 48};
    const SegmentedGeometry geometry(scene, viewport, 1);
    MovingTriangleCache cache;
    int checked = 0;
    for (const bool held : {false, true})
        for (std::uint32_t triangle = 0; triangle < 2; ++triangle)
            for (const double xn : {-0.1, 0.05, 0.15})
                for (const double yn : {-0.2, 0.1})
                    for (const float t : {0.1f, 0.5f, 0.9f}) {
                        const ShadingSite site{glm::dvec2(xn, yn), glm::dvec2(1.0), held, false};
                        const TriangleSurfacePoint point(geometry, viewport, site, triangle, cache);
                        SurfacePoint full;
                        glm::vec4 color;
                        ASSERT_TRUE(point.at(t, false, full));
                        ASSERT_TRUE(point.vertexColorAt(t, color));
                        EXPECT_EQ(color, full.vertexColor) << "triangle " << triangle << " held " << held;
                        if (held) continue;
                        const double x = xn * 16.0 / 3.0 - double(t), y = yn * 4.0;
                        EXPECT_NEAR(color.x, 0.5 + x / 8.0, 1e-5) << "triangle " << triangle << " at " << xn << ", " << yn << ", t " << t;
                        EXPECT_NEAR(color.y, 0.5 + y / 8.0, 1e-5);
                        EXPECT_NEAR(color.z, 0.25f, 1e-6f);
                        ++checked;
                    }
    EXPECT_EQ(checked, 36);
}

}  // namespace streak::exposure
