// The two reference renderers proved against closed forms and against each other.

#include "image/metrics.h"
#include "methods/registry.h"
#include "scene/builtin_scenes.h"
#include "support/sanitized.h"
#include "support/test_scenes.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <tuple>

namespace streak {

namespace {

Image renderWith(const std::string& method, const Scene& scene, int width, int height, int samples, int aa = 1,
                 ShadingMode shading = ShadingMode::Unlit, RenderStats* statsOut = nullptr) {
    OptionMap options;
    options.set("samples", std::to_string(samples));
    std::unique_ptr<Renderer> renderer = createRenderer(method, options);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.aa = aa;
    settings.shading = shading;
    settings.seed = 5;
    RenderStats stats;
    RenderContext context{stats};
    Image image = renderer->render(scene, settings, context);
    if (statsOut) *statsOut = stats;
    return image;
}

Scene builtin(const std::string& name) {
    Scene scene = makeBuiltinScene(name, OptionMap());
    validateScene(scene);
    return scene;
}

double maxAbsDifference(const Image& a, const Image& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(a.pixels()[i][c] - b.pixels()[i][c])));
    return worst;
}

}  // namespace

TEST(ReferenceRenderers, QuadTranslatingOverPixelsCoversTheAnalyticFraction) {
    // A white quad whose right edge sweeps from x = 2 to x = 14 over a black 16x4 image: the
    // centre x_c = p + 1/2 of pixel p is covered while the edge is right of it, for a fraction
    // (14 - x_c) / 12 of the shutter. Unlit white on black, so the pixel value is that fraction.
    // S stratified times resolve it within 1/S (accumulation: one time step; stochastic: one
    // stratum per pixel).
    const test::PixelCamera cam{16, 4, 3.0f};
    Scene scene = test::emptyScene();
    const std::uint32_t white = test::addMaterial(scene, glm::vec3(1.0f));
    test::addPixelQuad(scene, cam, white, -20.0f, -1.0f, 2.0f, 5.0f, 12.0f, 0.0f);
    validateScene(scene);
    for (const char* method : {"accumulation", "stochastic"}) {
        for (int samples : {7, 64}) {
            SCOPED_TRACE(std::string(method) + " S=" + std::to_string(samples));
            const Image image = renderWith(method, scene, 16, 4, samples);
            for (int px = 0; px < 16; ++px) {
                const float xc = float(px) + 0.5f;
                const float expected = std::clamp((14.0f - xc) / 12.0f, 0.0f, 1.0f);
                for (int py = 0; py < 4; ++py) EXPECT_NEAR(image.at(px, py).x, expected, 1.0f / samples + 1e-5f) << px;
            }
        }
    }
}

TEST(ReferenceRenderers, SquareOnBezierPiecesBendingApartAroundTheirJointIsCoveredAllAlong) {
    // An 8x8 pixel white square on two quadratic Bezier pieces (control points below, pixels),
    // the first bending 30 pixels up and the second 30 down, joined at t = 1/2 on the shutter's
    // chord. At any time the square covers 64 pixels of the black image, so the image sums to
    // 64 whatever the sample times. stochastic's one stratum per sample holds the joint: bounds
    // from the stratum's ends and middle alone (all on the chord) would miss both bends.
    const test::PixelCamera cam{100, 80, 4.0f};
    Scene scene = test::emptyScene();
    const std::uint32_t white = test::addMaterial(scene, glm::vec3(1.0f));
    Mesh mesh;
    mesh.material = white;
    mesh.numKeys = 5;
    mesh.interpolation = MotionInterpolation::Bezier;
    mesh.bezierPieces = 2;
    for (const glm::vec2 o : {glm::vec2(0, 0), glm::vec2(20, -60), glm::vec2(40, 0), glm::vec2(60, 60), glm::vec2(80, 0)})
        for (const glm::vec2 corner : {glm::vec2(0, 0), glm::vec2(0, 8), glm::vec2(8, 8), glm::vec2(8, 0)})
            mesh.positions.push_back(cam.at(10 + o.x + corner.x, 36 + o.y + corner.y));
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(mesh);
    validateScene(scene);
    for (const auto& [method, samples, tolerance] : {std::tuple{"accumulation", 64, 0.02}, std::tuple{"stochastic", 1, 0.1}}) {
        const Image image = renderWith(method, scene, 100, 80, samples, 4);
        double sum = 0.0;
        for (int y = 0; y < 80; ++y)
            for (int x = 0; x < 100; ++x) sum += double(image.at(x, y).x);
        EXPECT_NEAR(sum, 64.0, 64.0 * tolerance) << method;
    }
}

TEST(ReferenceRenderers, StaticSceneRendersTheSameUnderBoth) {
    // With nothing moving, every time sample sees the same image, so both methods must agree
    // sample for sample (same sub-pixel positions, same shading); only float rounding of the
    // motion weights differs.
    Scene scene = builtin("rotating-cube");
    for (Mesh& mesh : scene.meshes)
        for (std::size_t i = mesh.numVertices(); i < mesh.positions.size(); ++i) {
            mesh.positions[i] = mesh.positions[i % mesh.numVertices()];
            mesh.normals[i] = mesh.normals[i % mesh.numVertices()];
        }
    const Image accumulation = renderWith("accumulation", scene, 128, 96, 3, 2, ShadingMode::Phong);
    const Image stochastic = renderWith("stochastic", scene, 128, 96, 3, 2, ShadingMode::Phong);
    EXPECT_LT(maxAbsDifference(accumulation, stochastic), 2e-3);
    EXPECT_GT(psnr(accumulation, stochastic), 60.0);
    // And not trivially: the cube is there.
    EXPECT_NE(accumulation.at(64, 48), scene.background);
}

class ReferenceConvergence : public ::testing::Test {
protected:
    // accumulation with 2048 shutter times on rotating-cube at 256x192 (128x96 sanitized): the
    // converged image.
    static constexpr int kW = test::kSanitized ? 128 : 256, kH = test::kSanitized ? 96 : 192;
    static void SetUpTestSuite() {
        s_scene = new Scene(builtin("rotating-cube"));
        s_reference = new Image(renderWith("accumulation", *s_scene, kW, kH, 2048, 1, ShadingMode::Phong));
    }
    static void TearDownTestSuite() {
        delete s_scene;
        delete s_reference;
    }
    static Scene* s_scene;
    static Image* s_reference;
};
Scene* ReferenceConvergence::s_scene = nullptr;
Image* ReferenceConvergence::s_reference = nullptr;

TEST_F(ReferenceConvergence, AccumulationConvergesWithSamples) {
    const double psnr16 = psnr(renderWith("accumulation", *s_scene, kW, kH, 16, 1, ShadingMode::Phong), *s_reference);
    const double psnr256 = psnr(renderWith("accumulation", *s_scene, kW, kH, 256, 1, ShadingMode::Phong), *s_reference);
    EXPECT_GE(psnr256, 40.0);
    EXPECT_GT(psnr256, psnr16 + 6.0);
}

TEST_F(ReferenceConvergence, Stochastic1024SppReachesTheReference) {
    const Image stochastic = renderWith("stochastic", *s_scene, kW, kH, 1024, 1, ShadingMode::Phong);
    EXPECT_GE(psnr(stochastic, *s_reference), 33.0);
    // And it is noisy at a low sample count: fewer samples, lower PSNR.
    const Image noisy = renderWith("stochastic", *s_scene, kW, kH, 4, 1, ShadingMode::Phong);
    EXPECT_LT(psnr(noisy, *s_reference), psnr(stochastic, *s_reference) - 10.0);
}

TEST(ReferenceRenderers, TranslucentLayersBlendInDepthOrder) {
    // Over an opaque blue quad: red (alpha 0.5) nearest, then green (alpha 0.25), submitted
    // back to front. Expected C = 0.5 red + 0.5 (0.25 green + 0.75 blue) = (0.5, 0.125, 0.375)
    // where all overlap, and 0.5 red + 0.5 blue = (0.5, 0, 0.5) right of the green quad.
    Scene scene = test::emptyScene();
    const test::PixelCamera near{8, 8, 2.0f}, mid{8, 8, 3.0f}, far{8, 8, 4.0f};
    test::addPixelQuad(scene, far, test::addMaterial(scene, {0, 0, 1}), -1, -1, 9, 9);
    test::addPixelQuad(scene, mid, test::addMaterial(scene, {0, 1, 0}, 0.25f), -1, -1, 4, 9);
    test::addPixelQuad(scene, near, test::addMaterial(scene, {1, 0, 0}, 0.5f), -1, -1, 9, 9);
    validateScene(scene);
    for (const char* method : {"accumulation", "stochastic"}) {
        SCOPED_TRACE(method);
        const Image image = renderWith(method, scene, 8, 8, 2);
        EXPECT_NEAR(image.at(1, 4).x, 0.5f, 1e-5f);
        EXPECT_NEAR(image.at(1, 4).y, 0.125f, 1e-5f);
        EXPECT_NEAR(image.at(1, 4).z, 0.375f, 1e-5f);
        EXPECT_NEAR(image.at(6, 4).x, 0.5f, 1e-5f);
        EXPECT_NEAR(image.at(6, 4).y, 0.0f, 1e-5f);
        EXPECT_NEAR(image.at(6, 4).z, 0.5f, 1e-5f);
    }
}

TEST(ReferenceRenderers, CrossingTrianglesSwapOrderMidShutter) {
    // Two full-screen quads passing through each other at t = 1/2: red from depth 2 to 4,
    // green from 4 to 2. Each is in front for half the shutter, so every pixel is half red,
    // half green (within 1/S).
    Scene scene = test::emptyScene();
    const test::PixelCamera c2{8, 8, 2.0f}, c4{8, 8, 4.0f};
    const std::uint32_t red = test::addMaterial(scene, {1, 0, 0}), green = test::addMaterial(scene, {0, 1, 0});
    auto corners = [](const test::PixelCamera& c) {
        return std::array<glm::vec3, 4>{c.at(-4, -4), c.at(-4, 12), c.at(12, 12), c.at(12, -4)};
    };
    test::addMovingQuad(scene, red, corners(c2), corners(c4));
    test::addMovingQuad(scene, green, corners(c4), corners(c2));
    validateScene(scene);
    for (const char* method : {"accumulation", "stochastic"}) {
        SCOPED_TRACE(method);
        const Image image = renderWith(method, scene, 8, 8, 32);
        EXPECT_NEAR(image.at(3, 3).x, 0.5f, 1.0f / 32 + 1e-5f);
        EXPECT_NEAR(image.at(3, 3).y, 0.5f, 1.0f / 32 + 1e-5f);
    }
}

TEST(ReferenceRenderers, AntiAliasingAveragesSubpixelCoverage) {
    // A static white quad covering the left 3/8 of pixel column 2 (x in [2, 2.375)): with
    // 8x8 sub-pixel samples exactly 3 of 8 columns of samples are inside.
    const test::PixelCamera cam{4, 4, 2.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), -5.0f, -5.0f, 2.375f, 9.0f);
    validateScene(scene);
    for (const char* method : {"accumulation", "stochastic"}) {
        const Image image = renderWith(method, scene, 4, 4, 1, 8);
        EXPECT_NEAR(image.at(2, 1).x, 3.0f / 8.0f, 1e-5f) << method;
        EXPECT_NEAR(image.at(1, 1).x, 1.0f, 1e-5f) << method;
        EXPECT_NEAR(image.at(3, 1).x, 0.0f, 1e-5f) << method;
    }
}

TEST(ReferenceRenderers, CameraMotionBlursAStaticScene) {
    // pan: static geometry, moving camera. Both methods see the same blur: the stochastic
    // image converges to the accumulation one.
    const Scene scene = builtin("pan");
    const Image accumulation = renderWith("accumulation", scene, 96, 72, 256, 1, ShadingMode::Phong);
    const Image stochastic = renderWith("stochastic", scene, 96, 72, 256, 1, ShadingMode::Phong);
    EXPECT_GT(psnr(accumulation, stochastic), 33.0);
    const Image sharp = renderWith("accumulation", scene, 96, 72, 1, 1, ShadingMode::Phong);
    EXPECT_LT(psnr(accumulation, sharp), psnr(accumulation, stochastic) - 5.0);
}

TEST(ReferenceRenderers, NearPlaneCrossingGeometryIsClippedNotLost) {
    // A floor reaching from behind the camera to far ahead: its near part is clipped, the
    // rest must still be drawn, and both methods agree.
    Scene scene = test::emptyScene();
    Mesh floor;
    floor.material = test::addMaterial(scene, glm::vec3(1.0f));
    floor.positions = {{-5, -1, 5}, {5, -1, 5}, {5, -1, -50}, {-5, -1, -50}};
    floor.positions.insert(floor.positions.end(), floor.positions.begin(), floor.positions.end());
    floor.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(floor);
    validateScene(scene);
    const Image a = renderWith("accumulation", scene, 32, 32, 1);
    const Image s = renderWith("stochastic", scene, 32, 32, 1);
    EXPECT_FLOAT_EQ(a.at(16, 31).x, 1.0f);  // bottom centre: the floor just below the camera
    EXPECT_FLOAT_EQ(a.at(16, 2).x, 0.0f);   // top: background
    EXPECT_LT(maxAbsDifference(a, s), 1e-6);
}

TEST(Registry, UnknownNamesAndOptionsAreErrors) {
    EXPECT_THROW(createRenderer("nosuch", OptionMap()), Error);
    OptionMap bad;
    bad.set("samples", "0");
    EXPECT_THROW(createRenderer("accumulation", bad), Error);
    OptionMap unknown;
    unknown.set("mask-bits", "64");
    EXPECT_THROW(createRenderer("stochastic", unknown), Error);
    EXPECT_GE(registeredMethods().size(), 2u);
}

}  // namespace streak
