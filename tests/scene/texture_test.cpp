#include "scene/texture.h"
#include "image/color.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

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

TEST(Texture, WrapModesAtEveryTexelOfSizesOddAndPowersOfTwo) {
    // Texel i holds the value i: at texel centres far outside [0, 1] each mode's texel, the
    // remainder written out here, for a width of 3 (wrapped by division) and 4 (by a mask).
    for (const int size : {3, 4})
        for (const WrapMode mode : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge}) {
            std::vector<glm::vec4> texels;
            for (int i = 0; i < size; ++i) texels.push_back(glm::vec4(float(i)));
            const Texture tex = Texture::fromLinear(size, 1, texels, mode, mode);
            for (int i = -3 * size - 1; i <= 3 * size + 1; ++i) {
                int want = std::clamp(i, 0, size - 1);
                if (mode == WrapMode::Repeat) want = ((i % size) + size) % size;
                if (mode == WrapMode::MirroredRepeat) {
                    const int m = ((i % (2 * size)) + 2 * size) % (2 * size);
                    want = m < size ? m : 2 * size - 1 - m;
                }
                EXPECT_EQ(tex.sampleBilinear({(float(i) + 0.5f) / float(size), 0.5f}, 0).x, float(want))
                    << "size " << size << " mode " << int(mode) << " texel " << i;
            }
        }
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

// A lookup's plan (Texture::lookupOf): an isotropic footprint 4 texels across is one tap on
// level 2; one 2 texels across and 16 along is 8 taps on level 1, 2 texels apart along the
// major axis; one that is not finite takes the coarsest level. Planned once, the lookup at
// another point is that point's own (what a still pixel's samples share).
TEST(TextureFootprint, ALookupsPlanIsItsLevelAndItsTapsAlongTheMajorAxis) {
    const Texture tex = stripes([](int x, int y) { return (x + 3 * y) / 5; });  // 256 x 256
    const float t = 1.0f / 256;
    const Texture::Lookup iso = tex.lookupOf({{4.0f * t, 0.0f}, {0.0f, 4.0f * t}});
    EXPECT_EQ(iso.taps, 1);
    EXPECT_NEAR(iso.lod, 2.0f, 1e-5f);
    const Texture::Lookup aniso = tex.lookupOf({{0.0f, 16.0f * t}, {2.0f * t, 0.0f}});
    EXPECT_EQ(aniso.taps, 8);
    EXPECT_NEAR(aniso.lod, 1.0f, 1e-5f);
    EXPECT_NEAR(std::abs(aniso.step.y), 2.0f * t, 1e-7f);
    EXPECT_NEAR(aniso.step.x, 0.0f, 1e-7f);
    const Texture::Lookup wild = tex.lookupOf({{std::numeric_limits<float>::infinity(), 0.0f}, {0.0f, t}});
    EXPECT_EQ(wild.taps, 1);
    EXPECT_EQ(wild.lod, float(tex.numLevels() - 1));
    for (const glm::vec2 uv : {glm::vec2(0.31f, 0.62f), glm::vec2(0.05f, 0.9f)})
        EXPECT_EQ(tex.sample(uv, aniso), tex.sample(uv, TextureFootprint{{0.0f, 16.0f * t}, {2.0f * t, 0.0f}}));
}

// minLod is a floor: the taps widen to it and fewer of them cover the major axis.
TEST(TextureFootprint, MinLodWidensTheTaps) {
    const Texture vertical = stripes([](int x, int) { return x / 4; });
    const glm::vec2 centre(2.0f / 256, 0.5f);
    const TextureFootprint blurred{{1.0f / 256, 0.0f}, {0.0f, 64.0f / 256}, 3.0f};  // 8 texels: two stripes
    EXPECT_NEAR(vertical.sample(centre, blurred).x, vertical.sample(centre, 3.0f).x, 1e-5f);
}

}  // namespace streak

namespace streak {

namespace {

// The box mean of the bilinear level-0 texture over the parallelogram uv + u dx + v dy, u and v
// in [-1/2, 1/2], by brute force: the independent reference for TextureFootprint::isBox. With
// `keep`, only over the points it keeps, and `kept` receives their fraction.
template <class Keep>
glm::vec4 bruteForceBox(const Texture& tex, glm::vec2 uv, glm::vec2 dx, glm::vec2 dy, Keep&& keep, float* kept = nullptr) {
    constexpr int kSteps = 96;
    glm::vec4 sum(0.0f);
    int count = 0;
    for (int j = 0; j < kSteps; ++j)
        for (int i = 0; i < kSteps; ++i) {
            const float u = (float(i) + 0.5f) / kSteps - 0.5f, v = (float(j) + 0.5f) / kSteps - 0.5f;
            const glm::vec2 p = uv + u * dx + v * dy;
            if (!keep(p)) continue;
            sum += tex.sampleBilinear(p, 0);
            ++count;
        }
    if (kept) *kept = float(count) / float(kSteps * kSteps);
    return count > 0 ? sum / float(count) : glm::vec4(0.0f);
}
glm::vec4 bruteForceBox(const Texture& tex, glm::vec2 uv, glm::vec2 dx, glm::vec2 dy) {
    return bruteForceBox(tex, uv, dx, dy, [](glm::vec2) { return true; });
}

// Checks of 3 texels, with a bright 2-texel border every 32 texels: the detail an atlas packs.
Texture checksAndBorders() {
    constexpr int kSize = 128;
    std::vector<glm::vec4> texels(kSize * kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const float check = ((x / 3 + y / 3) % 2 == 0) ? 0.8f : 0.2f;
            const bool border = x % 32 < 2 || y % 32 < 2;
            texels[std::size_t(y) * kSize + x] = glm::vec4(border ? 4.0f : check);
        }
    return Texture::fromLinear(kSize, kSize, texels);
}

}  // namespace

// A box footprint averages the texels of its parallelogram: within 0.03 of the brute-force mean
// on footprints 1 to 24 texels wide, at any slant, and closer to it than the GPU lookup of the
// same footprint (whose bell reaches twice as far: here into the bright borders).
TEST(TextureFootprint, BoxIsTheMeanOverItsParallelogram) {
    const Texture tex = checksAndBorders();
    std::uint32_t state = 12345u;
    auto uniform = [&] { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1u << 24); };
    double boxError = 0.0, lookupError = 0.0, worst = 0.0;
    constexpr int kCases = 300;
    for (int c = 0; c < kCases; ++c) {
        const float width = 1.0f + 23.0f * uniform(), aspect = 0.3f + 0.7f * uniform(), angle = 6.2831853f * uniform();
        const glm::vec2 axis(std::cos(angle), std::sin(angle));
        const glm::vec2 dx = axis * width / 128.0f, dy = glm::vec2(-axis.y, axis.x) * width * aspect / 128.0f;
        const glm::vec2 uv(uniform(), uniform());
        const float truth = bruteForceBox(tex, uv, dx, dy).x;
        const float box = tex.sample(uv, TextureFootprint{dx, dy, 0.0f, true}).x;
        const float lookup = tex.sample(uv, TextureFootprint{dx, dy}).x;
        boxError += std::abs(box - truth), lookupError += std::abs(lookup - truth);
        worst = std::max(worst, double(std::abs(box - truth)));
    }
    boxError /= kCases, lookupError /= kCases;
    EXPECT_LT(boxError, 0.03);
    EXPECT_LT(boxError, 0.5 * lookupError) << "box " << boxError << ", lookup " << lookupError;
    std::printf("box footprint: mean error %.4f (worst %.4f), GPU lookup %.4f\n", boxError, worst, lookupError);
    // A footprint within one texel is one bilinear tap.
    const glm::vec2 uv(0.37f, 0.61f), small(0.4f / 128.0f, 0.0f);
    EXPECT_EQ(tex.sample(uv, TextureFootprint{small, glm::vec2(small.y, small.x), 0.0f, true}), tex.sampleBilinear(uv, 0));
}

// A box less than a texel wide on a magnified texture is one bilinear tap at its centre, which
// is not its mean where it straddles a texel centre (the bilinear surface bends there). A box
// shared by N samples a side takes at least N taps a side on level 0 (boxGrid's fewestTaps), and
// comes as close to the brute-force mean as N x N point samples do. On a coarser level the fewest
// taps change nothing: there the box's longer axis set the level.
TEST(TextureFootprint, ABoxSharedByManySamplesTakesAsManyTapsOnAMagnifiedTexture) {
    const Texture tex = checksAndBorders();
    std::uint32_t state = 777u;
    auto uniform = [&] { return float((state = state * 1664525u + 1013904223u) >> 8) / float(1u << 24); };
    double oneTapError = 0.0, fourTapsError = 0.0;
    constexpr int kCases = 300;
    for (int c = 0; c < kCases; ++c) {
        const float width = 0.3f + 0.6f * uniform(), angle = 6.2831853f * uniform();
        const glm::vec2 axis(std::cos(angle), std::sin(angle));
        const glm::vec2 dx = axis * width / 128.0f, dy = glm::vec2(-axis.y, axis.x) * width / 128.0f;
        const glm::vec2 uv(uniform(), uniform());
        const float truth = bruteForceBox(tex, uv, dx, dy).x;
        const TextureFootprint box{dx, dy, 0.0f, true};
        const glm::vec2 size(128.0f);
        const Texture::BoxGrid plain = tex.boxGrid(glm::length(dx * size), glm::length(dy * size));
        const Texture::BoxGrid four = tex.boxGrid(glm::length(dx * size), glm::length(dy * size), 0.0f, 1.0f, 1, glm::ivec2(4));
        ASSERT_EQ(plain.tapsX * plain.tapsY, 1);
        ASSERT_EQ(four.level, 0);
        ASSERT_EQ(four.tapsX, 4);
        ASSERT_EQ(four.tapsY, 4);
        oneTapError += std::abs(tex.sampleBox(uv, box, plain).x - truth);
        fourTapsError += std::abs(tex.sampleBox(uv, box, four).x - truth);
    }
    oneTapError /= kCases, fourTapsError /= kCases;
    std::printf("a box under a texel: one tap %.5f, 4 x 4 taps %.5f off its mean\n", oneTapError, fourTapsError);
    EXPECT_LT(fourTapsError, 0.25 * oneTapError);
    // On level 2 (a box 40 x 4 texels) the fewest taps leave the grid as it was.
    const Texture::BoxGrid wide = tex.boxGrid(40.0f, 4.0f), wideFour = tex.boxGrid(40.0f, 4.0f, 0.0f, 1.0f, 1, glm::ivec2(4));
    ASSERT_GT(wide.level, 0);
    EXPECT_EQ(wideFour.level, wide.level);
    EXPECT_EQ(wideFour.tapsX, wide.tapsX);
    EXPECT_EQ(wideFour.tapsY, wide.tapsY);
}

// A box's budget (boxGrid's last argument): a quarter of it at one time, all of it over its
// times. A still box 12 texels a side takes level 1 (6 x 6 = 36 taps; level 0 would be 144) with
// the whole budget, level 2 (3 x 3) with a quarter (16 at a time); swept along a path 40
// texels long it takes at most budget / taps times, but always the covering ones (two a width).
TEST(TextureFootprint, ABoxTakesAQuarterOfItsBudgetAtATimeAndItAllOverItsPath) {
    const Texture tex = checksAndBorders();
    for (const int budget : {Texture::kMaxSweptBoxTaps, Texture::kMaxSweptBoxTaps / 4}) {
        const Texture::BoxGrid still = tex.boxGrid(12.0f, 12.0f, 0.0f, 1.0f, 1, glm::ivec2(1), budget);
        EXPECT_LE(still.tapsX * still.tapsY, budget / 4) << budget;
        EXPECT_EQ(still.level, budget == Texture::kMaxSweptBoxTaps ? 1 : 2) << budget;
        EXPECT_EQ(still.tapsX, budget == Texture::kMaxSweptBoxTaps ? 6 : 3) << budget;
        const Texture::BoxGrid swept = tex.boxGrid(12.0f, 12.0f, 40.0f, 2.0f, 32, glm::ivec2(1), budget);
        EXPECT_EQ(swept.level, still.level) << budget;
        const int covering = 7;  // ceil(2 * 40 / 12)
        EXPECT_EQ(swept.tapsAlong, std::max(covering, budget / (swept.tapsX * swept.tapsY))) << budget;
    }
    // The default is the whole budget.
    const Texture::BoxGrid plain = tex.boxGrid(12.0f, 12.0f), whole = tex.boxGrid(12.0f, 12.0f, 0.0f, 1.0f, 1, glm::ivec2(1), Texture::kMaxSweptBoxTaps);
    EXPECT_EQ(plain.level, whole.level);
    EXPECT_EQ(plain.tapsX, whole.tapsX);
}

// Clipped to a uv triangle, a box averages only the texels inside it, and says how much of the
// box that is: on the texture of an atlas, a triangle whose edge crosses the box must not see
// the texels beyond its edge. Brute force over box and triangle is the reference.
TEST(TextureFootprint, ClippedBoxIsTheMeanOverItsPartInsideTheTriangle) {
    const Texture tex = checksAndBorders();
    // A triangle whose long edge runs next to the bright border at x = 64 texels: the boxes
    // straddle it, so an unclipped box sees the border and a clipped one must not.
    const std::array<glm::vec2, 3> triangle{glm::vec2(0.30f, 0.20f), glm::vec2(0.49f, 0.20f), glm::vec2(0.49f, 0.80f)};
    auto inside = [&](glm::vec2 p) {
        auto side = [](glm::vec2 a, glm::vec2 b, glm::vec2 q) { return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x); };
        const float d0 = side(triangle[0], triangle[1], p), d1 = side(triangle[1], triangle[2], p), d2 = side(triangle[2], triangle[0], p);
        return (d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0);
    };
    double clippedError = 0.0, unclippedError = 0.0, coverageError = 0.0;
    constexpr int kCases = 40;
    for (int c = 0; c < kCases; ++c) {
        const float width = 4.0f + 0.25f * float(c);  // 4 to 14 texels
        const glm::vec2 dx(width / 128.0f, 0.0f), dy(0.0f, width / 128.0f);
        const glm::vec2 uv(0.49f - 0.3f * width / 128.0f, 0.3f + 0.012f * float(c));
        float kept = 0.0f, inside01 = 0.0f;
        const float truth = bruteForceBox(tex, uv, dx, dy, inside, &kept).x;
        const float clipped = tex.sampleBox(uv, TextureFootprint{dx, dy, 0.0f, true, &triangle}, &inside01).x;
        const float unclipped = tex.sample(uv, TextureFootprint{dx, dy, 0.0f, true}).x;
        clippedError += std::abs(clipped - truth), unclippedError += std::abs(unclipped - truth);
        coverageError += std::abs(inside01 - kept);
    }
    clippedError /= kCases, unclippedError /= kCases, coverageError /= kCases;
    std::printf("clipped box: mean error %.4f, unclipped %.4f, coverage error %.4f\n", clippedError, unclippedError, coverageError);
    EXPECT_LT(clippedError, 0.05);
    EXPECT_LT(clippedError, 0.25 * unclippedError);
    EXPECT_LT(coverageError, 0.05);
}

// A box under one texel is one tap at its centre, clipped like any other: a centre beyond the
// triangle's edge counts nothing inside and reads the triangle's nearest texels, never the next
// chart of an atlas (here the bright border) at full weight; a centre inside is the plain tap.
TEST(TextureFootprint, AOneTapBoxIsClippedToTheTriangle) {
    const Texture tex = checksAndBorders();
    const std::array<glm::vec2, 3> triangle{glm::vec2(0.30f, 0.20f), glm::vec2(0.49f, 0.20f), glm::vec2(0.49f, 0.80f)};
    const glm::vec2 dx(0.5f / 128.0f, 0.0f), dy(0.0f, 0.5f / 128.0f);
    const glm::vec2 beyond(0.506f, 0.5f);  // on the border at texel x = 64.8, past the edge at 62.7
    ASSERT_GT(tex.sampleBox(beyond, TextureFootprint{dx, dy, 0.0f, true}).x, 3.0f);
    float inside = -1.0f;
    const float clipped = tex.sampleBox(beyond, TextureFootprint{dx, dy, 0.0f, true, &triangle}, &inside).x;
    EXPECT_EQ(inside, 0.0f);
    EXPECT_LT(clipped, 1.0f);
    const glm::vec2 within(0.45f, 0.5f);
    const float plain = tex.sampleBox(within, TextureFootprint{dx, dy, 0.0f, true}).x;
    EXPECT_EQ(tex.sampleBox(within, TextureFootprint{dx, dy, 0.0f, true, &triangle}, &inside).x, plain);
    EXPECT_EQ(inside, 1.0f);
}

}  // namespace streak
