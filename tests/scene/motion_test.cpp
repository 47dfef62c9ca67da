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

TEST(MotionWeights, BezierPiecesAreEachTheirOwnCurveAndJoinAtTheirSharedKeys) {
    // Two quadratic pieces on 5 keys: piece 0 is the curve of keys 0-2 over t in [0, 1/2], piece 1
    // that of keys 2-4 over [1/2, 1], each at its own local time 2t and 2t - 1.
    const float keys[5] = {1.0f, 5.0f, 3.0f, -2.0f, 4.0f};
    const auto quadratic = [](const float* p, float u) { return (1 - u) * (1 - u) * p[0] + 2 * u * (1 - u) * p[1] + u * u * p[2]; };
    for (const float t : {0.0f, 0.1f, 0.3f, 0.45f, 0.5f, 0.55f, 0.8f, 1.0f}) {
        const MotionWeights w = motionWeights(5, MotionInterpolation::Bezier, t, 2);
        EXPECT_EQ(w.count, 3);
        EXPECT_EQ(w.first, t < 0.5f ? 0 : 2);
        const float expected = t < 0.5f ? quadratic(keys, 2 * t) : quadratic(keys + 2, 2 * t - 1);
        EXPECT_NEAR(w.apply(keys), expected, 1e-5f) << t;
    }
    // Continuous at the joint: both sides meet key 2.
    EXPECT_NEAR(motionWeights(5, MotionInterpolation::Bezier, std::nextafter(0.5f, 0.0f), 2).apply(keys), 3.0f, 1e-5f);
    EXPECT_NEAR(motionWeights(5, MotionInterpolation::Bezier, 0.5f, 2).apply(keys), 3.0f, 1e-6f);
    // One piece is the one curve of before, to the bit.
    Rng rng(11);
    for (int trial = 0; trial < 200; ++trial) {
        const int k = 2 + int(rng.next() % 15);
        const float t = rng.uniform();
        const MotionWeights a = motionWeights(k, MotionInterpolation::Bezier, t), b = motionWeights(k, MotionInterpolation::Bezier, t, 1);
        EXPECT_EQ(a.first, b.first);
        EXPECT_EQ(a.count, k);
        for (int i = 0; i < k; ++i) EXPECT_EQ(a.weights[i], b.weights[i]);
    }
    // Pieces of degree 1 are the piecewise-linear keys.
    for (const float t : {0.0f, 0.2f, 0.37f, 0.5f, 0.9f, 1.0f})
        EXPECT_NEAR(motionWeights(5, MotionInterpolation::Bezier, t, 4).apply(keys), motionWeights(5, MotionInterpolation::PiecewiseLinear, t).apply(keys),
                    1e-5f);
}

}  // namespace streak
