// A pixel's surfaces into deep layers and samples (exposure/sample_passes.h), against closed
// forms: the alphas that composite "over" to the summed shares, and the layering rules.

#include "exposure/sample_passes.h"

#include <gtest/gtest.h>

#include <vector>

namespace streak::exposure {
namespace {

DeepLayer layer(std::uint32_t object, double share, double color, float nearest, float farthest) {
    return {object, share, glm::dvec3(color), nearest, farthest};
}

// Front to back, each sample over what lies behind it, as OpenEXR's flatten of tidy samples.
glm::vec4 compositeOver(const std::vector<DeepSample>& samples) {
    glm::vec3 color(0.0f);
    float alpha = 0.0f;
    for (const DeepSample& s : samples) {
        color += (1.0f - alpha) * s.color;
        alpha += (1.0f - alpha) * s.alpha;
    }
    return glm::vec4(color, alpha);
}

TEST(DeepLayers, SharesSideBySideCompositeOverToTheirSum) {
    // Two surfaces showing at different times of the exposure, 0.3 and 0.5 of it, and the
    // background the remaining 0.2: their alphas are 0.3, then 0.5 of the 0.7 left.
    std::vector<DeepLayer> layers{layer(1, 0.5, 0.25, 3.0f, 3.0f), layer(0, 0.3, 0.3, 2.0f, 2.0f)};
    EXPECT_EQ(layerDeepSurfaces(layers, 16), 0);
    const glm::vec3 background(0.5f);
    std::vector<DeepSample> samples;
    deepSamplesOf(layers, &background, samples);
    ASSERT_EQ(samples.size(), 3u);
    EXPECT_FLOAT_EQ(samples[0].z, 2.0f);
    EXPECT_FLOAT_EQ(samples[0].alpha, 0.3f);
    EXPECT_FLOAT_EQ(samples[0].color.x, 0.3f);
    EXPECT_FLOAT_EQ(samples[1].z, 3.0f);
    EXPECT_FLOAT_EQ(samples[1].alpha, 0.5f / 0.7f);
    EXPECT_FLOAT_EQ(samples[1].color.x, 0.25f / 0.7f);
    EXPECT_FLOAT_EQ(samples[2].z, kEmptyDepth);
    EXPECT_FLOAT_EQ(samples[2].alpha, 1.0f);
    const glm::vec4 flat = compositeOver(samples);
    EXPECT_NEAR(flat.x, 0.3f + 0.25f + 0.2f * 0.5f, 1e-6f);
    EXPECT_NEAR(flat.w, 1.0f, 1e-6f);
    // Without the background: the surfaces' colour, and their summed share as alpha.
    deepSamplesOf(layers, nullptr, samples);
    ASSERT_EQ(samples.size(), 2u);
    EXPECT_NEAR(compositeOver(samples).x, 0.55f, 1e-6f);
    EXPECT_NEAR(compositeOver(samples).w, 0.8f, 1e-6f);
}

TEST(DeepLayers, OneObjectOverOverlappingDepthsIsOneLayerAndTheResultIsTidy) {
    // Object 0 over [2, 2.5] and [2.4, 3] (one smooth surface); object 1 over [2.8, 4], which
    // overlaps it but is another object; object 0 again at [5, 5] (behind: its own layer); and
    // object 2 starting at 5 too (no order between them: joined).
    std::vector<DeepLayer> layers{layer(0, 0.1, 0.1, 2.4f, 3.0f), layer(1, 0.2, 0.2, 2.8f, 4.0f), layer(0, 0.1, 0.1, 2.0f, 2.5f),
                                  layer(0, 0.1, 0.1, 5.0f, 5.0f), layer(2, 0.1, 0.1, 5.0f, 6.0f)};
    EXPECT_EQ(layerDeepSurfaces(layers, 16), 0);
    ASSERT_EQ(layers.size(), 3u);
    EXPECT_EQ(layers[0].object, 0u);
    EXPECT_DOUBLE_EQ(layers[0].share, 0.2);
    EXPECT_FLOAT_EQ(layers[0].nearest, 2.0f);
    EXPECT_FLOAT_EQ(layers[0].farthest, 2.8f);  // held to the next layer's front
    EXPECT_FLOAT_EQ(layers[1].nearest, 2.8f);
    EXPECT_FLOAT_EQ(layers[1].farthest, 4.0f);
    EXPECT_FLOAT_EQ(layers[2].nearest, 5.0f);
    EXPECT_FLOAT_EQ(layers[2].farthest, 6.0f);
    EXPECT_DOUBLE_EQ(layers[2].share, 0.2);
    for (std::size_t i = 0; i + 1 < layers.size(); ++i) EXPECT_LE(layers[i].farthest, layers[i + 1].nearest);
}

TEST(DeepLayers, PastTheBoundTheClosestInDepthAreJoined) {
    // Gaps 1, 0.1, 2 and 0.2 between five layers of different objects: a bound of 3 joins across
    // the two smallest (0.1 and 0.2).
    std::vector<DeepLayer> layers{layer(0, 0.1, 0.1, 1.0f, 1.0f), layer(1, 0.1, 0.1, 2.0f, 2.0f), layer(2, 0.1, 0.1, 2.1f, 2.1f),
                                  layer(3, 0.1, 0.1, 4.1f, 4.1f), layer(4, 0.2, 0.2, 4.3f, 4.5f)};
    EXPECT_EQ(layerDeepSurfaces(layers, 3), 2);
    ASSERT_EQ(layers.size(), 3u);
    EXPECT_FLOAT_EQ(layers[0].nearest, 1.0f);
    EXPECT_FLOAT_EQ(layers[1].nearest, 2.0f);
    EXPECT_FLOAT_EQ(layers[1].farthest, 2.1f);
    EXPECT_DOUBLE_EQ(layers[1].share, 0.2);
    EXPECT_FLOAT_EQ(layers[2].nearest, 4.1f);
    EXPECT_FLOAT_EQ(layers[2].farthest, 4.5f);
    EXPECT_NEAR(layers[2].share, 0.3, 1e-12);
    // A bound of 1 leaves one layer holding every share.
    EXPECT_EQ(layerDeepSurfaces(layers, 1), 2);
    ASSERT_EQ(layers.size(), 1u);
    EXPECT_NEAR(layers[0].share, 0.6, 1e-12);
    EXPECT_FLOAT_EQ(layers[0].farthest, 4.5f);
}

TEST(DeepLayers, AFullyCoveringFrontLeavesNothingBehind) {
    std::vector<DeepLayer> layers{layer(0, 1.0, 0.7, 1.0f, 1.0f), layer(1, 0.0, 0.0, 2.0f, 2.0f)};
    layerDeepSurfaces(layers, 16);
    const glm::vec3 background(1.0f);
    std::vector<DeepSample> samples;
    deepSamplesOf(layers, &background, samples);
    ASSERT_EQ(samples.size(), 1u);
    EXPECT_FLOAT_EQ(samples[0].alpha, 1.0f);
    EXPECT_FLOAT_EQ(samples[0].color.x, 0.7f);
}

}  // namespace
}  // namespace streak::exposure
