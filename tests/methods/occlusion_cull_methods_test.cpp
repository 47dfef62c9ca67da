// The occlusion cull (exposure::cullHiddenIntervals) in the methods that resolve exposure
// intervals: dropping what no resolve can show leaves every image as it was, to rounding.

#include "image/metrics.h"
#include "scene/builtin_scenes.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

namespace streak {

namespace {

// Every built-in scene, the dense ones made lighter, with its name.
std::vector<std::pair<std::string, Scene>> lightBuiltinScenes() {
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const std::string name(info.name);
        OptionMap sceneOptions;
        if (name == "cubes") sceneOptions.set("n", "150");
        if (name == "sphere") sceneOptions.set("triangles", "2000");
        Scene scene = makeBuiltinScene(name, sceneOptions);
        validateScene(scene);
        scenes.emplace_back(name, std::move(scene));
    }
    return scenes;
}

bool sameBits(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && std::equal(a.pixels().begin(), a.pixels().end(), b.pixels().begin()) &&
           std::equal(a.alpha().begin(), a.alpha().end(), b.alpha().begin());
}

}  // namespace

TEST(OcclusionCull, EveryBuiltinSceneRendersAsWithoutIt) {
    double culled = 0.0;
    for (const auto& [name, scene] : lightBuiltinScenes()) {
        for (const char* method : {"analytic", "higher-order"}) {
            SCOPED_TRACE(name + " " + method);
            RenderStats stats;
            const Image with = test::render(method, scene, 64, 48, OptionMap(), &stats, ShadingMode::Phong);
            const Image without = test::render(method, scene, 64, 48, test::withOption("occlusion-cull", "0"), nullptr, ShadingMode::Phong);
            EXPECT_GE(psnr(with, without), 60.0);
            culled += stats.counter("hidden_intervals_culled");
        }
    }
    EXPECT_GT(culled, 0.0);  // the scenes do hide intervals: the cull ran
}

TEST(OcclusionCull, AnalyticsEarlyCullLeavesEveryBitAsItWas) {
    // analytic does not solve a segment at a sample that an opaque triangle drawn before it
    // covers all the shutter from nearer than the segment's nearest corner: the resolve's cull
    // would drop each such interval, so every image is the one without the early cull, to the
    // bit, on every built-in scene at --aa 2 (lit) and on a stack of quads where a translucent
    // one is drawn first (it hides nothing: counted as an occluder, the opaque quad behind it
    // would vanish) and a moving opaque one hides the one behind it for part of the shutter.
    double hidden = 0.0;
    for (const auto& [name, scene] : lightBuiltinScenes()) {
        SCOPED_TRACE(name);
        RenderStats stats;
        const Image with = test::render("analytic", scene, 64, 48, OptionMap(), &stats, ShadingMode::Phong, 2);
        const Image without = test::render("analytic", scene, 64, 48, test::withOption("early-cull", "0"), nullptr, ShadingMode::Phong, 2);
        EXPECT_TRUE(sameBits(with, without));
        hidden += stats.counter("samples_hidden_before_solving");
    }
    EXPECT_GT(hidden, 0.0);  // the scenes do hide segments early: the cull ran

    Scene scene = test::emptyScene();
    const std::uint32_t glass = test::addMaterial(scene, glm::vec3(0.2f, 0.4f, 1.0f), 0.5f);
    const std::uint32_t red = test::addMaterial(scene, glm::vec3(1, 0, 0)), green = test::addMaterial(scene, glm::vec3(0, 1, 0));
    const std::uint32_t blue = test::addMaterial(scene, glm::vec3(0, 0, 1));
    auto quad = [](float x0, float x1, float z, float shift) {
        std::array<glm::vec3, 4> open{glm::vec3(x0, 2, z), glm::vec3(x0, -2, z), glm::vec3(x1, -2, z), glm::vec3(x1, 2, z)}, close = open;
        for (glm::vec3& p : close) p.x += shift;
        return std::pair{open, close};
    };
    for (const auto& [material, q] : {std::pair{glass, quad(-6, 6, -3, 0)}, std::pair{red, quad(-6, 0.5f, -4, 0)},
                                      std::pair{green, quad(-8, 8, -5, 0)}, std::pair{blue, quad(-1, 1, -4.5f, 2)}})
        test::addMovingQuad(scene, material, q.first, q.second);
    validateScene(scene);
    RenderStats stats;
    const Image with = test::render("analytic", scene, 32, 24, OptionMap(), &stats, ShadingMode::Unlit, 3);
    const Image without = test::render("analytic", scene, 32, 24, test::withOption("early-cull", "0"), nullptr, ShadingMode::Unlit, 3);
    EXPECT_TRUE(sameBits(with, without));
    EXPECT_GT(stats.counter("samples_hidden_before_solving"), 0.0);
    // Through the glass, the red quad on the left, the green one on the right.
    EXPECT_GT(with.at(10, 12).x, 0.4f);
    EXPECT_GT(with.at(24, 12).y, 0.4f);
}

}  // namespace streak
