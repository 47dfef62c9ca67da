// Line samples (--option line-samples=1 of analytic and motion-path, exposure/line_samples.h)
// against closed forms: where nothing in a tile moves, each sample is the line through it across
// its pixel.

#include "exposure/line_samples.h"
#include "image/cryptomatte.h"
#include "image/metrics.h"
#include "methods/registry.h"
#include "raster/sample_pattern.h"
#include "support/render.h"
#include "support/test_scenes.h"
#include "streak/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace streak {

using test::render;
using test::withOption;

constexpr const char* kLineMethods[] = {"analytic", "motion-path"};

// In a still frame each sample is the horizontal line
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

// Adds the triangles to the scene at their depths, through the test camera, as one mesh each,
// named `name` and their index.
void addRasterTriangles(Scene& scene, const test::PixelCamera& cam, const std::vector<RasterTriangle>& triangles, std::uint32_t material,
                        const std::string& name) {
    for (const RasterTriangle& t : triangles) {
        Mesh mesh;
        mesh.name = name + std::to_string(&t - triangles.data());
        mesh.material = material;
        mesh.numKeys = 2;  // the same pose at both ends: still
        for (int key = 0; key < 2; ++key)
            for (const glm::vec2& c : t.corners) mesh.positions.push_back(cam.at(c.x, c.y) * (t.depth / cam.depth));
        mesh.triangles = {{0, 1, 2}};
        scene.meshes.push_back(mesh);
    }
}

}  // namespace

TEST(LineSamplesMethods, EachRowIsTheExactLengthOfItsLineThatEachSurfaceShows) {
    // Red triangles at depth 2 over green ones at depth 5 (no two of one colour meet; their
    // corners far apart, so edges of every slope, some crossing whole pixels), black behind:
    // each pixel's red is the mean of the rows' red lengths, its green the mean of the green
    // lengths less what red hides there, and each mesh's Cryptomatte coverage its own share.
    constexpr int kWidth = 24, kHeight = 16;
    const test::PixelCamera cam{kWidth, kHeight, 3.0f};
    const std::vector<RasterTriangle> front{{{glm::vec2(2.3f, 1.2f), glm::vec2(9.7f, 14.1f), glm::vec2(13.1f, 3.4f)}, 2.0f},
                                            {{glm::vec2(15.2f, 2.6f), glm::vec2(22.6f, 5.3f), glm::vec2(16.9f, 11.8f)}, 2.0f}};
    const std::vector<RasterTriangle> back{{{glm::vec2(5.1f, 9.3f), glm::vec2(21.4f, 14.7f), glm::vec2(19.8f, 0.6f)}, 5.0f},
                                           {{glm::vec2(0.4f, 6.2f), glm::vec2(4.9f, 15.3f), glm::vec2(4.8f, 2.1f)}, 5.0f}};
    Scene scene = test::emptyScene();
    addRasterTriangles(scene, cam, front, test::addMaterial(scene, {1, 0, 0}), "front");
    addRasterTriangles(scene, cam, back, test::addMaterial(scene, {0, 1, 0}), "back");
    validateScene(scene);
    // --aa 1-3 at their own rows (n^2), and line-rows choosing fewer or more (rows 0: the pattern's).
    const std::pair<int, int> cases[] = {{1, 0}, {2, 0}, {3, 0}, {2, 3}, {3, 2}, {1, 5}};
    for (const char* method : kLineMethods)
    for (const auto& [aa, rows] : cases) {
        SCOPED_TRACE(std::string(method) + " --aa " + std::to_string(aa) + " line-rows " + std::to_string(rows));
        const raster::SamplePattern pattern = rows > 0 ? raster::SamplePattern::rows(rows) : raster::samplePatternFor(aa, false);
        RenderStats stats;
        // With the Cryptomatte object pass: each mesh's coverage of a pixel is what it shows.
        RenderSettings settings;
        settings.width = kWidth, settings.height = kHeight, settings.shading = ShadingMode::Unlit, settings.aa = aa;
        settings.passes.objectId = true;
        settings.passes.cryptoRanks = 4;
        RenderContext context{stats};
        OptionMap options = withOption("line-samples", "1");
        options.set("line-rows", std::to_string(rows));
        const Image lines = createRenderer(method, options)->render(scene, settings, context);
        auto coverageOf = [&](const std::string& name, std::size_t i) {
            float sum = 0.0f;
            for (int r = 0; r < settings.passes.cryptoRanks; ++r) {
                const ImageChannel* id = nullptr;
                const ImageChannel* share = nullptr;
                for (const ImageChannel& c : lines.channels()) {
                    if (c.name == cryptomatteChannel("CryptoObject", r, false)) id = &c;
                    if (c.name == cryptomatteChannel("CryptoObject", r, true)) share = &c;
                }
                if (id && share && id->values[i] == cryptomatteId(name)) sum += share->values[i];
            }
            return sum;
        };
        const Image points = render(method, scene, kWidth, kHeight, OptionMap(), nullptr, ShadingMode::Unlit, aa);
        EXPECT_EQ(stats.counter("line_samples"), 1.0);
        // Every tile is still, so every sample is one of the rows.
        EXPECT_NEAR(stats.counter("intervals_per_sample_mean") * double(kWidth * kHeight * pattern.count()), stats.counter("intervals"), 1e-6);
        double lineError = 0.0, pointError = 0.0;
        for (int py = 0; py < kHeight; ++py)
            for (int px = 0; px < kWidth; ++px) {
                glm::vec2 expected(0.0f);  // red, green
                std::vector<float> shown(front.size() + back.size(), 0.0f);  // each mesh's
                for (const glm::i64vec2& offset : pattern.offsets) {
                    const float y = float(py) + float(offset.y) / float(raster::kSubpixelScale);
                    const float x0 = float(px), x1 = x0 + 1.0f;
                    // The front triangles do not meet; each back one is what no front one covers.
                    std::vector<std::pair<float, float>> reds;
                    for (std::size_t k = 0; k < front.size(); ++k)
                        if (const auto c = crossing(front[k], y)) {
                            reds.push_back(*c);
                            shown[k] += within(c->first, c->second, x0, x1);
                        }
                    for (std::size_t k = 0; k < back.size(); ++k)
                        if (const auto c = crossing(back[k], y)) {
                            float length = within(c->first, c->second, x0, x1);
                            for (const auto& r : reds) length -= within(std::max(c->first, r.first), std::min(c->second, r.second), x0, x1);
                            shown[front.size() + k] += length;
                        }
                }
                for (float& length : shown) length /= float(pattern.count());
                for (std::size_t k = 0; k < shown.size(); ++k) {
                    (k < front.size() ? expected.x : expected.y) += shown[k];
                    const std::string name = k < front.size() ? "front" + std::to_string(k) : "back" + std::to_string(k - front.size());
                    EXPECT_NEAR(coverageOf(name, std::size_t(py) * kWidth + std::size_t(px)), shown[k], 2e-5f) << name << " " << px << "," << py;
                }
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

TEST(LineSamplesMethods, LineRowsWithoutLineSamplesIsRefused) {
    // Rows of lines that are never drawn would change nothing: say so rather than ignore it.
    for (const char* method : kLineMethods) {
        EXPECT_THROW(createRenderer(method, withOption("line-rows", "3")), Error) << method;
        OptionMap options = withOption("line-samples", "1");
        options.set("line-rows", std::to_string(exposure::kMaxLineRows + 1));
        EXPECT_THROW(createRenderer(method, options), Error) << method;
    }
}

TEST(LineSamplesMethods, TilesWithMotionKeepTheirPointSamples) {
    // A quad sliding 12 pixels in the left tile and a still one in the right half (analytic's
    // tiles are 16 pixels, motion-path's 32): the sliding tile renders bit for bit as without line samples, the still one does
    // not (its slanted edge is integrated along x), and a moving camera, whose frame holds no
    // still segment, renders as without them everywhere.
    constexpr int kWidth = 64, kHeight = 8;
    const test::PixelCamera cam{kWidth, kHeight, 3.0f};
    Scene scene = test::emptyScene();
    const std::uint32_t white = test::addMaterial(scene, glm::vec3(1.0f));
    test::addPixelQuad(scene, cam, white, 1.0f, 1.0f, 3.0f, 7.0f, 12.0f, 0.0f);
    test::addMovingQuad(scene, white, {cam.at(34.0f, 1.0f), cam.at(34.0f, 7.0f), cam.at(61.0f, 7.0f), cam.at(61.0f, 3.5f)},
                        {cam.at(34.0f, 1.0f), cam.at(34.0f, 7.0f), cam.at(61.0f, 7.0f), cam.at(61.0f, 3.5f)});
    validateScene(scene);
    for (const char* method : kLineMethods) {
    SCOPED_TRACE(method);
    const Image lines = render(method, scene, kWidth, kHeight, withOption("line-samples", "1"), nullptr, ShadingMode::Unlit, 2);
    const Image points = render(method, scene, kWidth, kHeight, OptionMap(), nullptr, ShadingMode::Unlit, 2);
    double leftDifference = 0.0, rightDifference = 0.0;
    for (int py = 0; py < kHeight; ++py)
        for (int px = 0; px < kWidth; ++px) {
            const double d = std::abs(double(lines.at(px, py).x) - double(points.at(px, py).x));
            (px < 32 ? leftDifference : rightDifference) = std::max(px < 32 ? leftDifference : rightDifference, d);
        }
    EXPECT_EQ(leftDifference, 0.0);
    EXPECT_GT(rightDifference, 0.05);

    Scene moving = scene;
    moving.camera.close = CameraPose::lookAt(glm::vec3(0.1f, 0.0f, 0.0f), glm::vec3(0.1f, 0.0f, -1.0f));
    RenderStats stats;
    const Image movingLines = render(method, moving, kWidth, kHeight, withOption("line-samples", "1"), &stats, ShadingMode::Unlit, 2);
    EXPECT_EQ(psnr(movingLines, render(method, moving, kWidth, kHeight, OptionMap(), nullptr, ShadingMode::Unlit, 2)),
              std::numeric_limits<double>::infinity());
    }
}

TEST(LineSamplesMethods, AMeshCoveringALineTogetherHidesWhatLiesBehindItEveryBitKept) {
    // A red sheet of one-pixel squares, each two triangles, set half a pixel off the pixels so
    // that no triangle covers any pixel's line end to end, at depth 2 over a green quad at depth
    // 6, which comes first in the scene. The early cull takes the union of the sheet's stretches
    // at each line: it skips the quad's samples under the sheet, and every bit stays as without it.
    constexpr int kWidth = 40, kHeight = 16;
    const test::PixelCamera cam{kWidth, kHeight, 2.0f};
    Scene scene = test::emptyScene();
    const std::uint32_t red = test::addMaterial(scene, {1, 0, 0}), green = test::addMaterial(scene, {0, 1, 0});
    const test::PixelCamera far{kWidth, kHeight, 6.0f};
    test::addPixelQuad(scene, far, green, -1.0f, -1.0f, float(kWidth) + 1.0f, float(kHeight) + 1.0f);
    Mesh sheet;
    sheet.material = red;
    sheet.numKeys = 2;  // the same pose at both ends: still
    constexpr int kCells = kWidth - 1, kRows = 10;
    for (int key = 0; key < 2; ++key)
        for (int j = 0; j <= kRows; ++j)
            for (int i = 0; i <= kCells; ++i) sheet.positions.push_back(cam.at(0.5f + float(i), 3.5f + float(j)));
    const auto vertex = [&](int i, int j) { return std::uint32_t(j * (kCells + 1) + i); };
    for (int j = 0; j < kRows; ++j)
        for (int i = 0; i < kCells; ++i) {
            sheet.triangles.push_back({vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1)});
            sheet.triangles.push_back({vertex(i, j), vertex(i + 1, j + 1), vertex(i + 1, j)});
        }
    scene.meshes.push_back(sheet);
    validateScene(scene);
    for (const char* method : kLineMethods) {
        SCOPED_TRACE(method);
        OptionMap lines = withOption("line-samples", "1"), unculled = withOption("line-samples", "1");
        unculled.set("early-cull", "0");
        RenderStats culledStats, unculledStats;
        const Image culled = render(method, scene, kWidth, kHeight, lines, &culledStats, ShadingMode::Unlit, 2);
        const Image all = render(method, scene, kWidth, kHeight, unculled, &unculledStats, ShadingMode::Unlit, 2);
        EXPECT_EQ(psnr(culled, all), std::numeric_limits<double>::infinity());
        EXPECT_EQ(culledStats.counter("line_samples"), 1.0);
        // The quad's samples under the sheet's rows: (kRows - 1) pixel rows wholly under it.
        EXPECT_GE(culledStats.counter("samples_hidden_before_solving"), double((kRows - 1) * (kCells - 1) * 4));
        EXPECT_EQ(unculledStats.counter("samples_hidden_before_solving"), 0.0);
        // And the sheet is red where it lies, the quad green around it.
        EXPECT_NEAR(culled.at(20, 8).x, 1.0f, 1e-5f);
        EXPECT_NEAR(culled.at(20, 1).y, 1.0f, 1e-5f);
    }
}

}  // namespace streak
