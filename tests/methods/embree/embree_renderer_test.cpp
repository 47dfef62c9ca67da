#include "methods/embree/embree_renderer.h"

#include "image/metrics.h"
#include "scene/builtin_scenes.h"
#include "support/render.h"
#include "support/sanitized.h"
#include "support/test_scenes.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <string>

namespace streak {
namespace {

OptionMap samples(int s) { return test::withOption("samples", std::to_string(s)); }

std::vector<std::string> builtinNames() {
    std::vector<std::string> names;
    for (const BuiltinSceneInfo& info : builtinScenes()) names.emplace_back(info.name);
    return names;
}

class EmbreeBuiltin : public testing::TestWithParam<std::string> {};

// The same ray times as stochastic's samples (stratifiedSampleTime), so the two differ only
// where a ray and the rasterizer's snapped edges disagree, and in the texture footprint.
TEST_P(EmbreeBuiltin, AgreesWithStochasticAtTheSameSamples) {
    const Scene scene = test::validBuiltin(GetParam());
    const int s = test::kSanitized ? 8 : 64;
    const Image traced = test::render("embree", scene, 64, 48, samples(s), nullptr, ShadingMode::Phong, 2);
    const Image rasterized = test::render("stochastic", scene, 64, 48, samples(s), nullptr, ShadingMode::Phong, 2);
    EXPECT_GE(psnr(traced, rasterized), 45.0);
}

// Converged: 1024 ray times per sample against accumulation's 1024 shutter times.
TEST_P(EmbreeBuiltin, ConvergesToAccumulation) {
    if (test::kSanitized) GTEST_SKIP() << "the agreement above runs the same code";
    const Scene scene = test::validBuiltin(GetParam());
    const Image traced = test::render("embree", scene, 48, 36, samples(1024), nullptr, ShadingMode::Phong);
    const Image reference = test::render("accumulation", scene, 48, 36, samples(1024), nullptr, ShadingMode::Phong);
    EXPECT_GE(psnr(traced, reference), 40.0);
}

INSTANTIATE_TEST_SUITE_P(Scenes, EmbreeBuiltin, testing::ValuesIn(builtinNames()));

// Without motion every ray time sees the same scene: one sample is the pinhole image, the
// rasterizer's up to rounding: texture footprints, and samples within 1/256 pixel of an edge
// (snapped there) that a ray and the fill rule give to different sides.
TEST(Embree, AStaticSceneIsTheRasterizedOne) {
    for (const char* spec : {"rotating-cube", "spin", "sphere"}) {
        OptionMap still;
        still.set(std::string(spec) == "rotating-cube" ? "speed" : std::string(spec) == "spin" ? "angle" : "travel", "0");
        const Scene scene = test::validBuiltin(spec, still);
        const Image traced = test::render("embree", scene, 96, 72, samples(1), nullptr, ShadingMode::Phong, 2, true);
        const Image rasterized = test::render("accumulation", scene, 96, 72, samples(1), nullptr, ShadingMode::Phong, 2, true);
        EXPECT_GE(psnr(traced, rasterized), 55.0) << spec;
    }
}

// Bezier keys are cut into curve-segments linear time steps, as motion-path cuts them;
// stochastic evaluates the curve itself.
TEST(Embree, CutsBezierKeysIntoTimeSteps) {
    OptionMap curved;
    curved.set("keys", "3");
    curved.set("curve", "bezier");
    const Scene scene = test::validBuiltin("spin", curved);
    OptionMap coarse = samples(16), fine = samples(16);
    coarse.set("curve-segments", "1");
    fine.set("curve-segments", "16");
    const Image rasterized = test::render("stochastic", scene, 64, 48, samples(16));
    const double coarseDb = psnr(test::render("embree", scene, 64, 48, coarse), rasterized);
    const double fineDb = psnr(test::render("embree", scene, 64, 48, fine), rasterized);
    EXPECT_GE(fineDb, 40.0);
    EXPECT_GT(fineDb, coarseDb + 3.0);
}

TEST(Embree, CountsTranslucentLayersPastItsBudget) {
    const Scene scene = test::validBuiltin("translucent");
    OptionMap one = samples(4);
    one.set("max-layers", "1");
    RenderStats clipped, full;
    test::render("embree", scene, 64, 48, one, &clipped);
    test::render("embree", scene, 64, 48, samples(4), &full);
    EXPECT_GT(clipped.counter("translucent_layer_overflow_samples"), 0.0);
    EXPECT_EQ(full.counter("translucent_layer_overflow_samples"), 0.0);
    EXPECT_GT(full.counter("rays"), 64.0 * 48.0 * 4.0);  // translucent hits are traced through
}

TEST(Embree, RejectsOptionsOutOfRange) {
    EXPECT_THROW(createRenderer("embree", samples(0)), Error);
    EXPECT_THROW(createRenderer("embree", test::withOption("curve-segments", "0")), Error);
    EXPECT_THROW(createRenderer("embree", test::withOption("mask-bits", "32")), Error);
}

}  // namespace
}  // namespace streak
