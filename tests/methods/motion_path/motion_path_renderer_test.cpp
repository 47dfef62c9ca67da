// The motion-path renderer against closed forms and the accumulation reference.

#include "image/metrics.h"
#include "methods/registry.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_loader.h"
#include "support/render.h"
#include "support/sanitized.h"
#include "support/shared_scenes.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

namespace streak {

using test::render;
using test::withOption;

TEST(MotionPathRenderer, TranslatingQuadCoversTheAnalyticFraction) {
    // As for the references: the quad's right edge sweeps x from 2 to 14; pixel p is covered
    // for (14 - (p + 1/2)) / 12 of the shutter, within one time slice (1/mask-bits).
    const test::PixelCamera cam{16, 4, 3.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), -20.0f, -1.0f, 2.0f, 5.0f, 12.0f, 0.0f);
    validateScene(scene);
    for (int bits : {32, 128, 256}) {
        const Image image = render("motion-path", scene, 16, 4, withOption("mask-bits", std::to_string(bits)));
        for (int px = 0; px < 16; ++px) {
            const float expected = std::clamp((14.0f - (float(px) + 0.5f)) / 12.0f, 0.0f, 1.0f);
            EXPECT_NEAR(image.at(px, 2).x, expected, 1.0f / bits + 1e-5f) << "bits " << bits << " px " << px;
        }
    }
}

TEST(MotionPathRenderer, CrossingQuadsSwapOrderMidShutter) {
    // Red moves from depth 2 to 4, green from 4 to 2: their intervals cross at t = 1/2 and are
    // split there; each pixel is half red, half green.
    const Scene scene = test::crossingQuads();
    RenderStats stats;
    const Image image = render("motion-path", scene, 8, 8, OptionMap(), &stats);
    EXPECT_NEAR(image.at(3, 3).x, 0.5f, 1.0f / 128 + 1e-5f);
    EXPECT_NEAR(image.at(3, 3).y, 0.5f, 1.0f / 128 + 1e-5f);
    EXPECT_GT(stats.counter("interval_splits"), 0.0);
    // Without the depth-time sort the nearer-at-start red wins the whole shutter.
    const Image unsorted = render("motion-path", scene, 8, 8, withOption("sort", "0"));
    EXPECT_GT(unsorted.at(3, 3).x, 0.9f);
}

TEST(MotionPathRenderer, TwistingTriangleIsSeenTwice) {
    // builtin:twist flips its triangle over: near the flip axis a pixel sees it before and
    // after the flip, two intervals of one path; the image agrees with the reference.
    Scene scene = makeBuiltinScene("twist", OptionMap());
    validateScene(scene);
    RenderStats stats;
    const Image mp = render("motion-path", scene, 128, 96, OptionMap(), &stats, ShadingMode::Phong);
    const Image ref = render("accumulation", scene, 128, 96, withOption("samples", "1024"), nullptr, ShadingMode::Phong);
    EXPECT_GT(stats.counter("intervals_per_sample_max"), 1.0);
    EXPECT_GT(psnr(mp, ref), 40.0);
}

TEST(MotionPathRenderer, ASliverThinnerThanTheFixedPointGridStillCoversItsSamples) {
    // A still red triangle 0.0025 px high in front of a blue quad: its corners snap to one row
    // of the 1/256-pixel grid the faces are rasterized on, so the rasterizer sees no area, yet
    // the pixel centre (10.5, 10.5) lies inside it (between its lower edge at y = 10.499 and
    // its long edge, at y = 10.50025 there). The sample is red, as the exact triangle says and
    // analytic draws it; it showed the quad through the hole (on a dense sphere's silhouette,
    // the sphere's back face).
    const int width = 32, height = 24;
    const test::PixelCamera near{width, height, 2.0f}, far{width, height, 4.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, far, test::addMaterial(scene, glm::vec3(0, 0, 1)), -1.0f, -1.0f, 33.0f, 25.0f);
    Mesh sliver;
    sliver.material = test::addMaterial(scene, glm::vec3(1, 0, 0));
    // Counter-clockwise on screen (y up): A, C, B with raster y down.
    const glm::vec3 a = near.at(10.3f, 10.499f), b = near.at(10.7f, 10.499f), c = near.at(10.7f, 10.5015f);
    sliver.positions = {a, c, b, a, c, b};
    sliver.triangles = {glm::uvec3(0, 1, 2)};
    scene.meshes.push_back(sliver);
    validateScene(scene);
    for (const char* method : {"motion-path", "analytic"}) {
        SCOPED_TRACE(method);
        RenderStats stats;
        const Image image = render(method, scene, width, height, OptionMap(), &stats);
        EXPECT_NEAR(image.at(10, 10).x, 1.0f, 1e-6f);
        EXPECT_NEAR(image.at(10, 10).z, 0.0f, 1e-6f);
        EXPECT_NEAR(image.at(10, 11).z, 1.0f, 1e-6f);  // the pixel below: the quad
        if (std::string(method) == "motion-path") {
            EXPECT_EQ(stats.counter("path_faces_snapped_away"), 1.0);
        }
    }
}

TEST(MotionPathRenderer, StaticSceneMatchesTheReference) {
    Scene scene = makeBuiltinScene("rotating-cube", OptionMap());
    for (Mesh& mesh : scene.meshes)
        for (std::size_t i = mesh.numVertices(); i < mesh.positions.size(); ++i) {
            mesh.positions[i] = mesh.positions[i % mesh.numVertices()];
            mesh.normals[i] = mesh.normals[i % mesh.numVertices()];
        }
    validateScene(scene);
    const Image mp = render("motion-path", scene, 128, 96, OptionMap(), nullptr, ShadingMode::Phong, 2);
    const Image ref = render("accumulation", scene, 128, 96, withOption("samples", "1"), nullptr, ShadingMode::Phong, 2);
    EXPECT_GT(psnr(mp, ref), 50.0);
}

TEST(MotionPathRenderer, AgreesWithTheReferenceOnMovingScenes) {
    // 40 dB is the figure the issue asks of every scene; these are small renders of the
    // hardest ones (rotation with K = 2 keys, translucency, thin fast bars). Under the
    // sanitizers the 1024-time reference is most of the time; motion-path's translucent path
    // runs there in ShutterAgreement.
    std::vector<const char*> names{"rotating-cube", "translucent", "fence"};
    if (test::kSanitized) names = {"rotating-cube", "fence"};
    for (const char* name : names) {
        SCOPED_TRACE(name);
        Scene scene = makeBuiltinScene(name, OptionMap());
        validateScene(scene);
        const Image mp = render("motion-path", scene, 128, 96, OptionMap(), nullptr, ShadingMode::Phong);
        const Image ref = render("accumulation", scene, 128, 96, withOption("samples", "1024"), nullptr, ShadingMode::Phong);
        EXPECT_GT(psnr(mp, ref), 40.0);
    }
}

TEST(MotionPathRenderer, AntiAliasingAveragesExactSubsampleCoverage) {
    // A quad below y = 1.375 whose right edge sweeps x from 0 to 4: with 8x8 sub-samples, 3 of
    // 8 rows of pixel row 1 are inside, and a sub-sample at x is covered for (4 - x) / 4 of the
    // shutter. Pixel (px, 1) is 3/8 * (3.5 - px) / 4, within one time slice.
    const test::PixelCamera cam{4, 4, 2.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), -20.0f, -5.0f, 0.0f, 1.375f, 4.0f, 0.0f);
    validateScene(scene);
    const Image image = render("motion-path", scene, 4, 4, OptionMap(), nullptr, ShadingMode::Unlit, 8);
    for (int px = 0; px < 4; ++px) EXPECT_NEAR(image.at(px, 1).x, 3.0f / 8.0f * (3.5f - float(px)) / 4.0f, 1.0f / 128 + 1e-5f) << px;
    EXPECT_NEAR(image.at(1, 0).x, (3.5f - 1.0f) / 4.0f, 1.0f / 128 + 1e-5f);
    EXPECT_NEAR(image.at(1, 2).x, 0.0f, 1e-6f);
}

TEST(MotionPathRenderer, MultiKeyAndCameraMotionAgreeWithTheReference) {
    // K = 5 piecewise-linear keys give four paths per triangle, one per key segment; a moving
    // camera (pan) bends screen paths, followed by curve-segments linear pieces. Both agree with
    // the reference; for pan, more pieces are closer.
    Scene cube = makeBuiltinScene("rotating-cube", withOption("keys", "5"));
    validateScene(cube);
    RenderStats stats;
    const Image mp = render("motion-path", cube, 128, 96, OptionMap(), &stats, ShadingMode::Phong);
    EXPECT_EQ(stats.counter("segments_per_triangle"), 4.0);
    EXPECT_GT(psnr(mp, render("accumulation", cube, 128, 96, withOption("samples", "1024"), nullptr, ShadingMode::Phong)), 40.0);

    // The pan with its camera turned 40 degrees over the shutter, so screen paths bend.
    Scene pan = makeBuiltinScene("pan", OptionMap());
    pan.camera.close = CameraPose::lookAt(glm::vec3(0.7f, 0.9f, 5.0f), glm::vec3(6.0f, 0.0f, -1.0f));
    validateScene(pan);
    const Image ref = render("accumulation", pan, 128, 96, withOption("samples", "1024"), nullptr, ShadingMode::Phong);
    RenderStats panStats;
    const double one = psnr(render("motion-path", pan, 128, 96, withOption("curve-segments", "1"), &panStats, ShadingMode::Phong), ref);
    EXPECT_EQ(panStats.counter("segments_per_triangle"), 1.0);
    const double eight = psnr(render("motion-path", pan, 128, 96, withOption("curve-segments", "8"), nullptr, ShadingMode::Phong), ref);
    EXPECT_GT(eight, 45.0);
    EXPECT_GT(eight, one + 1.0) << one << " " << eight;
    // By default the pieces are as many (1, 2, 4 ...) as keep the vertices within 1/8 pixel of
    // their true screen paths: on this turn as close to the reference as 8 fixed pieces.
    RenderStats chosenStats;
    const double chosen = psnr(render("motion-path", pan, 128, 96, OptionMap(), &chosenStats, ShadingMode::Phong), ref);
    std::printf("pan turned: 1 piece %.1f dB, 8 pieces %.1f dB, chosen %g pieces (%.3f px) %.1f dB\n", one, eight,
                chosenStats.counter("curve_segments"), chosenStats.counter("curve_deviation_px"), chosen);
    EXPECT_LE(chosenStats.counter("curve_deviation_px"), 0.125);
    EXPECT_GT(chosenStats.counter("curve_segments"), 1.0);
    EXPECT_GT(chosen, eight - 0.5);
}

TEST(MotionPathRenderer, BudgetsAreBoundedAndCounted) {
    // Ten static quads stacked in depth over every pixel: with a budget of 4 paths per sample
    // every sample overflows, the nearest are kept (the front quad's colour wins) and the
    // overflow is counted (without the early cull, which would drop the hidden quads first).
    Scene scene = test::emptyScene();
    for (int i = 0; i < 10; ++i) {
        const test::PixelCamera cam{8, 8, 2.0f + float(i)};
        test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(float(i) / 10.0f)), -2, -2, 10, 10);
    }
    validateScene(scene);
    RenderStats stats;
    OptionMap options;
    options.set("max-fragments", "4");
    options.set("max-intervals", "3");
    options.set("early-cull", "0");
    const Image image = render("motion-path", scene, 8, 8, options, &stats);
    EXPECT_FLOAT_EQ(image.at(4, 4).x, 0.0f);
    EXPECT_EQ(stats.counter("fragment_overflow_samples"), 64.0);
    EXPECT_EQ(stats.counter("intervals_per_sample_max"), 3.0);
}

// A dense double-sided model under a camera move (BENCHMARKS, "Budgets on the CPU"): the
// default budgets drop nothing, so the image is the one of budgets 16 times larger, while the
// paper's GPU budgets (150 fragments, 90 intervals) overflow and lose geometry visibly.
TEST(MotionPathRenderer, DefaultBudgetsDropNothingOnADenseModel) {
    STREAK_REQUIRE_SHARED_SCENES();
    GltfOptions gltf;
    GltfLookAt look;
    look.position = {-0.03f, 0.025f, 0.05f};
    look.target = {0.0f, 0.0f, 0.0f};
    look.positionEnd = glm::vec3(-0.02f, 0.025f, 0.055f);
    look.verticalFovDegrees = 40.0f;
    gltf.lookAt = look;
    Scene scene = loadScene(test::sharedScene("ToyCar/glTF/ToyCar.gltf"), gltf);
    validateScene(scene);
    auto budgets = [](int fragments, int intervals) {
        OptionMap options = withOption("max-fragments", std::to_string(fragments));
        options.set("max-intervals", std::to_string(intervals));
        return options;
    };
    RenderStats defaults, paper;
    const Image image = render("motion-path", scene, 160, 120, OptionMap(), &defaults);
    const Image unlimited = render("motion-path", scene, 160, 120, budgets(1 << 16, 1 << 15));
    const Image paperImage = render("motion-path", scene, 160, 120, budgets(150, 90), &paper);
    EXPECT_EQ(defaults.counter("fragment_overflow_samples"), 0.0);
    EXPECT_EQ(defaults.counter("interval_overflow_samples"), 0.0);
    EXPECT_GT(psnr(image, unlimited), 90.0);
    EXPECT_GT(paper.counter("fragment_overflow_samples") + paper.counter("interval_overflow_samples"), 0.0);
    EXPECT_LT(psnr(paperImage, unlimited), 45.0) << "the scene must be dense enough for the paper's budgets to lose geometry";
}

}  // namespace streak
