#include "methods/post_filter/post_filter_renderer.h"

#include "image/metrics.h"
#include "exposure/reconstruction_filter.h"
#include "support/render.h"
#include "support/test_scenes.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace streak {
namespace {

using exposure::ReconstructionOptions;
using exposure::VelocityFrame;
using exposure::clampVelocities;
using exposure::neighborMax;
using exposure::tileMax;

// Without motion every velocity is zero: NeighborMax is below half a pixel everywhere and the
// filter returns the centre frame, the pinhole image.
TEST(PostFilter, AStaticSceneIsThePinholeRender) {
    for (const char* spec : {"rotating-cube", "spin", "sphere"}) {
        OptionMap still;
        still.set(std::string(spec) == "rotating-cube" ? "speed" : std::string(spec) == "spin" ? "angle" : "travel", "0");
        const Scene scene = test::validBuiltin(spec, still);
        RenderStats stats;
        const Image filtered = test::render("post-filter", scene, 96, 72, OptionMap{}, &stats, ShadingMode::Phong, 2);
        const Image pinhole = test::render("accumulation", scene, 96, 72, test::withOption("samples", "1"), nullptr, ShadingMode::Phong, 2);
        EXPECT_GE(psnr(filtered, pinhole), 60.0) << spec;
        EXPECT_EQ(stats.counter("moving_pixels"), 0.0) << spec;
    }
}

// A white quad over black slides 16 pixels to the right over the shutter. The exact blur is
// the box-filtered ramp: coverage(x) = clamp((x - 20) / 16) - clamp((x - 60) / 16) at the pixel
// centre x, for the quad on [20, 60] at shutter open. The filter sees the quad at shutter
// centre ([28, 68], V = 8 pixels) and spreads it along V into ramps, with its known error: a
// pixel on the quad cannot see the background the quad hides, so the ramp is too bright on the
// quad's side of each edge (0.86 where the truth is 0.53, beside the edge). Within 0.35 of the
// ramp at every pixel, and less than 0.65 of the centre frame's mean error (which is a step, off
// by up to 0.5 at each edge).
TEST(PostFilter, ATranslatingQuadGivesTheBoxFilteredRamp) {
    const test::PixelCamera cam{96, 8, 4.0f};
    Scene scene = test::emptyScene();
    const std::uint32_t white = test::addMaterial(scene, glm::vec3(1.0f));
    auto quad = [&](float x0, float x1) {
        return std::array<glm::vec3, 4>{cam.at(x0, -2.0f), cam.at(x0, 10.0f), cam.at(x1, 10.0f), cam.at(x1, -2.0f)};
    };
    test::addMovingQuad(scene, white, quad(20.0f, 60.0f), quad(36.0f, 76.0f));
    validateScene(scene);
    const Image filtered = test::render("post-filter", scene, 96, 8, OptionMap{}, nullptr, ShadingMode::Unlit);
    const Image centre = test::render("accumulation", scene, 96, 8, test::withOption("samples", "1"), nullptr, ShadingMode::Unlit);
    double worst = 0.0, mean = 0.0, centreWorst = 0.0, centreMean = 0.0;
    for (int x = 0; x < 96; ++x) {
        const float c = float(x) + 0.5f;
        const float ramp = std::clamp((c - 20.0f) / 16.0f, 0.0f, 1.0f) - std::clamp((c - 60.0f) / 16.0f, 0.0f, 1.0f);
        const double error = std::abs(filtered.at(x, 4).x - ramp);
        worst = std::max(worst, error);
        mean += error / 96.0;
        centreWorst = std::max(centreWorst, double(std::abs(centre.at(x, 4).x - ramp)));
        centreMean += std::abs(centre.at(x, 4).x - ramp) / 96.0;
    }
    std::printf("post-filter against the ramp: worst %.3f, mean %.4f; centre frame: worst %.3f, mean %.4f\n", worst, mean, centreWorst, centreMean);
    EXPECT_LT(worst, 0.35);
    EXPECT_LT(mean, 0.65 * centreMean);
    EXPECT_GT(centreWorst, 0.45);
    // Each side is a ramp: rising over the leading edge, falling over the trailing one.
    for (int x = 16; x < 40; ++x) EXPECT_LE(filtered.at(x, 4).x, filtered.at(x + 1, 4).x + 1e-6f) << x;
    for (int x = 56; x < 80; ++x) EXPECT_GE(filtered.at(x, 4).x + 1e-6f, filtered.at(x + 1, 4).x) << x;
}

TEST(PostFilter, TilesKeepTheLargestVelocityAndNeighboursSpreadIt) {
    VelocityFrame frame;
    frame.width = 8, frame.height = 4;
    frame.velocity.assign(32, glm::vec2(0.0f));
    frame.velocity[frame.index(1, 1)] = {1.0f, 0.0f};
    frame.velocity[frame.index(2, 3)] = {0.0f, -3.0f};
    const std::vector<glm::vec2> tiles = tileMax(frame, 4);  // 2 x 1 tiles
    ASSERT_EQ(tiles.size(), 2u);
    EXPECT_EQ(tiles[0], glm::vec2(0.0f, -3.0f));
    EXPECT_EQ(tiles[1], glm::vec2(0.0f));
    const std::vector<glm::vec2> neighbors = neighborMax(tiles, 2, 1);
    EXPECT_EQ(neighbors[1], glm::vec2(0.0f, -3.0f));
}

TEST(PostFilter, ClampsVelocitiesToTheRadiusAndDropsSubpixelOnes) {
    VelocityFrame frame;
    frame.width = 3, frame.height = 1;
    frame.velocity = {{0.3f, 0.0f}, {30.0f, 40.0f}, {2.0f, 0.0f}};
    ReconstructionOptions options;
    options.maxRadius = 10.0f;
    clampVelocities(frame, options);
    EXPECT_EQ(frame.velocity[0], glm::vec2(0.0f));
    EXPECT_NEAR(frame.velocity[1].x, 6.0f, 1e-5f);
    EXPECT_NEAR(frame.velocity[1].y, 8.0f, 1e-5f);
    EXPECT_EQ(frame.velocity[2], glm::vec2(2.0f, 0.0f));
}

TEST(PostFilter, RejectsOptionsOutOfRange) {
    EXPECT_THROW(createRenderer("post-filter", test::withOption("tile", "0")), Error);
    EXPECT_THROW(createRenderer("post-filter", test::withOption("samples", "0")), Error);
    OptionMap wide;
    wide.set("tile", "8");
    wide.set("max-radius", "16");
    EXPECT_THROW(createRenderer("post-filter", wide), Error);
}

}  // namespace
}  // namespace streak
