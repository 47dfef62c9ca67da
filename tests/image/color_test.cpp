#include "image/color.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace streak {
namespace {

TEST(Color, KnownValues) {
    EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);
    EXPECT_FLOAT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(linearToSrgb(1.0f), 1.0f);
    // 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357
    EXPECT_NEAR(linearToSrgb(0.5f), 0.735357f, 1e-5f);
    EXPECT_NEAR(srgbToLinear(0.735357f), 0.5f, 1e-5f);
    // Linear toe segment: slope 12.92 below 0.0031308.
    EXPECT_NEAR(linearToSrgb(0.001f), 0.01292f, 1e-7f);
    EXPECT_NEAR(srgbToLinear(0.02f), 0.02f / 12.92f, 1e-9f);
    // Both branches meet at the threshold.
    EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-5f);
    EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-6f);
}

TEST(Color, EncodingClampsOutOfRange) {
    EXPECT_EQ(linearToSrgb(-0.5f), 0.0f);
    EXPECT_EQ(linearToSrgb(7.0f), 1.0f);
    EXPECT_EQ(linearToSrgb(std::numeric_limits<float>::infinity()), 1.0f);
    EXPECT_EQ(linearToSrgb(std::numeric_limits<float>::quiet_NaN()), 0.0f);
    EXPECT_EQ(linearToSrgb8(-1.0f), 0);
    EXPECT_EQ(linearToSrgb8(100.0f), 255);
}

TEST(Color, Vec3IsComponentwise) {
    const glm::vec3 encoded = linearToSrgb(glm::vec3(0.0f, 0.5f, 3.0f));
    EXPECT_EQ(encoded.x, 0.0f);
    EXPECT_EQ(encoded.y, linearToSrgb(0.5f));
    EXPECT_EQ(encoded.z, 1.0f);
}

TEST(Color, AllCodesRoundTrip) {
    for (int code = 0; code < 256; ++code) {
        const float linear = srgb8ToLinear(std::uint8_t(code));
        EXPECT_EQ(linearToSrgb8(linear), code) << "code " << code;
        EXPECT_NEAR(linear, srgbToLinear(code / 255.0f), 1e-6f) << "code " << code;
        EXPECT_NEAR(linearToSrgb(linear) * 255.0f, float(code), 1e-3f) << "code " << code;
    }
    EXPECT_EQ(srgb8ToLinear(0), 0.0f);
    EXPECT_EQ(srgb8ToLinear(255), 1.0f);
}

TEST(Color, TableIsStrictlyIncreasing) {
    for (int code = 1; code < 256; ++code)
        EXPECT_LT(srgb8ToLinear(std::uint8_t(code - 1)), srgb8ToLinear(std::uint8_t(code))) << "code " << code;
}

TEST(Color, EightBitRoundsToNearest) {
    EXPECT_EQ(linearToSrgb8(srgbToLinear(100.4f / 255.0f)), 100);
    EXPECT_EQ(linearToSrgb8(srgbToLinear(100.6f / 255.0f)), 101);
    EXPECT_EQ(linearToSrgb8(srgbToLinear(0.4f / 255.0f)), 0);
    EXPECT_EQ(linearToSrgb8(srgbToLinear(254.6f / 255.0f)), 255);
}

}  // namespace
}  // namespace streak
