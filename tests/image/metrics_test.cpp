#include "image/metrics.h"

#include "image/color.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace streak {
namespace {

// An image from display-space (encoded) values, so tests can reason in what the metrics see.
template <typename Fn>
Image fromEncoded(int width, int height, Fn encodedAt) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec3 e = encodedAt(x, y);
            image.at(x, y) = {srgbToLinear(e.x), srgbToLinear(e.y), srgbToLinear(e.z)};
        }
    return image;
}

// Smooth structure with some edges, values well inside (0, 1).
Image pattern(int width, int height) {
    return fromEncoded(width, height, [](int x, int y) {
        const float v = 0.5f + 0.3f * std::sin(x / 3.0f) * std::cos(y / 5.0f) + ((x / 8 + y / 8) % 2 ? 0.1f : -0.1f);
        return glm::vec3(v, 0.8f * v + 0.1f, 1.0f - v);
    });
}

// image plus Gaussian noise of the given standard deviation in display space.
Image noisy(const Image& image, float sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, sigma);
    Image out = image;
    for (glm::vec3& p : out.pixels())
        for (int c = 0; c < 3; ++c) p[c] = srgbToLinear(std::clamp(linearToSrgb(p[c]) + noise(rng), 0.0f, 1.0f));
    return out;
}

TEST(Metrics, PsnrIdenticalIsInfinite) {
    const Image a = pattern(9, 7);
    EXPECT_EQ(psnr(a, a), std::numeric_limits<double>::infinity());
    // Differences beyond what a PNG holds (above 1, below 0) are invisible to the metrics.
    Image b = a;
    b.at(0, 0) = glm::vec3(5.0f);
    Image c = a;
    c.at(0, 0) = glm::vec3(1.0f);
    c.at(1, 0) = glm::vec3(-2.0f);
    b.at(1, 0) = glm::vec3(0.0f);
    EXPECT_EQ(psnr(b, c), std::numeric_limits<double>::infinity());
}

TEST(Metrics, PsnrKnownValue) {
    // 2x2 images, 12 samples. a is black. b is black except encoded R = 1 at (0,0) and encoded
    // G = 51/255 = 0.2 at (1,1). MSE = (1^2 + 0.2^2) / 12 = 1.04 / 12 = 0.0866667;
    // PSNR = 10 log10(1 / MSE) = 10 log10(11.538462) = 10.621479 dB.
    const Image a(2, 2);
    Image b(2, 2);
    b.at(0, 0).x = srgb8ToLinear(255);
    b.at(1, 1).y = srgb8ToLinear(51);
    EXPECT_NEAR(psnr(a, b), 10.621479, 1e-4);
}

TEST(Metrics, PsnrKnownValueUniformError) {
    // Every sample off by 0.1 in display space: MSE = 0.01, PSNR = 20 dB.
    const Image a = fromEncoded(3, 5, [](int, int) { return glm::vec3(0.4f); });
    const Image b = fromEncoded(3, 5, [](int, int) { return glm::vec3(0.5f); });
    EXPECT_NEAR(psnr(a, b), 20.0, 1e-4);
}

TEST(Metrics, PsnrIsSymmetric) {
    const Image a = pattern(17, 11);
    const Image b = noisy(a, 0.05f, 7);
    EXPECT_EQ(psnr(a, b), psnr(b, a));
    EXPECT_TRUE(std::isfinite(psnr(a, b)));
    EXPECT_GT(psnr(a, noisy(a, 0.01f, 7)), psnr(a, b));
}

TEST(Metrics, ForegroundPsnrKnownValue) {
    // Five pixels, encoded 8-bit values; foreground: a channel of either image above 2/255.
    //   0: both black                      background
    //   1: a black, b grey 1/255           background (its error is not counted)
    //   2: a black, b red 3/255            foreground: error (3/255)^2
    //   3: a grey 0.5, b grey 0.4 (encoded) foreground: error 3 * 0.1^2
    //   4: a green 255, b green 255        foreground, no error
    // Foreground: 3 pixels, 9 samples. MSE = ((3/255)^2 + 0.03) / 9; PSNR = 24.751222 dB.
    // Whole image: (3 (1/255)^2 + (3/255)^2 + 0.03) / 15: 26.963067 dB.
    Image a(5, 1), b(5, 1);
    b.at(1, 0) = glm::vec3(srgb8ToLinear(1));
    b.at(2, 0).x = srgb8ToLinear(3);
    a.at(3, 0) = glm::vec3(srgbToLinear(0.5f));
    b.at(3, 0) = glm::vec3(srgbToLinear(0.4f));
    a.at(4, 0).y = b.at(4, 0).y = srgb8ToLinear(255);
    const ForegroundPsnr foreground = foregroundPsnr(a, b);
    EXPECT_EQ(foreground.pixels, 3u);
    EXPECT_NEAR(foreground.psnr, 24.751222, 1e-3);
    EXPECT_NEAR(psnr(a, b), 26.963067, 1e-3);
    // Symmetric: "either image".
    EXPECT_EQ(foregroundPsnr(b, a).pixels, 3u);
    EXPECT_EQ(foregroundPsnr(b, a).psnr, foreground.psnr);
    // A threshold of 0 takes pixel 1 in: 12 samples, ((3 (1/255)^2 + (3/255)^2 + 0.03) / 12,
    // 25.993966 dB. A threshold of 0.45 keeps pixels 3 and 4: 0.03 / 6, 23.010300 dB.
    EXPECT_EQ(foregroundPsnr(a, b, 0.0f).pixels, 4u);
    EXPECT_NEAR(foregroundPsnr(a, b, 0.0f).psnr, 25.993966, 1e-3);
    EXPECT_EQ(foregroundPsnr(a, b, 0.45f).pixels, 2u);
    EXPECT_NEAR(foregroundPsnr(a, b, 0.45f).psnr, 23.010300, 1e-3);
}

TEST(Metrics, ForegroundPsnrOfBlackAndIdenticalImages) {
    // No foreground at all: nothing differs, +infinity over 0 pixels.
    const ForegroundPsnr black = foregroundPsnr(Image(4, 3), Image(4, 3));
    EXPECT_EQ(black.pixels, 0u);
    EXPECT_EQ(black.psnr, std::numeric_limits<double>::infinity());
    const Image a = pattern(9, 7);
    const ForegroundPsnr same = foregroundPsnr(a, a);
    EXPECT_EQ(same.pixels, 63u);
    EXPECT_EQ(same.psnr, std::numeric_limits<double>::infinity());
    EXPECT_THROW(foregroundPsnr(Image(4, 3), Image(3, 4)), Error);
}

TEST(Metrics, SsimIdenticalIsOne) {
    for (const auto& [w, h] : {std::pair{32, 24}, std::pair{1, 1}, std::pair{3, 2}, std::pair{1, 40}}) {
        const Image a = noisy(pattern(w, h), 0.1f, 3);
        EXPECT_DOUBLE_EQ(ssim(a, a), 1.0) << w << "x" << h;
    }
}

TEST(Metrics, SsimOfConstantImages) {
    // No variance, so only the luminance term is left: (2 mx my + C1) / (mx^2 + my^2 + C1)
    // with mx = 0.5, my = 0.25, C1 = 0.0001: 0.2501 / 0.3126 = 0.8000640.
    const Image a = fromEncoded(13, 12, [](int, int) { return glm::vec3(0.5f); });
    const Image b = fromEncoded(13, 12, [](int, int) { return glm::vec3(0.25f); });
    EXPECT_NEAR(ssim(a, b), 0.8000640, 1e-5);
    EXPECT_NEAR(ssim(b, a), 0.8000640, 1e-5);
}

TEST(Metrics, SsimMatchesReference) {
    // Reference from a direct (non-separable) double-precision evaluation in Python, with the
    // same edge clamping:
    //   g = [exp(-i*i / 4.5) for i in -5..5], normalised; cl(v, n) = min(max(v, 0), n - 1)
    //   mean(f, x, y) = sum g[i] g[j] f(cl(x+i, W), cl(y+j, H)) over i, j in -5..5
    //   ssim = average over pixels of (2 mx my + C1)(2 sxy + C2) / ((mx^2 + my^2 + C1)(sxx + syy + C2))
    // Grey images, so luma equals the encoded value.
    auto a = [](int x, int y) { return float((x * 7 + y * 13) % 17) / 16.0f; };
    auto b = [&](int x, int y) { return 0.8f * a(x, y) + 0.1f * float((x * 5 + y * 3) % 11) / 10.0f; };
    const Image imageA = fromEncoded(13, 9, [&](int x, int y) { return glm::vec3(a(x, y)); });
    const Image imageB = fromEncoded(13, 9, [&](int x, int y) { return glm::vec3(b(x, y)); });
    EXPECT_NEAR(ssim(imageA, imageB), 0.9643420, 2e-6);
}

TEST(Metrics, SsimNoisyCopyIsBelowOne) {
    const Image a = pattern(40, 32);
    const double value = ssim(a, noisy(a, 0.05f, 11));
    EXPECT_LT(value, 0.99);
    EXPECT_GT(value, 0.0);
}

TEST(Metrics, SsimDropsWithMoreNoise) {
    const Image a = pattern(40, 32);
    const double light = ssim(a, noisy(a, 0.02f, 5));
    const double medium = ssim(a, noisy(a, 0.08f, 5));
    const double heavy = ssim(a, noisy(a, 0.25f, 5));
    EXPECT_GT(light, medium);
    EXPECT_GT(medium, heavy);
    EXPECT_GT(heavy, 0.0);
    EXPECT_LT(light, 1.0);
}

TEST(Metrics, SsimWorksBelowWindowSize) {
    const Image a = pattern(5, 3);
    const double value = ssim(a, noisy(a, 0.1f, 2));
    EXPECT_TRUE(std::isfinite(value));
    EXPECT_LT(value, 1.0);
    EXPECT_GT(value, 0.0);
}

TEST(Metrics, SsimInvertedStructureIsNegative) {
    const Image a = fromEncoded(16, 16, [](int x, int y) { return glm::vec3((x + y) % 2 ? 1.0f : 0.0f); });
    const Image b = fromEncoded(16, 16, [](int x, int y) { return glm::vec3((x + y) % 2 ? 0.0f : 1.0f); });
    EXPECT_LT(ssim(a, b), -0.9);
}

TEST(Metrics, SizeMismatchThrows) {
    const Image a(4, 3), b(3, 4);
    EXPECT_THROW(psnr(a, b), Error);
    EXPECT_THROW(ssim(a, b), Error);
    EXPECT_THROW(errorHeatmap(a, b), Error);
    EXPECT_THROW(psnr(Image(), Image()), Error);
    EXPECT_THROW(ssim(Image(), Image()), Error);
}

TEST(Metrics, HeatmapBlackWhereEqual) {
    const Image a = pattern(6, 5);
    double maxError = -1.0;
    const Image same = errorHeatmap(a, a, &maxError);
    EXPECT_EQ(maxError, 0.0);
    ASSERT_EQ(same.width(), 6);
    ASSERT_EQ(same.height(), 5);
    for (const glm::vec3& p : same.pixels()) EXPECT_EQ(p, glm::vec3(0.0f));

    Image b = a;
    b.at(2, 3) = glm::vec3(1.0f) - a.at(2, 3);
    const Image heat = errorHeatmap(a, b, &maxError);
    EXPECT_GT(maxError, 0.0);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 6; ++x)
            if (x == 2 && y == 3)
                EXPECT_EQ(heat.at(x, y), glm::vec3(1.0f));  // the largest error is white
            else
                EXPECT_EQ(heat.at(x, y), glm::vec3(0.0f)) << x << "," << y;
}

TEST(Metrics, HeatmapRampAndMaxError) {
    // Encoded errors 0, 0.05, 0.1, 0.15, 0.2 map to the ramp's stops 0, 1/4, 1/2, 3/4, 1:
    // black, blue, red, yellow, white.
    const Image a(5, 1);
    const Image b = fromEncoded(5, 1, [](int x, int) { return glm::vec3(0.05f * x); });
    double maxError = 0.0;
    const Image heat = errorHeatmap(a, b, &maxError);
    EXPECT_NEAR(maxError, 0.2, 1e-6);
    const glm::vec3 expected[] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
    for (int x = 0; x < 5; ++x)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(heat.at(x, 0)[c], expected[x][c], 1e-4) << x << "," << c;

    // Displayed brightness grows with the error all along the ramp.
    const Image fine = fromEncoded(41, 1, [](int x, int) { return glm::vec3(0.01f * x); });
    const Image fineHeat = errorHeatmap(Image(41, 1), fine);
    auto luma = [](glm::vec3 p) {
        const glm::vec3 e = linearToSrgb(p);
        return 0.299f * e.x + 0.587f * e.y + 0.114f * e.z;
    };
    for (int x = 1; x < 41; ++x) EXPECT_LT(luma(fineHeat.at(x - 1, 0)), luma(fineHeat.at(x, 0))) << x;
}

}  // namespace
}  // namespace streak
