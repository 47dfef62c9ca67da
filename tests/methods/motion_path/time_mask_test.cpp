#include "methods/motion_path/time_mask.h"
#include "util/random.h"

#include <gtest/gtest.h>

#include <cmath>

namespace streak::motion_path {

TEST(TimeMask, SpansByCentreInclusion) {
    // n = 8: centres at 1/16, 3/16, ...; [0.25, 0.5) holds the centres of slices 2 and 3.
    const TimeMask m = TimeMask::span(0.25f, 0.5f, 8);
    EXPECT_EQ(m.count(), 2);
    EXPECT_TRUE(m.test(2));
    EXPECT_TRUE(m.test(3));
    EXPECT_FALSE(m.test(4));
    EXPECT_EQ(TimeMask::full(128).count(), 128);
    EXPECT_EQ(TimeMask::full(256).count(), 256);
    EXPECT_TRUE(TimeMask::span(0.3f, 0.3f, 64).isEmpty());
    // Bits past the 64-bit word boundary.
    const TimeMask wide = TimeMask::span(0.2f, 0.8f, 256);
    EXPECT_EQ(wide.count(), 154);  // centres (i + 1/2)/256 in [0.2, 0.8): i = 51 .. 204
    EXPECT_TRUE(wide.test(64) && wide.test(51) && wide.test(204) && !wide.test(205) && !wide.test(50));
}

TEST(TimeMask, ExposedSlicesAreSlicesOfTheRowsExposure) {
    // Triangle curve: [0, 0.5] is half the exposure, [0, 0.25] an eighth.
    const ShutterCurve triangle = ShutterCurve::parse("triangle");
    const ShutterWindow window{0.0f, 1.0f, &triangle};
    EXPECT_EQ(TimeMask::exposed(0.0f, 0.5f, window, 64).count(), 32);
    EXPECT_EQ(TimeMask::exposed(0.0f, 0.25f, window, 64).count(), 8);
    // A rolling row open over [0.5, 0.75]: nothing before it, all of it from 0.5 on.
    const ShutterWindow row{0.5f, 0.25f, nullptr};
    EXPECT_TRUE(TimeMask::exposed(0.0f, 0.5f, row, 64).isEmpty());
    EXPECT_EQ(TimeMask::exposed(0.5f, 1.0f, row, 64), TimeMask::full(64));
    // The identity window is span() itself.
    EXPECT_EQ(TimeMask::exposed(0.3f, 0.7f, ShutterWindow{}, 128), TimeMask::span(0.3f, 0.7f, 128));
}

TEST(TimeMask, OcclusionLogic) {
    const TimeMask front = TimeMask::span(0.0f, 0.5f, 32), back = TimeMask::span(0.25f, 1.0f, 32);
    EXPECT_EQ(back.minus(front).count(), 16);
    EXPECT_EQ((front | back).count(), 32);
    EXPECT_EQ((front & back).count(), 8);
}

TEST(TimeMask, RandomSpansMeasureTheirLengthWithinOneSlice) {
    Rng rng(9);
    for (int bits : {32, 64, 128, 256})
        for (int i = 0; i < 500; ++i) {
            float t0 = rng.uniform(), t1 = rng.uniform();
            if (t0 > t1) std::swap(t0, t1);
            EXPECT_LE(std::abs(float(TimeMask::span(t0, t1, bits).count()) / bits - (t1 - t0)), 1.0f / bits + 1e-6f);
        }
}

}  // namespace streak::motion_path
