// The passes (depth, Cryptomatte object and material IDs) of the methods that write them,
// against closed forms: a quad sweeping over another in front of the background.

#include "image/cryptomatte.h"
#include "image/passes.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace streak {
namespace {

constexpr int kWidth = 16, kHeight = 4;

// "wall" (material "grey") at depth 3 covers x < 6; "sweeper" (material "white") at depth 2, in
// front of it, has its right edge sweep x from 2 to 14 over the shutter. At pixel centre x_c the
// sweeper covers s = (14 - x_c) / 12 of the shutter (clamped), the wall the rest where x_c < 6.
Scene sweptWall() {
    Scene scene = test::emptyScene(glm::vec3(0.2f));
    const std::uint32_t grey = test::addMaterial(scene, glm::vec3(0.5f)), white = test::addMaterial(scene, glm::vec3(1.0f));
    scene.materials[grey].name = "grey", scene.materials[white].name = "white";
    test::addPixelQuad(scene, test::PixelCamera{kWidth, kHeight, 3.0f}, grey, -20.0f, -1.0f, 6.0f, 5.0f);
    scene.meshes.back().name = "wall";
    test::addPixelQuad(scene, test::PixelCamera{kWidth, kHeight, 2.0f}, white, -30.0f, -1.0f, 2.0f, 5.0f, 12.0f, 0.0f);
    scene.meshes.back().name = "sweeper";
    validateScene(scene);
    return scene;
}

struct Expected {
    float sweeper, wall;
};
Expected expectedAt(int px) {
    const float xc = float(px) + 0.5f, sweeper = std::clamp((14.0f - xc) / 12.0f, 0.0f, 1.0f);
    return {sweeper, xc < 6.0f ? 1.0f - sweeper : 0.0f};
}

const ImageChannel& channel(const Image& image, const std::string& name) {
    for (const ImageChannel& c : image.channels())
        if (c.name == name) return c;
    ADD_FAILURE() << "no channel " << name;
    static const ImageChannel none;
    return none;
}

// The coverage of `name` at pixel i in type `type`'s ranks.
float coverageOf(const Image& image, const char* type, const std::string& name, int ranks, std::size_t i) {
    float sum = 0.0f;
    for (int r = 0; r < ranks; ++r)
        if (channel(image, cryptomatteChannel(type, r, false)).values[i] == cryptomatteId(name))
            sum += channel(image, cryptomatteChannel(type, r, true)).values[i];
    return sum;
}

void expectPasses(const std::string& method, const OptionMap& options, float coverageTolerance, float depthTolerance) {
    SCOPED_TRACE(method);
    std::unique_ptr<Renderer> renderer = createRenderer(method, OptionMap(options));
    ASSERT_TRUE(renderer->writesPasses());
    RenderSettings settings;
    settings.width = kWidth, settings.height = kHeight, settings.shading = ShadingMode::Unlit;
    settings.passes.depth = settings.passes.objectId = settings.passes.materialId = true;
    settings.passes.cryptoRanks = 3;  // two layers, the last rank in its R and G
    RenderStats stats;
    RenderContext context{stats};
    const Image image = renderer->render(sweptWall(), settings, context);
    for (const char* name : {"Z", "Z.min", "CryptoObject00.r", "CryptoObject00.a", "CryptoObject01.r", "CryptoObject01.a", "CryptoMaterial01.g"})
        EXPECT_EQ(channel(image, name).values.size(), std::size_t(kWidth * kHeight)) << name;
    EXPECT_EQ(image.metadata().at("cryptomatte/" + cryptomatteKey("CryptoObject") + "/name"), "CryptoObject");
    for (int py = 0; py < kHeight; ++py)
        for (int px = 0; px < kWidth; ++px) {
            SCOPED_TRACE("pixel " + std::to_string(px) + "," + std::to_string(py));
            const std::size_t i = std::size_t(py) * kWidth + std::size_t(px);
            const Expected e = expectedAt(px);
            EXPECT_NEAR(coverageOf(image, "CryptoObject", "sweeper", 3, i), e.sweeper, coverageTolerance);
            EXPECT_NEAR(coverageOf(image, "CryptoObject", "wall", 3, i), e.wall, coverageTolerance);
            EXPECT_NEAR(coverageOf(image, "CryptoMaterial", "white", 3, i), e.sweeper, coverageTolerance);
            EXPECT_NEAR(coverageOf(image, "CryptoMaterial", "grey", 3, i), e.wall, coverageTolerance);
            // The coverages sum to alpha; rank 0 holds the larger; the unused rank is empty.
            const float rank0 = channel(image, "CryptoObject00.g").values[i], rank1 = channel(image, "CryptoObject00.a").values[i];
            EXPECT_NEAR(rank0 + rank1, image.alphaAt(px, py), 1e-5f);
            EXPECT_GE(rank0, rank1);
            EXPECT_EQ(channel(image, "CryptoObject01.g").values[i], 0.0f);
            // Depth: the coverage-weighted mean of 2 and 3, and the nearest; 1e10 where nothing shows.
            const float covered = e.sweeper + e.wall;
            const float z = channel(image, "Z").values[i], zMin = channel(image, "Z.min").values[i];
            if (covered == 0.0f) {
                EXPECT_EQ(z, kEmptyDepth);
                EXPECT_EQ(zMin, kEmptyDepth);
                continue;
            }
            EXPECT_NEAR(z, (2.0f * e.sweeper + 3.0f * e.wall) / covered, depthTolerance);
            if (e.sweeper > coverageTolerance) EXPECT_NEAR(zMin, 2.0f, 1e-4f);
            if (e.sweeper == 0.0f) EXPECT_NEAR(zMin, 3.0f, 1e-4f);
        }
}

TEST(PassesMethods, ExactMethodsWriteExactCoveragesAndDepth) {
    for (const char* method : {"motion-path", "analytic", "higher-order"}) expectPasses(method, OptionMap(), 1e-5f, 1e-4f);
}

TEST(PassesMethods, DepthIsTheMeanOverTheShutterAndTheNearestItGets) {
    // A quad filling the image recedes from depth 2 to 4 over the shutter: view depth is linear
    // in time, so Z is 3 and Z.min 2 at every pixel.
    Scene scene = test::emptyScene();
    const test::PixelCamera near{kWidth, kHeight, 2.0f}, far{kWidth, kHeight, 4.0f};
    test::addMovingQuad(scene, test::addMaterial(scene, glm::vec3(1.0f)),
                        {near.at(-8, -8), near.at(-8, 12), near.at(24, 12), near.at(24, -8)}, {far.at(-8, -8), far.at(-8, 12), far.at(24, 12), far.at(24, -8)});
    validateScene(scene);
    for (const char* method : {"motion-path", "analytic", "higher-order"}) {
        std::unique_ptr<Renderer> renderer = createRenderer(method, OptionMap());
        RenderSettings settings;
        settings.width = kWidth, settings.height = kHeight, settings.aa = 2;
        settings.passes.depth = true;
        RenderStats stats;
        RenderContext context{stats};
        const Image image = renderer->render(scene, settings, context);
        for (std::size_t i = 0; i < std::size_t(kWidth * kHeight); ++i) {
            EXPECT_NEAR(channel(image, "Z").values[i], 3.0f, 1e-4f) << method << " pixel " << i;
            EXPECT_NEAR(channel(image, "Z.min").values[i], 2.0f, 1e-4f) << method << " pixel " << i;
        }
    }
}

TEST(PassesMethods, EmbreeWritesItsSampledEstimate) {
    // 64 stratified times: coverages within 1/64; the mean depth as its shares are (one in 64
    // moves it by at most 1/64 of a unit over the covered share).
    expectPasses("embree", test::withOption("samples", "64"), 1.0f / 64.0f + 1e-5f, 0.05f);
}

TEST(PassesMethods, OnlyTheMethodsThatWritePassesSaySo) {
    for (const char* method : {"accumulation", "stochastic", "post-filter", "blur-shell"})
        EXPECT_FALSE(createRenderer(method, OptionMap())->writesPasses()) << method;
}

}  // namespace
}  // namespace streak
