// The occlusion cull (exposure::cullHiddenIntervals) in the methods that resolve exposure
// intervals: dropping what no resolve can show leaves every image as it was, to rounding.

#include "image/metrics.h"
#include "scene/builtin_scenes.h"
#include "support/render.h"

#include <gtest/gtest.h>

namespace streak {

TEST(OcclusionCull, EveryBuiltinSceneRendersAsWithoutIt) {
    double culled = 0.0;
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const std::string name(info.name);
        OptionMap sceneOptions;
        if (name == "cubes") sceneOptions.set("n", "150");
        if (name == "sphere") sceneOptions.set("triangles", "2000");
        Scene scene = makeBuiltinScene(name, sceneOptions);
        validateScene(scene);
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

}  // namespace streak
