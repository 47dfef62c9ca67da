// The analytic renderer against closed forms and the accumulation reference.

#include "image/metrics.h"
#include "methods/registry.h"
#include "scene/builtin_scenes.h"
#include "support/render.h"
#include "support/sanitized.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <vector>

namespace streak {

using test::render;
using test::withOption;


TEST(AnalyticRenderer, TranslatingQuadCoversTheExactFraction) {
    // The quad's right edge sweeps x from 2 to 14: pixel p is covered for (14 - (p + 1/2)) / 12
    // of the shutter, exactly (no time slices: only float rounding).
    const test::PixelCamera cam{16, 4, 3.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), -20.0f, -1.0f, 2.0f, 5.0f, 12.0f, 0.0f);
    validateScene(scene);
    const Image image = render("analytic", scene, 16, 4, OptionMap());
    for (int px = 0; px < 16; ++px)
        EXPECT_NEAR(image.at(px, 2).x, std::clamp((14.0f - (float(px) + 0.5f)) / 12.0f, 0.0f, 1.0f), 1e-5f) << px;
}

TEST(AnalyticRenderer, CrossingQuadsSwapExactlyAtTheCrossing) {
    // Red moves from depth 2 to 4, green from 4 to 2: each pixel is exactly half red, half green.
    const Scene scene = test::crossingQuads();
    const Image image = render("analytic", scene, 8, 8, OptionMap());
    EXPECT_NEAR(image.at(3, 3).x, 0.5f, 1e-4f);
    EXPECT_NEAR(image.at(3, 3).y, 0.5f, 1e-4f);
}

TEST(AnalyticRenderer, AgreesWithTheReferenceOnEveryBuiltinScene) {
    // The issue asks 45 dB against 3000 reference times at full size; these are small renders
    // against 1024, whose own noise is larger: 42 dB. Under the sanitizers the reference is
    // most of the time (20-25 s for each of twist, fence, pan and translucent); three scenes run
    // analytic's paths there (a turning cube, crossing triangles, textured cubes); translucent
    // runs in ShutterAgreement, twist in CullingTilesAndSamplesChangesNoImage, the thin bars in
    // CompressionKeepsTheBudgetAndDegradesGracefully.
    std::vector<const char*> names{"rotating-cube", "crossing", "twist", "fence", "pan", "translucent", "cubes"};
    if (test::kSanitized) names = {"rotating-cube", "crossing", "cubes"};
    for (const char* name : names) {
        SCOPED_TRACE(name);
        Scene scene = makeBuiltinScene(name, name == std::string("cubes") ? withOption("n", "150") : OptionMap());
        validateScene(scene);
        const Image an = render("analytic", scene, 96, 72, OptionMap(), nullptr, ShadingMode::Phong);
        const Image ref = render("accumulation", scene, 96, 72, withOption("samples", "1024"), nullptr, ShadingMode::Phong);
        EXPECT_GT(psnr(an, ref), 42.0);
    }
}

TEST(AnalyticRenderer, MultiKeyMotionIsCutIntoLinearSegments) {
    // K = 5 piecewise-linear keys: four segments per triangle, each solved exactly.
    Scene scene = makeBuiltinScene("rotating-cube", withOption("keys", "5"));
    validateScene(scene);
    RenderStats stats;
    const Image an = render("analytic", scene, 96, 72, OptionMap(), &stats, ShadingMode::Phong);
    EXPECT_EQ(stats.counter("segments_per_triangle"), 4.0);
    EXPECT_GT(psnr(an, render("accumulation", scene, 96, 72, withOption("samples", "1024"), nullptr, ShadingMode::Phong)), 42.0);
}

TEST(AnalyticRenderer, CompressionKeepsTheBudgetAndDegradesGracefully) {
    // fence: many thin bars per pixel. A budget of 1 merges (counted), stays within the budget,
    // and still resembles the uncompressed image; tile culling changes nothing but the work.
    Scene scene = makeBuiltinScene("fence", OptionMap());
    validateScene(scene);
    RenderStats full, compressed, unculled;
    const Image exact = render("analytic", scene, 96, 72, OptionMap(), &full);
    const Image small = render("analytic", scene, 96, 72, withOption("max-intervals", "1"), &compressed);
    EXPECT_GT(full.counter("intervals_per_sample_max"), 2.0);
    EXPECT_GT(compressed.counter("merges"), 0.0);
    EXPECT_GT(compressed.counter("compressed_samples"), 0.0);
    EXPECT_EQ(compressed.counter("resolved_intervals_max"), 1.0);
    EXPECT_EQ(full.counter("resolved_intervals_max"), full.counter("intervals_per_sample_max"));
    EXPECT_GT(psnr(exact, small), 20.0);
    EXPECT_LT(psnr(exact, small), 60.0);
    const Image noCull = render("analytic", scene, 96, 72, withOption("tile-cull", "0"), &unculled);
    EXPECT_EQ(psnr(exact, noCull), std::numeric_limits<double>::infinity());
    EXPECT_GT(full.counter("tiles_culled"), 0.0);
    EXPECT_EQ(unculled.counter("tiles_culled"), 0.0);
}

TEST(AnalyticRenderer, CullingTilesAndSamplesChangesNoImage) {
    // A sample skipped because a segment stays outside one of its edges would have had no span:
    // every built-in scene renders bit for bit as without the culls, and they do skip work.
    double tiles = 0.0, samples = 0.0;
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const std::string name(info.name);
        SCOPED_TRACE(name);
        OptionMap sceneOptions;
        if (name == "cubes") sceneOptions.set("n", "150");
        if (name == "sphere") sceneOptions.set("triangles", "2000");
        Scene scene = makeBuiltinScene(name, sceneOptions);
        validateScene(scene);
        RenderStats stats;
        const Image culled = render("analytic", scene, 64, 48, OptionMap(), &stats, ShadingMode::Phong, 2);
        const Image unculled = render("analytic", scene, 64, 48, withOption("tile-cull", "0"), nullptr, ShadingMode::Phong, 2);
        EXPECT_EQ(psnr(culled, unculled), std::numeric_limits<double>::infinity());
        tiles += stats.counter("tiles_culled"), samples += stats.counter("samples_culled");
    }
    EXPECT_GT(tiles, 0.0);
    EXPECT_GT(samples, 0.0);
}

TEST(AnalyticRenderer, SweptHullSkipsTheSamplesAFastDiagonalMoveLeavesOut) {
    // Small quads moving diagonally across the frame: each one's box is mostly empty, and its
    // swept hull holds every sample it covers. The image is bit for bit the one without the
    // hull, which solves at fewer than half the samples the other culls leave.
    Scene scene = test::emptyScene();
    const test::PixelCamera cam{96, 72, 3.0f};
    const std::uint32_t red = test::addMaterial(scene, {1, 0, 0}), green = test::addMaterial(scene, {0, 1, 0});
    for (int i = 0; i < 40; ++i) {  // 1.5-pixel quads moving 40 by 30 pixels, the rows apart
        const float x = float(i % 8) * 7.0f + 0.3f, y = float(i / 8) * 8.0f + 0.7f;
        test::addPixelQuad(scene, cam, i % 2 ? red : green, x, y, x + 1.5f, y + 1.5f, 40.0f, 30.0f);
    }
    validateScene(scene);
    RenderStats withHull, withoutHull;
    const Image hulled = render("analytic", scene, 96, 72, OptionMap(), &withHull, ShadingMode::Phong, 2);
    const Image boxed = render("analytic", scene, 96, 72, withOption("hull-cull", "0"), &withoutHull, ShadingMode::Phong, 2);
    EXPECT_EQ(psnr(hulled, boxed), std::numeric_limits<double>::infinity());
    EXPECT_EQ(withHull.counter("intervals"), withoutHull.counter("intervals"));
    const double solved = withHull.counter("roots_two") + withHull.counter("roots_linear") + withHull.counter("roots_none");
    const double solvedInBox = withoutHull.counter("roots_two") + withoutHull.counter("roots_linear") + withoutHull.counter("roots_none");
    EXPECT_GT(withHull.counter("intervals"), 1000.0);
    EXPECT_GT(solved, 0.0);
    EXPECT_LT(solved, 0.5 * solvedInBox);
}

TEST(AnalyticRenderer, DepthOrderCheckFindsNoErrorOnPlanarTranslation) {
    // Fronto-parallel quads translating in depth have exactly linear view depth at a pixel: the
    // linearisation never misorders them.
    const Scene scene = test::crossingQuads();
    RenderStats stats;
    render("analytic", scene, 8, 8, withOption("check-depth-order", "1"), &stats);
    EXPECT_GT(stats.counter("depth_overlap_time"), 0.0);
    EXPECT_NEAR(stats.counter("depth_misordered_fraction"), 0.0, 1e-9);
}

}  // namespace streak
