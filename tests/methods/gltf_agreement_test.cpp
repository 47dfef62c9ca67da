// Every Khronos sample model in ../shared/scenes, rendered unlit at 320x240 by the reference
// (accumulation, 256 shutter times) and by motion-path: the two agree at 35 dB PSNR or more.
// Stochastic rasterization renders each too, closer to the reference than one instant is, and
// embree at stochastic's ray times agrees with it at 40 dB.
// Each model's shutter is placed where it visibly moves; a render at one instant of the
// shutter differs from the blurred reference by more than the methods differ from each other,
// which proves that the motion is there to agree on.

#include "image/metrics.h"
#include "scene/scene_loader.h"
#include "support/render.h"
#include "support/sanitized.h"
#include "support/shared_scenes.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string_view>

namespace streak {

namespace {

constexpr int kWidth = 320, kHeight = 240;
constexpr double kMinAgreementDb = 35.0;

struct ModelCase {
    const char* name;
    const char* path;        ///< under ../shared/scenes
    double frame;            ///< at 24 frames per second
    double shutter;          ///< frames
    const char* animation;   ///< "" for the first
    int motionKeys;
    // A camera for models that do not move themselves (it may move over the shutter).
    bool hasLookAt = false;
    GltfLookAt lookAt = {};
    glm::vec3 slide{0.0f};  ///< world offset added to the last key of every mesh (object motion)
};

void PrintTo(const ModelCase& model, std::ostream* out) { *out << model.name; }

// Why each shutter: where the motion is large but not wild (a few to tens of pixels).
const ModelCase kModels[] = {
    // Rotating 90 degrees per quarter second: 30 degrees over [0.125, 0.208] s.
    {"AnimatedTriangle", "AnimatedTriangle/glTF/AnimatedTriangle.gltf", 3, 2, "", 3},
    // Spinning about y at 180 degrees per second: 15 degrees over [0.5, 0.583] s.
    {"AnimatedCube", "AnimatedCube/glTF/AnimatedCube.gltf", 12, 2, "", 3},
    // The boxes rise 2.52 units over [0, 1.25] s: [0.5, 0.625] s.
    {"BoxAnimated", "BoxAnimated/glTF-Binary/BoxAnimated.glb", 12, 3, "", 3},
    // The cubic-spline rotation between its second and third keys: curved, so 4 keys.
    {"InterpolationTest", "InterpolationTest/glTF-Binary/InterpolationTest.glb", 12, 3, "CubicSpline Rotation", 4},
    // The bone bends 45 degrees per half second: [0.5, 0.75] s.
    {"SimpleSkin", "SimpleSkin/glTF/SimpleSkin.gltf", 12, 6, "", 4},
    {"RiggedSimple", "RiggedSimple/glTF-Binary/RiggedSimple.glb", 20, 3, "", 3},
    {"RiggedFigure", "RiggedFigure/glTF-Binary/RiggedFigure.glb", 10, 2, "", 3},
    // Mid-stride.
    {"CesiumMan", "CesiumMan/glTF-Binary/CesiumMan.glb", 12, 2, "", 3},
    {"Fox", "Fox/glTF-Binary/Fox.glb", 10, 1, "Run", 3},
    // The weights go from (0, 1) to (1, 1) over [1, 2] s: [1, 1.5] s.
    {"SimpleMorph", "SimpleMorph/glTF/SimpleMorph.gltf", 24, 12, "", 2},
    {"AnimatedMorphCube", "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", 30, 6, "", 3},
    {"MorphStressTest", "MorphStressTest/glTF-Binary/MorphStressTest.glb", 24, 6, "TheWave", 3},
    // Static models. ToyCar (109k triangles): the camera moves a little while it looks at the
    // car. The 1M-triangle spheres: the model slides (about 13 pixels) under a still camera
    // that looks at four of them (10 degrees). A moving camera would make motion-path follow
    // every triangle with four path segments, which for 1M triangles takes gigabytes; and the
    // accumulation reference costs 0.05 s per shutter time even with most spheres off screen.
    // Both shutters keep most samples within motion-path's default fragment and interval
    // budgets: dense meshes blurred further overflow them, and it loses the agreement.
    {"ToyCar", "ToyCar/glTF/ToyCar.gltf", 0, 1, "", 2, true,
     {{-0.03f, 0.025f, 0.05f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, glm::vec3(-0.027f, 0.025f, 0.052f), std::nullopt, 40.0f}},
    {"MetalRoughSpheresNoTextures", "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb", 0, 1, "", 2, true,
     {{0.0028f, 0.0028f, 0.0105f}, {0.0028f, 0.0027f, 0.0f}, {0.0f, 1.0f, 0.0f}, std::nullopt, std::nullopt, 10.0f},
     {0.0001f, 0.0f, 0.0f}},
};

Image render(const std::string& method, const Scene& scene, int samples = 0) {
    return test::render(method, scene, kWidth, kHeight, samples > 0 ? test::withOption("samples", std::to_string(samples)) : OptionMap());
}

class GltfAgreement : public ::testing::TestWithParam<ModelCase> {};

}  // namespace

TEST_P(GltfAgreement, AccumulationAndMotionPathAgree) {
    STREAK_REQUIRE_SHARED_SCENES();
    const ModelCase& model = GetParam();
    // The million triangles of the spheres take 92 s under the sanitizers, on the paths ToyCar
    // (static, dense, its camera moving) and DefaultBudgetsDropNothingOnADenseModel run there.
    if (test::kSanitized && std::string_view(model.name) == "MetalRoughSpheresNoTextures")
        GTEST_SKIP() << "ToyCar runs the same paths under the sanitizers";
    GltfOptions options;
    options.frame = model.frame;
    options.shutter = model.shutter;
    options.animation = model.animation;
    options.motionKeys = model.motionKeys;
    options.aspect = float(kWidth) / float(kHeight);
    if (model.hasLookAt) options.lookAt = model.lookAt;
    Scene scene = loadScene(test::sharedScene(model.path), options);
    if (model.slide != glm::vec3(0.0f))
        for (Mesh& mesh : scene.meshes)
            for (std::size_t v = 0; v < mesh.numVertices(); ++v) mesh.positions[std::size_t(mesh.numKeys - 1) * mesh.numVertices() + v] += model.slide;
    validateScene(scene);
    ASSERT_GT(scene.numTriangles(), 0u);

    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const Image reference = render("accumulation", scene, test::kSanitized ? 64 : 256);
    const auto middle = Clock::now();
    const Image motionPath = render("motion-path", scene);
    const auto end = Clock::now();
    const Image instant = render("accumulation", scene, 1);
    const Image stochastic = render("stochastic", scene, 8);
    const auto last = Clock::now();
    const Image traced = render("embree", scene, 8);  // stochastic's ray times
    const double traceAgreement = psnr(stochastic, traced);
    const double agreement = psnr(reference, motionPath), blur = psnr(reference, instant), noisy = psnr(reference, stochastic);
    std::printf("[ %s ] PSNR %.2f dB (one instant: %.2f dB, stochastic: %.2f dB, embree against stochastic: %.2f dB); "
                "accumulation %.2f s, motion-path %.2f s, stochastic %.2f s\n",
                model.name, agreement, blur, noisy, traceAgreement, std::chrono::duration<double>(middle - start).count(),
                std::chrono::duration<double>(end - middle).count(), std::chrono::duration<double>(last - end).count());
    EXPECT_GE(agreement, kMinAgreementDb);
    EXPECT_LT(blur, agreement - 3.0) << "the shutter shows too little motion to test agreement";
    // The third CPU method renders the model too; with 8 time samples per pixel it is noisy,
    // but closer to the reference than a single instant.
    EXPECT_GT(noisy, blur);
    // Embree traces rays at the very times stochastic samples: the same noise, so they agree
    // far better than either agrees with the reference.
    EXPECT_GE(traceAgreement, 40.0);
    EXPECT_GT(psnr(reference, traced), blur);
}

INSTANTIATE_TEST_SUITE_P(SampleModels, GltfAgreement, ::testing::ValuesIn(kModels),
                         [](const ::testing::TestParamInfo<ModelCase>& info) { return std::string(info.param.name); });

}  // namespace streak
