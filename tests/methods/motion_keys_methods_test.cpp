// Keys chosen for glTF animations (GltfLoader's key chooser) judged by the images they give: the
// default keys against the animation's own keys, which an exact method renders exactly.
#include "image/metrics.h"
#include "scene/gltf_loader.h"
#include "support/gltf_samples.h"
#include "support/render.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace streak {
namespace {

Scene loadQuads(int motionKeys, RenderStats* stats = nullptr, int quads = 2) {
    GltfOptions options;
    options.shutter = 24.0;  // the animation's first second
    options.motionKeys = motionKeys;
    options.aspect = 64.0f / 48.0f;
    options.imageHeight = 240;  // the tolerance's pixels: an image 240 tall (the render below is smaller, and as exact)
    options.allowExternalFiles = false;
    return loadGltfFromMemory(test::quadsThroughEachOther(quads).gltfBytes(), "quads.gltf", "", options, stats);
}

// Two quads passing through each other along the view axis twice in the shutter (issue 32): on
// screen they barely move, so keys chosen by screen paths alone (as many as one quad alone
// gets) put the two crossings where those keys' straight depths cross, and the colour of the
// overlap is off by the time between. With the depth deviation counted, the default keys render
// as the animation's own 65 keys do (at t = k / 64, where the keys lie on it: the exact image),
// which the screen's keys and 3 keys miss by far.
TEST(MotionKeysMethods, QuadsPassingThroughEachOtherGetTheKeysTheirDepthsNeed) {
    RenderStats stats;
    const Scene chosen = loadQuads(0, &stats);
    const Scene exact = loadQuads(65);
    const int screenKeys = loadQuads(0, nullptr, 1).meshes[0].numKeys;
    for (const char* method : {"analytic", "motion-path"}) {
        const Image truth = test::render(method, exact, 64, 48, OptionMap(), nullptr, ShadingMode::Unlit, 2);
        auto dbWith = [&](const Scene& scene) { return psnr(test::render(method, scene, 64, 48, OptionMap(), nullptr, ShadingMode::Unlit, 2), truth); };
        const double chosenDb = dbWith(chosen), screenDb = dbWith(loadQuads(screenKeys)), fewDb = dbWith(loadQuads(3));
        std::printf("%s against 65 keys: %g keys (%s) %.1f dB, %d keys (the screen's) %.1f dB, 3 keys %.1f dB\n", method,
                    stats.counter("motion_keys"), stats.info().at("motion_keys_chosen_by").c_str(), chosenDb, screenKeys, screenDb, fewDb);
        EXPECT_GE(chosenDb, 60.0) << method;
        EXPECT_LT(screenDb, chosenDb - 10.0) << method;
        EXPECT_LT(fewDb, 30.0) << method;
    }
}

}  // namespace
}  // namespace streak
