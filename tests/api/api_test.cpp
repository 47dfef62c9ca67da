// The public API (include/streak/streak.h) as a user calls it: the user's own arrays with a
// closed-form image, loading, the registry, errors.

#include <streak/streak.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sk = streak::api;

namespace {

// A white quad at depth 3 seen by a 90-degree camera over a 16x4 image, its right edge
// sweeping raster x from 2 to 14 over the shutter (the reference renderers' closed form).
sk::Scene sweepingQuad() {
    const float depth = 3.0f, aspect = 4.0f;
    auto x = [&](float raster) { return (2.0f * raster / 16.0f - 1.0f) * depth * aspect; };
    auto y = [&](float raster) { return (1.0f - 2.0f * raster / 4.0f) * depth; };
    sk::Mesh quad;
    for (const float dx : {0.0f, 12.0f})
        quad.positions.insert(quad.positions.end(), {x(-20 + dx), y(-1), -depth, x(-20 + dx), y(5), -depth, x(2 + dx), y(5), -depth,
                                                     x(2 + dx), y(-1), -depth});
    quad.indices = {0, 1, 2, 0, 2, 3};
    sk::Material white;
    white.doubleSided = true;
    sk::Camera camera;
    camera.open.position = {0, 0, 0};
    camera.open.target = {0, 0, -1};
    camera.close = camera.open;
    camera.verticalFovDegrees = 90.0f;
    return sk::Scene::fromArrays({quad}, {white}, camera);
}

}  // namespace

TEST(Api, ArraysGiveTheClosedFormCoverage) {
    const sk::Scene scene = sweepingQuad();
    EXPECT_EQ(scene.numTriangles(), 2u);
    for (const char* method : {"analytic", "motion-path"}) {
        SCOPED_TRACE(method);
        sk::RenderSettings settings;
        settings.method = method;
        settings.width = 16, settings.height = 4;
        settings.unlit = true;
        const sk::RenderResult result = sk::render(scene, settings);
        ASSERT_EQ(result.image.rgb.size(), 16u * 4u * 3u);
        for (int px = 0; px < 16; ++px)
            EXPECT_NEAR(result.image.at(px, 1, 0), std::clamp((14.0f - (px + 0.5f)) / 12.0f, 0.0f, 1.0f), 2e-4f) << px;
        EXPECT_NE(result.statsJson.find("\"triangles\""), std::string::npos);
    }
    // Under a triangle curve: 1 - C((xc - 2) / 12), C(x) = 2x^2 up to 1/2.
    sk::RenderSettings settings;
    settings.method = "analytic", settings.width = 16, settings.height = 4, settings.unlit = true;
    const sk::Image curved = sk::render(scene.withShutter({"triangle", 1.0f}), settings).image;
    EXPECT_NEAR(curved.at(3, 0, 0), 1.0f - 2.0f * (1.5f / 12.0f) * (1.5f / 12.0f), 2e-4f);
}

TEST(Api, BadArraysRaiseOneClearError) {
    const sk::Scene good = sweepingQuad();
    sk::Mesh mesh;
    mesh.positions = {0, 0, -1, 1, 0, -1, 0, 1, -1, 0, 0, -1, 1, 0, -1, 0, 1, -1};
    mesh.indices = {0, 1, 2};
    const sk::Material material;
    const sk::Camera camera;
    auto message = [&](const sk::Mesh& m) {
        try {
            sk::Scene::fromArrays({m}, {material}, camera);
        } catch (const streak::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    sk::Mesh wrongShape = mesh;
    wrongShape.positions.pop_back();
    EXPECT_NE(message(wrongShape).find("positions must be keys x vertices x 3"), std::string::npos);
    sk::Mesh nan = mesh;
    nan.positions[4] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(message(nan).find("finite"), std::string::npos);
    sk::Mesh outOfRange = mesh;
    outOfRange.indices[2] = 7;
    EXPECT_NE(message(outOfRange).find("index 7 is out of range"), std::string::npos);
    sk::Mesh badMaterial = mesh;
    badMaterial.material = 3;
    EXPECT_NE(message(badMaterial).find("material 3 does not exist"), std::string::npos);
    EXPECT_EQ(message(mesh), "no error");
    EXPECT_THROW(good.withShutter({"gaussian", 1.0f}), streak::Error);
    EXPECT_THROW(good.withShutter({"box", 0.0f}), streak::Error);
    sk::RenderSettings unknown;
    unknown.method = "nosuch";
    EXPECT_THROW(sk::render(good, unknown), streak::Error);
    EXPECT_THROW(sk::Scene::load("builtin:nosuch"), streak::Error);
}

TEST(Api, ListsTheMethodsAndLoadsScenes) {
    const std::vector<sk::Method> methods = sk::methods();
    EXPECT_TRUE(std::any_of(methods.begin(), methods.end(), [](const sk::Method& m) { return m.name == "analytic"; }));
    const sk::Scene cubes = sk::Scene::load("builtin:cubes?n=10");
    EXPECT_EQ(cubes.numTriangles(), 120u);
    sk::RenderSettings settings;
    settings.width = 32, settings.height = 24;
    const sk::Image a = sk::render(cubes, settings).image, b = sk::render(cubes, settings).image;
    EXPECT_TRUE(std::isinf(sk::compare(a, b).psnr));
}
