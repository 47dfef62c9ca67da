// The GL methods under the shutter model against their CPU twins: the same curve and rolling
// windows in GLSL (scene.glsl) as in scene/shutter.h.

#include "image/metrics.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <string>

namespace streak {
namespace {

struct ShutterCase {
    const char* name;
    const char* curve;
    float rolling;
};

class ShutterGlAgreement : public testing::TestWithParam<ShutterCase> {};

TEST_P(ShutterGlAgreement, GlTwinsMatchTheirCpuTwins) {
    Scene scene = test::validBuiltin("rotating-cube");
    scene.shutter.curve = ShutterCurve::parse(GetParam().curve);
    scene.shutter.rollingDuration = GetParam().rolling;
    const std::pair<const char*, const char*> twins[] = {
        {"accumulation-gl", "accumulation"}, {"motion-path-gl", "motion-path"}, {"stochastic-gl", "stochastic"}, {"post-filter-gl", "post-filter"}};
    for (const auto& [gl, cpu] : twins) {
        SCOPED_TRACE(gl);
        const bool isSampling = std::string(gl) != "motion-path-gl" && std::string(gl) != "post-filter-gl";
        const OptionMap options = isSampling ? test::withOption("samples", "8") : OptionMap();
        // Hardware rasterization samples the grid's texel centres: compare on the grid.
        const bool onGrid = std::string(gl) == "accumulation-gl" || std::string(gl) == "post-filter-gl";
        const Image a = test::render(gl, scene, 64, 48, options, nullptr, ShadingMode::Phong, 1, onGrid);
        const Image b = test::render(cpu, scene, 64, 48, options, nullptr, ShadingMode::Phong, 1, onGrid);
        EXPECT_GE(psnr(a, b), 45.0);
    }
    // And the shutter changed the image: the default shutter is far from it.
    Scene box = test::validBuiltin("rotating-cube");
    EXPECT_LT(psnr(test::render("motion-path-gl", scene, 64, 48, OptionMap(), nullptr, ShadingMode::Phong),
                   test::render("motion-path-gl", box, 64, 48, OptionMap(), nullptr, ShadingMode::Phong)),
              35.0);
}

INSTANTIATE_TEST_SUITE_P(Shutters, ShutterGlAgreement,
                         testing::Values(ShutterCase{"triangle", "triangle", 1.0f}, ShutterCase{"rolling", "box", 0.25f},
                                         ShutterCase{"rolling_trapezoid", "trapezoid:0.3", 0.5f}),
                         [](const testing::TestParamInfo<ShutterCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace streak
