#include "scene/texture.h"
#include "image/color.h"

#include <gtest/gtest.h>

#include <cmath>

namespace streak {

namespace {

Texture grey2x2(float a, float b, float c, float d, WrapMode wrap = WrapMode::Repeat) {
    return Texture::fromLinear(2, 2, {glm::vec4(a), glm::vec4(b), glm::vec4(c), glm::vec4(d)}, wrap, wrap);
}

}  // namespace

TEST(Texture, MipChainAveragesInLinearLight) {
    const Texture tex = grey2x2(0.0f, 1.0f, 0.5f, 0.5f);
    ASSERT_EQ(tex.numLevels(), 2);
    EXPECT_FLOAT_EQ(tex.texel(1, 0, 0).x, 0.5f);
    // 8-bit sRGB input is decoded before averaging: black and white average to linear 0.5.
    const std::uint8_t rgba[8] = {0, 0, 0, 255, 255, 255, 255, 255};
    const Texture srgb = Texture::fromSrgb8(2, 1, rgba);
    EXPECT_FLOAT_EQ(srgb.texel(1, 0, 0).x, 0.5f);
    EXPECT_FLOAT_EQ(srgb.texel(0, 1, 0).x, 1.0f);
}

TEST(Texture, OddSizesReachOneTexel) {
    std::vector<glm::vec4> texels(5 * 3, glm::vec4(0.25f));
    const Texture tex = Texture::fromLinear(5, 3, texels);
    EXPECT_EQ(tex.width(tex.numLevels() - 1), 1);
    EXPECT_EQ(tex.height(tex.numLevels() - 1), 1);
    EXPECT_FLOAT_EQ(tex.texel(tex.numLevels() - 1, 0, 0).x, 0.25f);
}

TEST(Texture, BilinearAtCentresAndBetween) {
    const Texture tex = grey2x2(0.0f, 1.0f, 0.2f, 0.6f, WrapMode::ClampToEdge);
    EXPECT_FLOAT_EQ(tex.sampleBilinear({0.25f, 0.25f}, 0).x, 0.0f);   // centre of texel (0,0)
    EXPECT_FLOAT_EQ(tex.sampleBilinear({0.75f, 0.75f}, 0).x, 0.6f);   // centre of texel (1,1)
    EXPECT_FLOAT_EQ(tex.sampleBilinear({0.5f, 0.25f}, 0).x, 0.5f);    // between (0,0) and (1,0)
    EXPECT_FLOAT_EQ(tex.sampleBilinear({0.5f, 0.5f}, 0).x, 0.45f);    // all four
}

TEST(Texture, WrapModes) {
    const Texture repeat = grey2x2(0.0f, 1.0f, 0.0f, 1.0f, WrapMode::Repeat);
    const Texture clamp = grey2x2(0.0f, 1.0f, 0.0f, 1.0f, WrapMode::ClampToEdge);
    const Texture mirror = grey2x2(0.0f, 1.0f, 0.0f, 1.0f, WrapMode::MirroredRepeat);
    // u = 1.25 is texel 0 again when repeating, the last texel when clamped, texel 1 mirrored.
    EXPECT_FLOAT_EQ(repeat.sampleBilinear({1.25f, 0.25f}, 0).x, 0.0f);
    EXPECT_FLOAT_EQ(clamp.sampleBilinear({1.25f, 0.25f}, 0).x, 1.0f);
    EXPECT_FLOAT_EQ(mirror.sampleBilinear({1.25f, 0.25f}, 0).x, 1.0f);
    EXPECT_FLOAT_EQ(repeat.sampleBilinear({-0.25f, 0.25f}, 0).x, 1.0f);
}

TEST(Texture, LodFromFootprint) {
    std::vector<glm::vec4> texels(64 * 64, glm::vec4(1.0f));
    const Texture tex = Texture::fromLinear(64, 64, texels);
    // One texel per pixel: level 0; four texels per pixel along the longer axis: level 2.
    EXPECT_NEAR(tex.lodFromFootprint({1.0f / 64, 0}, {0, 1.0f / 64}), 0.0f, 1e-5f);
    EXPECT_NEAR(tex.lodFromFootprint({4.0f / 64, 0}, {0, 1.0f / 64}), 2.0f, 1e-5f);
    EXPECT_FLOAT_EQ(tex.lodFromFootprint({0, 0}, {0, 0}), 0.0f);
}

TEST(Texture, TrilinearBlendsLevels) {
    const Texture tex = grey2x2(0.0f, 1.0f, 0.0f, 0.0f, WrapMode::ClampToEdge);
    const float level0 = tex.sample({0.25f, 0.25f}, 0.0f).x;  // 0
    const float level1 = tex.sample({0.25f, 0.25f}, 1.0f).x;  // mean 0.25
    EXPECT_FLOAT_EQ(level0, 0.0f);
    EXPECT_FLOAT_EQ(level1, 0.25f);
    EXPECT_FLOAT_EQ(tex.sample({0.25f, 0.25f}, 0.5f).x, 0.125f);
    EXPECT_FLOAT_EQ(tex.sample({0.25f, 0.25f}, 9.0f).x, 0.25f);  // clamped to the last level
}

namespace {

// 256 x 256 texels, white where stripe(x, y) is even: stripes 4 texels wide.
template <class Stripe>
Texture stripes(Stripe stripe) {
    std::vector<glm::vec4> texels(256 * 256);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) texels[std::size_t(y) * 256 + x] = glm::vec4(stripe(x, y) % 2 == 0 ? 1.0f : 0.0f);
    return Texture::fromLinear(256, 256, texels);
}

}  // namespace

// A round footprint is one trilinear tap at the level of its diameter.
TEST(TextureFootprint, IsotropicIsOneTrilinearTap) {
    const Texture tex = stripes([](int x, int) { return x / 4; });
    const glm::vec2 uv(0.3f, 0.6f), dx(3.0f / 256, 1.0f / 256), dy(-1.0f / 256, 3.0f / 256);
    EXPECT_FLOAT_EQ(tex.sample(uv, TextureFootprint{dx, dy}).x, tex.sample(uv, tex.lodFromFootprint(dx, dy)).x);
    EXPECT_FLOAT_EQ(tex.sample(uv, TextureFootprint{}).x, tex.sampleBilinear(uv, 0).x);
}

// A footprint 1 texel across the stripes and 64 along them sees one stripe: white at its centre,
// where the longer axis' level (6, 64 texels) would average the stripes to grey.
TEST(TextureFootprint, AnisotropicKeepsTheMinorAxisSharp) {
    const Texture vertical = stripes([](int x, int) { return x / 4; });
    const glm::vec2 centre(2.0f / 256, 0.5f);  // between texels 1 and 2, both white
    const TextureFootprint alongV{{1.0f / 256, 0.0f}, {0.0f, 64.0f / 256}};
    EXPECT_NEAR(vertical.sample(centre, alongV).x, 1.0f, 1e-4f);
    EXPECT_NEAR(vertical.sample(centre, vertical.lodFromFootprint(alongV.duvdx, alongV.duvdy)).x, 0.5f, 0.05f);
    EXPECT_NEAR(vertical.sample(centre + glm::vec2(4.0f / 256, 0.0f), alongV).x, 0.0f, 1e-4f);  // the black stripe
    // Diagonal stripes (across (1,1)), a footprint 1 texel across and 32 along them.
    const Texture diagonal = stripes([](int x, int y) { return (x + y) / 8; });
    const float r = 1.0f / (256 * std::sqrt(2.0f));
    const TextureFootprint slanted{{r, r}, {32.0f * r, -32.0f * r}};
    const glm::vec2 onWhite(2.0f / 256, 2.0f / 256);  // x + y = 4 texels: the middle of stripe 0
    EXPECT_GT(diagonal.sample(onWhite, slanted).x, 0.9f);
    EXPECT_LT(diagonal.sample(onWhite + glm::vec2(4.0f / 256), slanted).x, 0.1f);  // x + y = 12: stripe 1
    EXPECT_NEAR(diagonal.sample(onWhite, diagonal.lodFromFootprint(slanted.duvdx, slanted.duvdy)).x, 0.5f, 0.1f);
}

// minLod is a floor: the taps widen to it and fewer of them cover the major axis.
TEST(TextureFootprint, MinLodWidensTheTaps) {
    const Texture vertical = stripes([](int x, int) { return x / 4; });
    const glm::vec2 centre(2.0f / 256, 0.5f);
    const TextureFootprint blurred{{1.0f / 256, 0.0f}, {0.0f, 64.0f / 256}, 3.0f};  // 8 texels: two stripes
    EXPECT_NEAR(vertical.sample(centre, blurred).x, vertical.sample(centre, 3.0f).x, 1e-5f);
}

}  // namespace streak
