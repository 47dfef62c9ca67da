// The analytic renderer against closed forms and the accumulation reference.

#include "image/metrics.h"
#include "methods/registry.h"
#include "raster/sample_pattern.h"
#include "scene/builtin_scenes.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
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
    // against 1024, whose own noise is larger: 42 dB.
    for (const char* name : {"rotating-cube", "crossing", "twist", "fence", "pan", "translucent", "cubes"}) {
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

// line-samples=1 against the closed form: in a still frame each sample is the horizontal line
// through it across its pixel, so a pixel is the mean, over the pattern's rows, of the length of
// each row's line that every colour shows. Here that length comes from the triangles' corners in
// raster space alone: where the line crosses the edges (not the renderer's edge functions).
namespace {

struct RasterTriangle {
    std::array<glm::vec2, 3> corners;  ///< raster pixels
    float depth;                       ///< every corner's view depth
};

// The x stretch of the line at height y that the triangle covers, if any.
std::optional<std::pair<float, float>> crossing(const RasterTriangle& t, float y) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int e = 0; e < 3; ++e) {
        const glm::vec2 a = t.corners[std::size_t(e)], b = t.corners[std::size_t((e + 1) % 3)];
        if ((y < std::min(a.y, b.y)) || (y > std::max(a.y, b.y)) || a.y == b.y) continue;
        const float x = a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
        lo = std::min(lo, x), hi = std::max(hi, x);
    }
    if (!(hi > lo)) return std::nullopt;
    return std::make_pair(lo, hi);
}

// The length of [lo, hi] within [x0, x1].
float within(float lo, float hi, float x0, float x1) { return std::max(0.0f, std::min(hi, x1) - std::max(lo, x0)); }

// Adds the triangles to the scene at their depths, through the test camera, as one mesh each.
void addRasterTriangles(Scene& scene, const test::PixelCamera& cam, const std::vector<RasterTriangle>& triangles, std::uint32_t material) {
    for (const RasterTriangle& t : triangles) {
        Mesh mesh;
        mesh.material = material;
        mesh.numKeys = 2;  // the same pose at both ends: still
        for (int key = 0; key < 2; ++key)
            for (const glm::vec2& c : t.corners) mesh.positions.push_back(cam.at(c.x, c.y) * (t.depth / cam.depth));
        mesh.triangles = {{0, 1, 2}};
        scene.meshes.push_back(mesh);
    }
}

}  // namespace

TEST(AnalyticLineSamples, EachRowIsTheExactLengthOfItsLineThatEachSurfaceShows) {
    // Red triangles at depth 2 over green ones at depth 5 (of one colour none meet; corners far
    // apart, so edges of
    // every slope, some crossing whole pixels), black behind: each pixel's red is the mean of the
    // rows' red lengths, its green the mean of the green lengths less what red hides there.
    constexpr int kWidth = 24, kHeight = 16;
    const test::PixelCamera cam{kWidth, kHeight, 3.0f};
    const std::vector<RasterTriangle> front{{{glm::vec2(2.3f, 1.2f), glm::vec2(9.7f, 14.1f), glm::vec2(13.1f, 3.4f)}, 2.0f},
                                            {{glm::vec2(15.2f, 2.6f), glm::vec2(22.6f, 5.3f), glm::vec2(16.9f, 11.8f)}, 2.0f}};
    const std::vector<RasterTriangle> back{{{glm::vec2(5.1f, 9.3f), glm::vec2(21.4f, 14.7f), glm::vec2(19.8f, 0.6f)}, 5.0f},
                                           {{glm::vec2(0.4f, 6.2f), glm::vec2(4.9f, 15.3f), glm::vec2(4.8f, 2.1f)}, 5.0f}};
    Scene scene = test::emptyScene();
    addRasterTriangles(scene, cam, front, test::addMaterial(scene, {1, 0, 0}));
    addRasterTriangles(scene, cam, back, test::addMaterial(scene, {0, 1, 0}));
    validateScene(scene);
    for (const int aa : {1, 2, 3}) {
        SCOPED_TRACE(aa);
        const raster::SamplePattern pattern = raster::samplePatternFor(aa, false);
        RenderStats stats;
        const Image lines = render("analytic", scene, kWidth, kHeight, withOption("line-samples", "1"), &stats, ShadingMode::Unlit, aa);
        const Image points = render("analytic", scene, kWidth, kHeight, OptionMap(), nullptr, ShadingMode::Unlit, aa);
        EXPECT_EQ(stats.counter("line_samples"), 1.0);
        double lineError = 0.0, pointError = 0.0;
        for (int py = 0; py < kHeight; ++py)
            for (int px = 0; px < kWidth; ++px) {
                glm::vec2 expected(0.0f);  // red, green
                for (const glm::i64vec2& offset : pattern.offsets) {
                    const float y = float(py) + float(offset.y) / float(raster::kSubpixelScale);
                    const float x0 = float(px), x1 = x0 + 1.0f;
                    // The front triangles do not meet; each back one is what no front one covers.
                    std::vector<std::pair<float, float>> reds;
                    for (const RasterTriangle& t : front)
                        if (const auto c = crossing(t, y)) {
                            reds.push_back(*c);
                            expected.x += within(c->first, c->second, x0, x1);
                        }
                    for (const RasterTriangle& t : back)
                        if (const auto c = crossing(t, y)) {
                            float shown = within(c->first, c->second, x0, x1);
                            for (const auto& r : reds) shown -= within(std::max(c->first, r.first), std::min(c->second, r.second), x0, x1);
                            expected.y += shown;
                        }
                }
                expected /= float(pattern.count());
                const glm::vec3 got = lines.at(px, py), point = points.at(px, py);
                EXPECT_NEAR(got.x, expected.x, 2e-5f) << px << "," << py;
                EXPECT_NEAR(got.y, expected.y, 2e-5f) << px << "," << py;
                lineError = std::max({lineError, double(std::abs(got.x - expected.x)), double(std::abs(got.y - expected.y))});
                pointError = std::max({pointError, double(std::abs(point.x - expected.x)), double(std::abs(point.y - expected.y))});
            }
        // Points at the same rows are not lines: the closed form tells them apart.
        EXPECT_LT(lineError, 2e-5);
        EXPECT_GT(pointError, 0.1);
    }
}

TEST(AnalyticLineSamples, TilesWithMotionKeepTheirPointSamples) {
    // A quad sliding 12 pixels in the left tile and a still one in the right tile (tiles are 16
    // pixels): the sliding tile renders bit for bit as without line samples, the still one does
    // not (its slanted edge is integrated along x), and a moving camera, whose frame holds no
    // still segment, renders as without them everywhere.
    constexpr int kWidth = 32, kHeight = 8;
    const test::PixelCamera cam{kWidth, kHeight, 3.0f};
    Scene scene = test::emptyScene();
    const std::uint32_t white = test::addMaterial(scene, glm::vec3(1.0f));
    test::addPixelQuad(scene, cam, white, 1.0f, 1.0f, 3.0f, 7.0f, 12.0f, 0.0f);
    test::addMovingQuad(scene, white, {cam.at(18.0f, 1.0f), cam.at(18.0f, 7.0f), cam.at(29.0f, 7.0f), cam.at(29.0f, 3.5f)},
                        {cam.at(18.0f, 1.0f), cam.at(18.0f, 7.0f), cam.at(29.0f, 7.0f), cam.at(29.0f, 3.5f)});
    validateScene(scene);
    const Image lines = render("analytic", scene, kWidth, kHeight, withOption("line-samples", "1"), nullptr, ShadingMode::Unlit, 2);
    const Image points = render("analytic", scene, kWidth, kHeight, OptionMap(), nullptr, ShadingMode::Unlit, 2);
    double leftDifference = 0.0, rightDifference = 0.0;
    for (int py = 0; py < kHeight; ++py)
        for (int px = 0; px < kWidth; ++px) {
            const double d = std::abs(double(lines.at(px, py).x) - double(points.at(px, py).x));
            (px < 16 ? leftDifference : rightDifference) = std::max(px < 16 ? leftDifference : rightDifference, d);
        }
    EXPECT_EQ(leftDifference, 0.0);
    EXPECT_GT(rightDifference, 0.05);

    Scene moving = scene;
    moving.camera.close = CameraPose::lookAt(glm::vec3(0.1f, 0.0f, 0.0f), glm::vec3(0.1f, 0.0f, -1.0f));
    RenderStats stats;
    const Image movingLines = render("analytic", moving, kWidth, kHeight, withOption("line-samples", "1"), &stats, ShadingMode::Unlit, 2);
    EXPECT_EQ(psnr(movingLines, render("analytic", moving, kWidth, kHeight, OptionMap(), nullptr, ShadingMode::Unlit, 2)),
              std::numeric_limits<double>::infinity());
}

}  // namespace streak
