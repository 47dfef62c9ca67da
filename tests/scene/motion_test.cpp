#include "scene/motion.h"
#include "util/random.h"

#include <gtest/gtest.h>

#include <cmath>

namespace streak {

TEST(MotionWeights, LinearEndpointsAndMidpoint) {
    const float keys[2] = {2.0f, 6.0f};
    EXPECT_FLOAT_EQ(motionWeights(2, MotionInterpolation::PiecewiseLinear, 0.0f).apply(keys), 2.0f);
    EXPECT_FLOAT_EQ(motionWeights(2, MotionInterpolation::PiecewiseLinear, 1.0f).apply(keys), 6.0f);
    EXPECT_FLOAT_EQ(motionWeights(2, MotionInterpolation::PiecewiseLinear, 0.25f).apply(keys), 3.0f);
    // K = 2 Bezier is the same line.
    EXPECT_FLOAT_EQ(motionWeights(2, MotionInterpolation::Bezier, 0.25f).apply(keys), 3.0f);
}

TEST(MotionWeights, PiecewiseLinearPassesThroughKeys) {
    const float keys[4] = {0.0f, 3.0f, -1.0f, 5.0f};
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(motionWeights(4, MotionInterpolation::PiecewiseLinear, keyTime(k, 4)).apply(keys), keys[k], 1e-6f);
    // Halfway between keys 1 and 2 (t = 0.5).
    EXPECT_NEAR(motionWeights(4, MotionInterpolation::PiecewiseLinear, 0.5f).apply(keys), 1.0f, 1e-6f);
}

TEST(MotionWeights, QuadraticBezierClosedForm) {
    // B(t) = (1-t)^2 P0 + 2 t (1-t) P1 + t^2 P2; at t = 1/2: P0/4 + P1/2 + P2/4.
    const float keys[3] = {1.0f, 5.0f, 3.0f};
    EXPECT_NEAR(motionWeights(3, MotionInterpolation::Bezier, 0.5f).apply(keys), 0.25f + 2.5f + 0.75f, 1e-6f);
    const float t = 0.3f;
    const float expected = (1 - t) * (1 - t) * 1.0f + 2 * t * (1 - t) * 5.0f + t * t * 3.0f;
    EXPECT_NEAR(motionWeights(3, MotionInterpolation::Bezier, t).apply(keys), expected, 1e-6f);
    // Endpoints interpolate; inner control points do not.
    EXPECT_NEAR(motionWeights(3, MotionInterpolation::Bezier, 0.0f).apply(keys), 1.0f, 1e-6f);
    EXPECT_NEAR(motionWeights(3, MotionInterpolation::Bezier, 1.0f).apply(keys), 3.0f, 1e-6f);
}

TEST(MotionWeights, RandomsArePartitionsOfUnityAndBezierStaysInHull) {
    // Weights are a convex combination for every K and t, so a curve through random keys stays
    // within [min key, max key]; tolerance is float rounding of at most 16 terms.
    Rng rng(7);
    for (int trial = 0; trial < 2000; ++trial) {
        const int k = 2 + int(rng.next() % 15);
        const auto mode = rng.next() % 2 ? MotionInterpolation::Bezier : MotionInterpolation::PiecewiseLinear;
        const float t = rng.uniform();
        const MotionWeights w = motionWeights(k, mode, t);
        float sum = 0.0f;
        for (int i = 0; i < w.count; ++i) {
            EXPECT_GE(w.weights[i], 0.0f);
            sum += w.weights[i];
        }
        EXPECT_NEAR(sum, 1.0f, 1e-5f);
        float keys[MotionWeights::kMaxKeys];
        float lo = 1e9f, hi = -1e9f;
        for (int i = 0; i < k; ++i) keys[i] = rng.uniform(-10.0f, 10.0f), lo = std::min(lo, keys[i]), hi = std::max(hi, keys[i]);
        const float v = w.apply(keys);
        EXPECT_GE(v, lo - 1e-4f);
        EXPECT_LE(v, hi + 1e-4f);
    }
}

}  // namespace streak
