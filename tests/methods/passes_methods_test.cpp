// The passes (depth, Cryptomatte object and material IDs, the deep image) of the methods that
// write them, against closed forms: a quad sweeping over another in front of the background.

#include "image/cryptomatte.h"
#include "image/deep_image.h"
#include "image/passes.h"
#include "support/render.h"
#include "support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <string>
#include <tuple>
#include <vector>

namespace streak {
namespace {

constexpr int kWidth = test::kSweptWallWidth, kHeight = test::kSweptWallHeight;

using test::Expected;
using test::expectedAt;
using test::sweptWall;

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
            if (e.sweeper > coverageTolerance) { EXPECT_NEAR(zMin, 2.0f, 1e-4f); }
            if (e.sweeper == 0.0f) { EXPECT_NEAR(zMin, 3.0f, 1e-4f); }
        }
}

// A white quad filling the image, receding from depth 2 to 4 over the shutter.
Scene recedingQuad() {
    Scene scene = test::emptyScene();
    const test::PixelCamera near{kWidth, kHeight, 2.0f}, far{kWidth, kHeight, 4.0f};
    test::addMovingQuad(scene, test::addMaterial(scene, glm::vec3(1.0f)),
                        {near.at(-8, -8), near.at(-8, 12), near.at(24, 12), near.at(24, -8)}, {far.at(-8, -8), far.at(-8, 12), far.at(24, 12), far.at(24, -8)});
    validateScene(scene);
    return scene;
}

TEST(PassesMethods, ExactMethodsWriteExactCoveragesAndDepth) {
    for (const char* method : {"motion-path", "analytic", "higher-order"}) expectPasses(method, OptionMap(), 1e-5f, 1e-4f);
}

TEST(PassesMethods, DepthIsTheMeanOverTheShutterAndTheNearestItGets) {
    // A quad filling the image recedes from depth 2 to 4 over the shutter: view depth is linear
    // in time, so Z is 3 and Z.min 2 at every pixel.
    const Scene scene = recedingQuad();
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

// A render with the deep image (at most maxSamples layers a pixel; the background's sample
// unless `transparent`), unlit.
Image renderDeep(const std::string& method, const Scene& scene, const OptionMap& options, int maxSamples, bool withBackground, int aa,
                 RenderStats& stats) {
    std::unique_ptr<Renderer> renderer = createRenderer(method, OptionMap(options));
    RenderSettings settings;
    settings.width = kWidth, settings.height = kHeight, settings.shading = ShadingMode::Unlit, settings.aa = aa;
    settings.passes.deep = true;
    settings.passes.deepSamples = maxSamples;
    settings.passes.deepBackground = withBackground;
    RenderContext context{stats};
    Image image = renderer->render(scene, settings, context);
    EXPECT_NE(image.deep(), nullptr) << method;
    return image;
}

// A pixel's deep samples composited front to back, each over what lies behind (OpenEXR's
// flatten of tidy samples), after checking they are tidy.
glm::vec4 flattenDeep(std::span<const DeepSample> samples) {
    glm::vec3 color(0.0f);
    float alpha = 0.0f;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        EXPECT_LE(samples[k].z, samples[k].zBack);
        if (k > 0) { EXPECT_LT(samples[k - 1].z, samples[k].z); }
        if (k > 0) { EXPECT_LE(samples[k - 1].zBack, samples[k].z); }
        EXPECT_GE(samples[k].alpha, 0.0f);
        EXPECT_LE(samples[k].alpha, 1.0f);
        color += (1.0f - alpha) * samples[k].color;
        alpha += (1.0f - alpha) * samples[k].alpha;
    }
    return glm::vec4(color, alpha);
}

// Every pixel's deep samples flatten to the image's colour and coverage (with the background's
// sample, to its colour over the background and alpha 1).
void expectDeepFlattensToImage(const Image& image, bool withBackground, float tolerance) {
    for (int py = 0; py < image.height(); ++py)
        for (int px = 0; px < image.width(); ++px) {
            const glm::vec4 flat = flattenDeep(image.deep()->samples(px, py));
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(flat[c], image.at(px, py)[c], tolerance) << "pixel " << px << "," << py;
            EXPECT_NEAR(flat.w, withBackground ? 1.0f : image.alphaAt(px, py), tolerance) << "pixel " << px << "," << py;
        }
}

TEST(PassesMethods, ExactMethodsWriteTheClosedFormDeepSamples) {
    // Per pixel: the sweeper (white, depth 2) with its share s, the wall (grey 0.5, depth 3) with
    // its share w, over what s leaves (alpha w / (1 - s)), and the background (0.2) behind, at
    // 1e10, taking the rest.
    for (const char* method : {"motion-path", "analytic", "higher-order"}) {
        SCOPED_TRACE(method);
        RenderStats stats;
        const Image image = renderDeep(method, sweptWall(), OptionMap(), 16, true, 1, stats);
        for (int py = 0; py < kHeight; ++py)
            for (int px = 0; px < kWidth; ++px) {
                SCOPED_TRACE("pixel " + std::to_string(px) + "," + std::to_string(py));
                const Expected e = expectedAt(px);
                std::vector<DeepSample> expected;
                if (e.sweeper > 0.0f) expected.push_back({2.0f, 2.0f, glm::vec3(e.sweeper), e.sweeper});
                if (e.wall > 0.0f) expected.push_back({3.0f, 3.0f, glm::vec3(0.5f * e.wall / (1.0f - e.sweeper)), e.wall / (1.0f - e.sweeper)});
                if (e.sweeper + e.wall < 1.0f) expected.push_back({kEmptyDepth, kEmptyDepth, glm::vec3(0.2f), 1.0f});
                const std::span<const DeepSample> samples = image.deep()->samples(px, py);
                ASSERT_EQ(samples.size(), expected.size());
                for (std::size_t k = 0; k < samples.size(); ++k) {
                    EXPECT_NEAR(samples[k].z, expected[k].z, 1e-4f * expected[k].z) << "sample " << k;
                    EXPECT_NEAR(samples[k].zBack, expected[k].zBack, 1e-4f * expected[k].zBack) << "sample " << k;
                    EXPECT_NEAR(samples[k].alpha, expected[k].alpha, 1e-5f) << "sample " << k;
                    for (int c = 0; c < 3; ++c) EXPECT_NEAR(samples[k].color[c], expected[k].color[c], 1e-5f) << "sample " << k;
                }
            }
        expectDeepFlattensToImage(image, true, 1e-5f);
        EXPECT_EQ(stats.counter("deep_layers_merged"), 0.0);
    }
}

TEST(PassesMethods, ADeepSampleSpansTheDepthsItShowsAtOverTheShutter) {
    // A quad filling the image recedes from depth 2 to 4 over the shutter: one sample a pixel,
    // from 2 to 4, alpha 1 (nothing of the background).
    const Scene scene = recedingQuad();
    for (const char* method : {"motion-path", "analytic", "higher-order"}) {
        RenderStats stats;
        const Image image = renderDeep(method, scene, OptionMap(), 16, true, 2, stats);
        for (int py = 0; py < kHeight; ++py)
            for (int px = 0; px < kWidth; ++px) {
                const std::span<const DeepSample> samples = image.deep()->samples(px, py);
                ASSERT_EQ(samples.size(), 1u) << method;
                EXPECT_NEAR(samples[0].z, 2.0f, 1e-4f) << method;
                EXPECT_NEAR(samples[0].zBack, 4.0f, 1e-4f) << method;
                EXPECT_NEAR(samples[0].alpha, 1.0f, 1e-6f) << method;
            }
    }
}

TEST(PassesMethods, TransparentDeepHasNoBackgroundSampleAndFlattensToTheCoverage) {
    for (const char* method : {"motion-path", "analytic", "higher-order"}) {
        SCOPED_TRACE(method);
        RenderStats stats;
        const Image image = withTransparentBackground(renderDeep(method, sweptWall(), OptionMap(), 16, false, 2, stats), glm::vec3(0.2f));
        for (int py = 0; py < kHeight; ++py)
            for (int px = 0; px < kWidth; ++px)
                for (const DeepSample& s : image.deep()->samples(px, py)) EXPECT_LT(s.z, kEmptyDepth);
        expectDeepFlattensToImage(image, false, 1e-5f);
    }
}

TEST(PassesMethods, DeepSamplesPastTheBoundAreJoinedAndCounted) {
    // One layer a pixel: where the sweeper and the wall both show (x 2..5, every row) they become
    // one sample from 2 to 3 whose alpha is their summed share; the image is unchanged.
    for (const char* method : {"motion-path", "analytic", "higher-order"}) {
        SCOPED_TRACE(method);
        RenderStats stats;
        const Image image = renderDeep(method, sweptWall(), OptionMap(), 1, true, 1, stats);
        int joined = 0;
        for (int py = 0; py < kHeight; ++py)
            for (int px = 0; px < kWidth; ++px) {
                const Expected e = expectedAt(px);
                const std::span<const DeepSample> samples = image.deep()->samples(px, py);
                ASSERT_FALSE(samples.empty());
                if (e.sweeper > 0.0f && e.wall > 0.0f) {
                    ++joined;
                    EXPECT_NEAR(samples[0].z, 2.0f, 1e-4f);
                    EXPECT_NEAR(samples[0].zBack, 3.0f, 1e-4f);
                    EXPECT_NEAR(samples[0].alpha, e.sweeper + e.wall, 1e-5f);
                }
            }
        EXPECT_EQ(joined, 4 * kHeight);
        EXPECT_EQ(stats.counter("deep_layers_merged"), double(joined));
        EXPECT_EQ(stats.counter("deep_pixels_merged"), double(joined));
        expectDeepFlattensToImage(image, true, 1e-5f);
    }
}

TEST(PassesMethods, TranslucentDeepFlattensToTheImage) {
    // The sweeper at opacity 0.4: it and the wall behind it show at the same times, and still
    // composite to the image (its colour resolved before the shading, the wall's after).
    Scene scene = sweptWall();
    scene.materials[1].opacity = 0.4f;
    for (const char* method : {"motion-path", "analytic", "higher-order"}) {
        SCOPED_TRACE(method);
        RenderStats stats;
        const Image image = renderDeep(method, scene, OptionMap(), 16, true, 2, stats);
        expectDeepFlattensToImage(image, true, 1e-5f);
        // Where the sweeper shows over the wall (which covers the pixel), and where over the
        // background: its alpha is its opacity times its exposure (a share of 0.875 and 0.375).
        for (const auto& [px, sweeper, behind] : {std::tuple{3, 0.875f, 3.0f}, std::tuple{9, 0.375f, kEmptyDepth}}) {
            // (motion-path's translucent resolve leaves the background about 1e-6 where the wall
            // covers: a sample of that share, as its colour has.)
            const std::span<const DeepSample> samples = image.deep()->samples(px, 1);
            ASSERT_GE(samples.size(), 2u) << px;
            if (samples.size() > 2) { EXPECT_LT((1.0f - samples[0].alpha) * (1.0f - samples[1].alpha), 1e-5f); }
            EXPECT_NEAR(samples[0].z, 2.0f, 1e-4f);
            EXPECT_NEAR(samples[0].alpha, 0.4f * sweeper, 1e-5f) << px;
            EXPECT_NEAR(samples[1].z, behind, 1e-4f * behind);
            EXPECT_NEAR(samples[1].alpha, 1.0f, 1e-5f) << px;
        }
    }
    RenderStats stats;
    expectDeepFlattensToImage(renderDeep("embree", scene, test::withOption("samples", "16"), 16, true, 2, stats), true, 1e-5f);
}

TEST(PassesMethods, EmbreeWritesItsSampledDeepSamples) {
    // 64 stratified times: each layer's alpha as its share is, within 1/64.
    RenderStats stats;
    const Image image = renderDeep("embree", sweptWall(), test::withOption("samples", "64"), 16, true, 1, stats);
    for (int px = 0; px < kWidth; ++px) {
        const Expected e = expectedAt(px);
        const std::span<const DeepSample> samples = image.deep()->samples(px, 0);
        if (e.sweeper > 1.0f / 64.0f && e.sweeper < 1.0f) {
            ASSERT_GE(samples.size(), 2u) << px;
            EXPECT_NEAR(samples[0].z, 2.0f, 1e-4f);
            EXPECT_NEAR(samples[0].alpha, e.sweeper, 1.0f / 64.0f + 1e-5f) << px;
        }
    }
    expectDeepFlattensToImage(image, true, 1e-5f);
}

TEST(PassesMethods, AccumulationAndStochasticWriteTheirSampledEstimates) {
    // 64 instants, or 64 stratified times a sample: coverages within 1/64, as embree's.
    expectPasses("accumulation", test::withOption("samples", "64"), 1.0f / 64.0f + 1e-5f, 0.05f);
    expectPasses("stochastic", test::withOption("samples", "64"), 1.0f / 64.0f + 1e-5f, 0.05f);
}

TEST(PassesMethods, SampledDeepSamplesFlattenToTheImage) {
    // The swept wall, opaque and with the sweeper translucent (its fragments composited over
    // the wall): each time's surfaces kept by triangle across the times, which flatten to the
    // image; the sweeper's alpha within 1/16 of its closed form.
    Scene translucent = sweptWall();
    translucent.materials[1].opacity = 0.4f;
    for (const char* method : {"accumulation", "stochastic"})
        for (const Scene* scene : std::initializer_list<const Scene*>{&translucent, nullptr}) {
            SCOPED_TRACE(std::string(method) + (scene ? " translucent" : " opaque"));
            RenderStats stats;
            const Image image = renderDeep(method, scene ? *scene : sweptWall(), test::withOption("samples", "16"), 16, true, 2, stats);
            expectDeepFlattensToImage(image, true, 1e-5f);
            const std::span<const DeepSample> samples = image.deep()->samples(9, 1);
            ASSERT_EQ(samples.size(), 2u);
            EXPECT_NEAR(samples[0].z, 2.0f, 1e-4f);
            EXPECT_NEAR(samples[0].alpha, (scene ? 0.4f : 1.0f) * expectedAt(9).sweeper, 1.0f / 16.0f + 1e-5f);
        }
}

TEST(PassesMethods, OnlyTheMethodsThatWritePassesSaySo) {
    for (const char* method : {"motion-path", "analytic", "higher-order", "embree", "accumulation", "stochastic"})
        EXPECT_TRUE(createRenderer(method, OptionMap())->writesPasses()) << method;
    for (const char* method : {"post-filter", "blur-shell"}) EXPECT_FALSE(createRenderer(method, OptionMap())->writesPasses()) << method;
}

}  // namespace
}  // namespace streak
