// stochastic-gl against closed forms and against its CPU twin `stochastic`: same per-sample
// times, tests and shading, so the two images agree to rounding (measured: above 100 dB on
// llvmpipe). The bar here is 35 dB, what a user sees as the same image.

#include "image/metrics.h"
#include "methods/registry.h"
#include "scene/builtin_scenes.h"
#include "support/test_scenes.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

namespace streak {

namespace {

constexpr int kWidth = 96, kHeight = 72;
constexpr int kSamples = 4;
constexpr double kMinAgreementDb = 35.0;

Image renderWith(const std::string& method, const Scene& scene, int width, int height, int aa, ShadingMode shading,
                 RenderStats* statsOut = nullptr) {
    OptionMap options;
    options.set("samples", std::to_string(kSamples));
    std::unique_ptr<Renderer> renderer = createRenderer(method, options);
    RenderSettings settings;
    settings.width = width, settings.height = height, settings.aa = aa, settings.shading = shading;
    settings.seed = 11;
    RenderStats stats;
    RenderContext context{statsOut ? *statsOut : stats};
    return renderer->render(scene, settings, context);
}

void expectAgreement(const Scene& scene, int width, int height, int aa, ShadingMode shading = ShadingMode::Phong) {
    const Image cpu = renderWith("stochastic", scene, width, height, aa, shading);
    const Image gpu = renderWith("stochastic-gl", scene, width, height, aa, shading);
    EXPECT_GE(psnr(cpu, gpu), kMinAgreementDb);
}

// A w x h pixel square with top-left corner (x, y) + offsets[k] at key k: key poses of any count and
// interpolation (Bezier keys in `pieces` pieces).
void addKeyedSquare(Scene& scene, const test::PixelCamera& cam, std::uint32_t material, MotionInterpolation interpolation, float x,
                    float y, float size, const std::vector<glm::vec2>& offsets, int pieces = 1) {
    Mesh mesh;
    mesh.material = material;
    mesh.numKeys = int(offsets.size());
    mesh.interpolation = interpolation;
    mesh.bezierPieces = pieces;
    for (const glm::vec2& o : offsets)
        for (const glm::vec2& corner : {glm::vec2(0, 0), glm::vec2(0, size), glm::vec2(size, size), glm::vec2(size, 0)})
            mesh.positions.push_back(cam.at(x + o.x + corner.x, y + o.y + corner.y));
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.meshes.push_back(mesh);
}

// Squares crossing a 96x72 image fast (10 to 20 pixels per stratum at S = 4): on a line, on a
// Bezier curve (bending 14 pixels from its chord in the first and last strata), zigzagging
// through piecewise-linear keys inside strata, and on three quadratic pieces whose joints (1/3,
// 2/3) fall inside strata. Motion beyond the space-time bounds would go missing, and at these speeds
// that is a large error.
Scene fastMotionScene() {
    const test::PixelCamera cam{kWidth, kHeight, 4.0f};
    Scene scene = test::emptyScene();
    const std::uint32_t red = test::addMaterial(scene, glm::vec3(1.0f, 0.2f, 0.1f));
    const std::uint32_t green = test::addMaterial(scene, glm::vec3(0.1f, 1.0f, 0.2f), 0.5f);
    const std::uint32_t blue = test::addMaterial(scene, glm::vec3(0.2f, 0.3f, 1.0f));
    addKeyedSquare(scene, cam, red, MotionInterpolation::PiecewiseLinear, 4, 4, 12, {{0, 0}, {72, 8}});
    addKeyedSquare(scene, cam, green, MotionInterpolation::Bezier, 8, 44, 14, {{0, 0}, {20, -100}, {40, 100}, {60, -100}, {80, 0}});
    addKeyedSquare(scene, cam, blue, MotionInterpolation::PiecewiseLinear, 2, 24, 10,
                   {{0, 0}, {14, 30}, {28, 0}, {42, 30}, {56, 0}, {70, 30}, {84, 0}});
    const std::uint32_t yellow = test::addMaterial(scene, glm::vec3(0.9f, 0.8f, 0.1f));
    addKeyedSquare(scene, cam, yellow, MotionInterpolation::Bezier, 4, 30, 8, {{0, 0}, {10, 50}, {25, 0}, {40, -50}, {55, 0}, {70, 50}, {80, 0}}, 3);
    validateScene(scene);
    return scene;
}

Scene builtin(const std::string& name) {
    Scene scene = makeBuiltinScene(name, OptionMap());
    validateScene(scene);
    return scene;
}

}  // namespace

class StochasticGlBuiltin : public testing::TestWithParam<std::tuple<const char*, int>> {};

TEST_P(StochasticGlBuiltin, AgreesWithStochastic) {
    const auto [name, aa] = GetParam();
    expectAgreement(builtin(name), kWidth, kHeight, aa);
}

INSTANTIATE_TEST_SUITE_P(Scenes, StochasticGlBuiltin,
                         testing::Combine(testing::Values("rotating-cube", "crossing", "twist", "fence", "pan", "translucent", "cubes"),
                                          testing::Values(1, 2)),
                         [](const testing::TestParamInfo<std::tuple<const char*, int>>& info) {
                             std::string name = std::get<0>(info.param);
                             for (char& c : name)
                                 if (c == '-') c = '_';
                             return name + "_aa" + std::to_string(std::get<1>(info.param));
                         });

TEST(StochasticGl, FastMotionAgreesWithStochastic) {
    expectAgreement(fastMotionScene(), kWidth, kHeight, 1, ShadingMode::Unlit);
}

TEST(StochasticGl, FastMotionSeenByATurningCameraAgreesWithStochastic) {
    // The camera turns and slides over the shutter: screen paths curve even for linear motion.
    Scene scene = fastMotionScene();
    scene.camera.close = CameraPose::lookAt(glm::vec3(0.5f, 0.2f, 0.0f), glm::vec3(-0.4f, 0.3f, -1.0f));
    validateScene(scene);
    expectAgreement(scene, kWidth, kHeight, 1, ShadingMode::Unlit);
}

TEST(StochasticGl, StaticQuadGivesItsColourOnTheCoveredPixelsAndBackgroundElsewhere) {
    // Raster rectangle [2.25, 9.75] x [1.25, 5.75] of a 16x8 image, unlit: pixel centres
    // x + 1/2 in [3, 9] and y + 1/2 in [2, 5] are covered at every time, no other is.
    const test::PixelCamera cam{16, 8, 3.0f};
    Scene scene = test::emptyScene(glm::vec3(0.1f, 0.2f, 0.3f));
    const glm::vec3 color(0.75f, 0.5f, 0.25f);
    test::addPixelQuad(scene, cam, test::addMaterial(scene, color), 2.25f, 1.25f, 9.75f, 5.75f);
    validateScene(scene);
    const Image image = renderWith("stochastic-gl", scene, 16, 8, 1, ShadingMode::Unlit);
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 16; ++px) {
            const bool isCovered = px >= 2 && px <= 9 && py >= 1 && py <= 5;
            const glm::vec3 expected = isCovered ? color : scene.background;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(px, py)[c], expected[c], 1e-6f) << px << "," << py;
        }
}

TEST(StochasticGl, MovingEdgeCoversTheAnalyticFraction) {
    // A white quad whose right edge sweeps from x = 2 to x = 14 over a black 16x4 image: pixel
    // p's centre is covered for a fraction (14 - (p + 1/2)) / 12 of the shutter. Each of the S
    // stratified times of a pixel errs by at most one stratum, so the mean is within 1/S.
    const test::PixelCamera cam{16, 4, 3.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), -20.0f, -1.0f, 2.0f, 5.0f, 12.0f, 0.0f);
    validateScene(scene);
    const Image image = renderWith("stochastic-gl", scene, 16, 4, 1, ShadingMode::Unlit);
    for (int px = 0; px < 16; ++px) {
        const float expected = std::clamp((14.0f - (float(px) + 0.5f)) / 12.0f, 0.0f, 1.0f);
        for (int py = 0; py < 4; ++py) EXPECT_NEAR(image.at(px, py).x, expected, 1.0f / kSamples + 1e-5f) << px;
    }
}

TEST(StochasticGl, SharedEdgeThroughSamplesCoversEachOnceUnderTranslucency) {
    // A half-transparent square over the whole 16x16 image, split along its diagonal, which
    // runs through every pixel centre on it. The fill rule gives each of those samples to one
    // of the two triangles, so every pixel is blended exactly once: alpha times the colour
    // over black (twice would give 3/4, never would give 0).
    const test::PixelCamera cam{16, 16, 2.0f};
    Scene scene = test::emptyScene();
    const glm::vec3 color(0.8f, 0.6f, 0.4f);
    test::addPixelQuad(scene, cam, test::addMaterial(scene, color, 0.5f), 0.0f, 0.0f, 16.0f, 16.0f);
    validateScene(scene);
    RenderStats stats;
    const Image image = renderWith("stochastic-gl", scene, 16, 16, 1, ShadingMode::Unlit, &stats);
    for (int py = 0; py < 16; ++py)
        for (int px = 0; px < 16; ++px)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(px, py)[c], 0.5f * color[c], 1e-6f) << px << "," << py;
    EXPECT_EQ(stats.counter("translucent_layer_overflow_samples"), 0.0);
    EXPECT_EQ(stats.counter("translucent_list_overflow_fragments"), 0.0);
    EXPECT_EQ(stats.counter("time_samples_per_position"), double(kSamples));
    EXPECT_EQ(stats.counter("samples_per_pixel"), double(kSamples));
}

TEST(StochasticGl, GeometryThroughTheNearPlaneAndGuardBandAgreesWithStochastic) {
    // A floor from behind the camera to far ahead, sliding towards it, and a wall far wider
    // than the guard band: both are clipped at some sample times, so their bounding geometry
    // is the whole image and the test clips as the CPU does.
    Scene scene = test::emptyScene(glm::vec3(0.2f));
    const std::uint32_t floor = test::addMaterial(scene, glm::vec3(0.9f, 0.3f, 0.2f));
    const std::uint32_t wall = test::addMaterial(scene, glm::vec3(0.2f, 0.4f, 0.9f), 0.6f);
    const glm::vec3 slide(0.0f, 0.0f, 1.5f);
    test::addMovingQuad(scene, floor, {glm::vec3(-3, -1, -20), glm::vec3(-3, -1, 2), glm::vec3(3, -1, 2), glm::vec3(3, -1, -20)},
                        {glm::vec3(-3, -1, -20) + slide, glm::vec3(-3, -1, 2) + slide, glm::vec3(3, -1, 2) + slide,
                         glm::vec3(3, -1, -20) + slide});
    test::addMovingQuad(scene, wall, {glm::vec3(-400, 3, -4), glm::vec3(-400, -2, -4), glm::vec3(400, -2, -6), glm::vec3(400, 3, -6)},
                        {glm::vec3(-400, 3, -3), glm::vec3(-400, -2, -3), glm::vec3(400, -2, -7), glm::vec3(400, 3, -7)});
    validateScene(scene);
    expectAgreement(scene, kWidth, kHeight, 1);
    expectAgreement(scene, kWidth, kHeight, 2);
}

TEST(StochasticGl, RejectsBadOptions) {
    for (const auto& [key, value] : {std::pair{"samples", "0"}, {"gpu-memory", "0"}, {"layers", "1000"}, {"no-such-option", "1"}}) {
        OptionMap options;
        options.set(key, value);
        EXPECT_THROW(createRenderer("stochastic-gl", options), Error) << key;
    }
}

}  // namespace streak
