// The shutter model against its closed forms: curve integrals and inverses, rolling windows,
// positions; and the identity paths that keep a box shutter's images bit for bit.

#include "scene/shutter.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace streak {

TEST(ShutterCurve, BoxIsTheIdentity) {
    const ShutterCurve box;
    EXPECT_TRUE(box.isBox());
    EXPECT_TRUE(ShutterCurve::parse("box").isBox());
    // Any constant weight normalises to the box.
    EXPECT_TRUE(ShutterCurve::parse("0:3,0.25:3,1:3").isBox());
    for (double x : {0.0, 0.1, 0.37, 0.5, 0.99, 1.0}) {
        EXPECT_EQ(box.exposureAt(x), x);
        EXPECT_EQ(box.positionOf(x), x);
    }
}

TEST(ShutterCurve, TriangleIntegratesInClosedForm) {
    // w(x) = 4x up to 1/2, 4(1 - x) after: exposure 2x^2, then 1 - 2(1 - x)^2.
    const ShutterCurve triangle = ShutterCurve::parse("triangle");
    EXPECT_FALSE(triangle.isBox());
    EXPECT_FLOAT_EQ(triangle.weightAt(0.5f), 2.0f);
    EXPECT_FLOAT_EQ(triangle.weightAt(0.25f), 1.0f);
    for (int i = 0; i <= 20; ++i) {
        const double x = i / 20.0;
        const double expected = x <= 0.5 ? 2.0 * x * x : 1.0 - 2.0 * (1.0 - x) * (1.0 - x);
        EXPECT_NEAR(triangle.exposureAt(x), expected, 1e-6) << x;
        EXPECT_NEAR(triangle.positionOf(expected), x, 1e-5) << x;
    }
    // Spelled as points, the same curve.
    const ShutterCurve points = ShutterCurve::parse("0:0,0.5:7,1:0");
    for (double x : {0.1, 0.3, 0.6, 0.85}) EXPECT_NEAR(points.exposureAt(x), triangle.exposureAt(x), 1e-6);
}

TEST(ShutterCurve, TrapezoidNormalisesItsPlateau) {
    // Ramps of 1/4: area 3/4 before normalising, so the plateau weighs 4/3.
    const ShutterCurve trapezoid = ShutterCurve::parse("trapezoid:0.25");
    EXPECT_NEAR(trapezoid.weightAt(0.5f), 4.0f / 3.0f, 1e-6);
    EXPECT_NEAR(trapezoid.exposureAt(0.25), 0.5 * 0.25 * (4.0 / 3.0), 1e-6);
    EXPECT_NEAR(trapezoid.exposureAt(0.5), 0.5, 1e-6);
    EXPECT_NEAR(trapezoid.exposureAt(1.0), 1.0, 1e-12);
}

TEST(ShutterCurve, InverseRoundTripsThroughAClosedStretch) {
    // Open, closed over [0.4, 0.6], open again: no exposure is placed in the closed stretch.
    const ShutterCurve curve = ShutterCurve::parse("0:1,0.3:1,0.4:0,0.6:0,0.7:1,1:1");
    EXPECT_NEAR(curve.exposureAt(0.4), curve.exposureAt(0.6), 1e-9);
    for (int i = 0; i <= 100; ++i) {
        const double u = i / 100.0, x = curve.positionOf(u);
        EXPECT_NEAR(curve.exposureAt(x), u, 1e-6) << u;
        EXPECT_FALSE(x > 0.4 + 1e-6 && x < 0.6 - 1e-6) << u << " placed at " << x;
    }
}

TEST(ShutterCurve, BadCurvesAreRejectedWithTheirReason) {
    for (const std::string text : {"", "gaussian", "trapezoid:0", "trapezoid:0.7", "trapezoid:x", "0:1,0.5:1", "0.1:1,1:1",
                                   "0:1,0.6:1,0.5:1,1:1", "0:-1,1:1", "0:0,1:0", "0:1,nan:1,1:1", "0:1", "0:1;1:1"}) {
        SCOPED_TRACE(text);
        EXPECT_THROW(ShutterCurve::parse(text), Error);
    }
    std::string many = "0:1";
    for (int i = 1; i <= ShutterCurve::kMaxPoints; ++i) many += "," + std::to_string(double(i) / ShutterCurve::kMaxPoints) + ":1";
    EXPECT_THROW(ShutterCurve::parse(many), Error);
}

TEST(ShutterWindow, IdentityKeepsTimeToTheBit) {
    const Shutter shutter;
    const ShutterWindow window = shutter.rowWindow(7, 20);
    ASSERT_TRUE(window.isIdentity());
    for (float a : {0.0f, 0.1f, 0.3333333f, 0.7f})
        for (float b : {0.71f, 0.9f, 1.0f}) {
            EXPECT_EQ(window.measure(a, b), b - a);
            EXPECT_EQ(window.timeAt(a), a);
            EXPECT_EQ(window.timeBetween(a, b, 0.3f), a + 0.3f * (b - a));
        }
}

TEST(ShutterWindow, RollingRowsOpenTopFirstAndEachSeesAllItsExposure) {
    Shutter shutter;
    shutter.rollingDuration = 0.25f;
    shutter.curve = ShutterCurve::parse("triangle");
    const int height = 9;
    for (int row = 0; row < height; ++row) {
        const ShutterWindow w = shutter.rowWindow(row, height);
        EXPECT_NEAR(w.start, 0.75f * float(row) / 8.0f, 1e-7f);
        EXPECT_EQ(w.length, 0.25f);
        EXPECT_NEAR(w.measure(0.0f, 1.0f), 1.0f, 1e-6f);
        EXPECT_EQ(w.measure(0.0f, w.start), 0.0f);
        // The triangle within the window: half the exposure before its middle.
        EXPECT_NEAR(w.exposureAt(w.start + 0.125f), 0.5f, 1e-6f);
        EXPECT_NEAR(w.timeAt(0.5f), w.start + 0.125f, 1e-6f);
    }
    EXPECT_EQ(shutter.rowWindow(0, 1).start, 0.0f);
    EXPECT_THROW(checkRollingDuration(0.0), Error);
    EXPECT_THROW(checkRollingDuration(1.5), Error);
    EXPECT_EQ(checkRollingDuration(1.0), 1.0f);
}

TEST(ShutterPosition, PlacesTheOpenIntervalAroundTheFrame) {
    EXPECT_EQ(shutterOpenFrame(ShutterPosition::Start, 10.0, 0.5), 10.0);
    EXPECT_EQ(shutterOpenFrame(ShutterPosition::Center, 10.0, 0.5), 9.75);
    EXPECT_EQ(shutterOpenFrame(ShutterPosition::End, 10.0, 0.5), 9.5);
    EXPECT_EQ(parseShutterPosition("center"), ShutterPosition::Center);
    EXPECT_THROW(parseShutterPosition("middle"), Error);
}

}  // namespace streak
