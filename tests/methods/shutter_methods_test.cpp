// Every CPU method under the shutter model (scene/shutter.h), against closed forms: a triangle
// curve's quadratic coverage ramp, a rolling shutter's slant of a moving bar, a static scene
// that a rolling shutter leaves alone, and a box curve spelled as points rendering bit for bit
// as the default shutter.

#include "image/metrics.h"
#include "support/render.h"
#include "support/sanitized.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace streak {

namespace {

struct MethodCase {
    const char* name;
    const char* optionKey;    ///< "" for none
    const char* optionValue;
    float tolerance;          ///< of a coverage fraction
};

// Sampling methods place their S times at stratified shares of the exposure, so a coverage
// fraction is within 1/S; exact methods within float rounding, motion-path's masks within one
// slice.
const MethodCase kMethods[] = {
    {"accumulation", "samples", "64", 1.0f / 64.0f + 1e-4f},
    {"stochastic", "samples", "64", 1.0f / 64.0f + 1e-4f},
    {"embree", "samples", "64", 1.0f / 64.0f + 1e-4f},
    {"analytic", "", "", 2e-4f},
    {"higher-order", "", "", 2e-4f},
    {"motion-path", "", "", 2e-4f},
    {"motion-path", "exact-weights", "0", 1.0f / 128.0f + 1e-4f},
};

std::string label(const MethodCase& m) { return std::string(m.name) + (*m.optionKey ? std::string(" ") + m.optionKey + "=" + m.optionValue : ""); }

Image renderCase(const MethodCase& m, const Scene& scene, int width, int height, ShadingMode shading = ShadingMode::Unlit) {
    OptionMap options;
    if (*m.optionKey) options.set(m.optionKey, m.optionValue);
    return test::render(m.name, scene, width, height, options, nullptr, shading);
}

// White quad over black whose right edge sweeps raster x from 2 to 14 over the shutter.
Scene sweepingEdge() {
    const test::PixelCamera cam{16, 4, 3.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), -20.0f, -1.0f, 2.0f, 5.0f, 12.0f, 0.0f);
    validateScene(scene);
    return scene;
}

// The centroid in x of a row's values (its coverage) in pixels.
double rowCentroid(const Image& image, int row) {
    double sum = 0.0, moment = 0.0;
    for (int x = 0; x < image.width(); ++x) sum += image.at(x, row).x, moment += (x + 0.5) * image.at(x, row).x;
    return sum > 0.0 ? moment / sum : -1.0;
}

}  // namespace

TEST(ShutterMethods, TriangleCurveGivesTheQuadraticCoverageRamp) {
    // Pixel centre xc is covered once the edge passes it, from t = (xc - 2) / 12: under the
    // triangle curve its coverage is 1 - C(that), C(x) = 2x^2 up to 1/2, 1 - 2(1 - x)^2 after.
    Scene scene = sweepingEdge();
    scene.shutter.curve = ShutterCurve::parse("triangle");
    for (const MethodCase& m : kMethods) {
        SCOPED_TRACE(label(m));
        const Image image = renderCase(m, scene, 16, 4);
        for (int px = 0; px < 16; ++px) {
            const double x = std::clamp((px + 0.5 - 2.0) / 12.0, 0.0, 1.0);
            const double expected = 1.0 - (x <= 0.5 ? 2.0 * x * x : 1.0 - 2.0 * (1.0 - x) * (1.0 - x));
            for (int py = 0; py < 4; ++py) EXPECT_NEAR(image.at(px, py).x, expected, m.tolerance) << "pixel " << px;
        }
    }
}

TEST(ShutterMethods, BoxCurveSpelledAsPointsRendersTheDefaultBitForBit) {
    Scene defaults = test::validBuiltin("rotating-cube");
    Scene spelled = defaults;
    spelled.shutter.curve = ShutterCurve::parse("0:2,0.5:2,1:2");
    spelled.shutter.rollingDuration = 1.0f;
    for (const MethodCase& m : kMethods) {
        SCOPED_TRACE(label(m));
        const Image a = renderCase(m, defaults, 48, 36, ShadingMode::Phong), b = renderCase(m, spelled, 48, 36, ShadingMode::Phong);
        EXPECT_TRUE(std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin()));
    }
}

TEST(ShutterMethods, RollingShutterSlantsAMovingBarByTheRowDelay) {
    // A bar 2 pixels wide, centre at raster x 5 + 40 t, over 32 rows. Row y is open over
    // [s, s + D], s = (1 - D) y / 31: pixel centre xc is covered for the part of that window in
    // which the centre is within 1 of xc, t in ((xc - 6) / 40, (xc - 4) / 40). For small D the
    // rows slant by 40 (1 - D) / 31 pixels per row; D = 1 blurs every row alike from 5 to 45.
    const test::PixelCamera cam{64, 32, 3.0f};
    Scene scene = test::emptyScene();
    test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), 4.0f, -1.0f, 6.0f, 33.0f, 40.0f, 0.0f);
    validateScene(scene);
    for (const float d : {0.05f, 1.0f}) {
        scene.shutter.rollingDuration = d;
        for (const MethodCase& m : kMethods) {
            SCOPED_TRACE(label(m) + " D=" + std::to_string(d));
            const Image image = renderCase(m, scene, 64, 32);
            for (int y = 0; y < 32; ++y) {
                const double start = (1.0 - d) * y / 31.0;
                for (int x = 0; x < 64; ++x) {
                    const double xc = x + 0.5, lo = std::max(start, (xc - 6.0) / 40.0), hi = std::min(start + d, (xc - 4.0) / 40.0);
                    // Two edges cross each pixel's window: twice the one-edge bound.
                    EXPECT_NEAR(image.at(x, y).x, std::max(0.0, hi - lo) / d, 2.0f * m.tolerance) << "pixel " << x << ", row " << y;
                }
                if (d < 1.0f) { EXPECT_NEAR(rowCentroid(image, y), 5.0 + 40.0 * (start + 0.5 * d), 0.5) << "row " << y; }
            }
        }
    }
}

TEST(ShutterMethods, StaticSceneIsUnchangedByARollingShutterAndACurve) {
    OptionMap still;
    still.set("speed", "0");
    const Scene scene = test::validBuiltin("rotating-cube", still);
    Scene rolling = scene;
    rolling.shutter.rollingDuration = 0.25f;
    rolling.shutter.curve = ShutterCurve::parse("trapezoid:0.2");
    for (const MethodCase& m : kMethods) {
        SCOPED_TRACE(label(m));
        EXPECT_GE(psnr(renderCase(m, scene, 48, 36, ShadingMode::Phong), renderCase(m, rolling, 48, 36, ShadingMode::Phong)), 60.0);
    }
}

}  // namespace streak

namespace streak {

// Every method against accumulation's converged reference on every built-in scene, under a
// triangle curve and under a rolling shutter: exact methods within 45 dB, sampling ones 40 dB.
class ShutterAgreement : public testing::TestWithParam<std::string> {};

TEST_P(ShutterAgreement, EveryMethodMatchesConvergedAccumulation) {
    // Every scene runs the same code: the sanitizers need a textured (spin) and a translucent one,
    // and each shutter once (spin under the triangle curve, translucent under the rolling one).
    if (test::kSanitized && GetParam() != "spin" && GetParam() != "translucent")
        GTEST_SKIP() << "spin and translucent run the same code under the sanitizers";
    const int width = 48, height = 36;
    for (const char* shutter : {"triangle", "rolling"}) {
        if (test::kSanitized && (std::string(shutter) == "triangle") != (GetParam() == "spin")) continue;
        Scene scene = test::validBuiltin(GetParam());
        if (std::string(shutter) == "triangle") scene.shutter.curve = ShutterCurve::parse("triangle");
        else scene.shutter.rollingDuration = 0.25f;
        const Image reference = test::render("accumulation", scene, width, height, test::withOption("samples", "2000"), nullptr, ShadingMode::Phong);
        for (const auto& [method, isExact] : {std::pair{"analytic", true}, std::pair{"higher-order", true}, std::pair{"motion-path", true},
                                              std::pair{"stochastic", false}, std::pair{"embree", false}}) {
            SCOPED_TRACE(std::string(method) + " under " + shutter);
            const OptionMap options = isExact ? OptionMap() : test::withOption("samples", "64");
            EXPECT_GE(psnr(test::render(method, scene, width, height, options, nullptr, ShadingMode::Phong), reference), isExact ? 45.0 : 40.0);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, ShutterAgreement,
                         testing::Values("cubes", "rotating-cube", "spin", "clothball", "sphere", "crossing", "twist", "fence", "pan",
                                         "translucent"));

}  // namespace streak

namespace streak {

// post-filter honours a rolling shutter by its velocity scale alone: each row sees D of the
// motion, so D = 1/2 is the same filter as half the motion about the same centre frame.
TEST(ShutterMethods, PostFilterScalesVelocityByTheRollingDuration) {
    const test::PixelCamera cam{64, 16, 3.0f};
    auto quad = [&](float x0, float dx) {
        Scene scene = test::emptyScene();
        test::addPixelQuad(scene, cam, test::addMaterial(scene, glm::vec3(1.0f)), x0, 2.0f, x0 + 8.0f, 14.0f, dx, 0.0f);
        validateScene(scene);
        return scene;
    };
    Scene rolling = quad(20.0f, 16.0f);
    rolling.shutter.rollingDuration = 0.5f;
    const Scene half = quad(24.0f, 8.0f);  // centre at t = 1/2 as before: x from 28 to 36
    for (const char* method : {"post-filter"}) {  // post-filter-gl: tests/methods/gl (same velocity scale)
        SCOPED_TRACE(method);
        RenderStats stats;
        const Image a = test::render(method, rolling, 64, 16, OptionMap(), &stats);
        EXPECT_GE(psnr(a, test::render(method, half, 64, 16, OptionMap())), 60.0);
        EXPECT_LT(psnr(a, test::render(method, quad(20.0f, 16.0f), 64, 16, OptionMap())), 40.0);
        EXPECT_NE(stats.toJson().find("velocity scale only"), std::string::npos);
    }
}

}  // namespace streak
