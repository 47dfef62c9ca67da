// A property test over the animated Khronos sample models in ../shared/scenes: every model,
// every animation, the frames where wrong images were once found (10, 17, 30) and seeded
// random frames and shutters. motion-path and analytic each agree with the accumulation
// reference at 35 dB or more; a failure names the case. Small images keep it quick.

#include "image/metrics.h"
#include "scene/scene_loader.h"
#include "support/render.h"
#include "support/sanitized.h"
#include "support/shared_scenes.h"
#include "util/error.h"
#include "util/random.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace streak {

namespace {

constexpr int kWidth = 96, kHeight = 72, kAa = 2;
constexpr double kMinAgreementDb = 35.0;

const char* const kAnimatedModels[] = {
    "AnimatedTriangle/glTF/AnimatedTriangle.gltf",   "AnimatedCube/glTF/AnimatedCube.gltf",
    "BoxAnimated/glTF-Binary/BoxAnimated.glb",       "InterpolationTest/glTF-Binary/InterpolationTest.glb",
    "SimpleSkin/glTF/SimpleSkin.gltf",               "RiggedSimple/glTF-Binary/RiggedSimple.glb",
    "RiggedFigure/glTF-Binary/RiggedFigure.glb",     "CesiumMan/glTF-Binary/CesiumMan.glb",
    "Fox/glTF-Binary/Fox.glb",                       "SimpleMorph/glTF/SimpleMorph.gltf",
    "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", "MorphStressTest/glTF-Binary/MorphStressTest.glb",
};

// Loads the model with animation `index` (its default animation when there is none), or
// returns false when it has no such animation.
bool load(const std::string& path, int index, double frame, double shutter, Scene& scene) {
    GltfOptions options;
    options.frame = frame, options.shutter = shutter;
    options.animation = std::to_string(index);
    options.aspect = float(kWidth) / float(kHeight);
    options.imageHeight = kHeight;
    try {
        scene = loadScene(test::sharedScene(path), options);
    } catch (const Error& e) {
        if (std::string(e.what()).find("no animation") == std::string::npos) throw;
        return false;
    }
    validateScene(scene);
    return true;
}

}  // namespace

TEST(GltfFrames, ExactMethodsAgreeWithTheReferenceOnEveryModelAnimationAndFrame) {
    STREAK_REQUIRE_SHARED_SCENES();
    int numCases = 0;
    for (std::size_t model = 0; model < std::size(kAnimatedModels); ++model) {
        const char* path = kAnimatedModels[model];
        for (int animation = 0;; ++animation) {
            Rng rng(hashValues(model, std::uint64_t(animation)));
            std::vector<std::pair<double, double>> shutters{{10, 1}, {17, 1}, {30, 1}};
            if (test::kSanitized) shutters.resize(1);
            for (int i = 0; i < (test::kSanitized ? 0 : 2); ++i) shutters.emplace_back(std::floor(rng.uniform() * 40.0), 0.25 + 1.75 * rng.uniform());
            bool hasAnimation = true;
            for (const auto& [frame, shutter] : shutters) {
                Scene scene;
                if (!load(path, animation, frame, shutter, scene)) {
                    hasAnimation = false;
                    break;
                }
                const Image reference = test::render("accumulation", scene, kWidth, kHeight, test::withOption("samples", "256"), nullptr,
                                                     ShadingMode::Unlit, kAa);
                for (const char* method : {"motion-path", "analytic"}) {
                    const Image image = test::render(method, scene, kWidth, kHeight, OptionMap(), nullptr, ShadingMode::Unlit, kAa);
                    const double db = psnr(reference, image);
                    EXPECT_GE(db, kMinAgreementDb) << path << " animation " << animation << " frame " << frame << " shutter " << shutter
                                                   << ": " << method;
                }
                ++numCases;
            }
            if (!hasAnimation) break;
        }
    }
    std::printf("%d cases\n", numCases);
    EXPECT_GT(numCases, test::kSanitized ? 12 : 60);
}

}  // namespace streak
