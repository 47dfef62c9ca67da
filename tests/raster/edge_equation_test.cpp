#include "raster/edge_equation.h"
#include "util/random.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace streak::raster {

TEST(SolveQuadratic, ClosedForms) {
    double r[2];
    ASSERT_EQ(solveQuadratic({1.0, -3.0, 2.0}, r), 2);  // (u-1)(u-2)
    EXPECT_DOUBLE_EQ(r[0], 1.0);
    EXPECT_DOUBLE_EQ(r[1], 2.0);
    ASSERT_EQ(solveQuadratic({0.0, 2.0, -1.0}, r), 1);  // linear
    EXPECT_DOUBLE_EQ(r[0], 0.5);
    EXPECT_EQ(solveQuadratic({1.0, 0.0, 1.0}, r), 0);   // no real root
    ASSERT_EQ(solveQuadratic({1.0, -2.0, 1.0}, r), 1);  // double root
    EXPECT_DOUBLE_EQ(r[0], 1.0);
    EXPECT_EQ(solveQuadratic({0.0, 0.0, 1.0}, r), 0);
    // Tiny leading coefficient: the small root stays accurate (cancellation-free form); the
    // exact root of 1e-9 u^2 + u - 1/4 is 1/4 - 1e-9/16 + O(1e-18).
    ASSERT_EQ(solveQuadratic({1e-9, 1.0, -0.25}, r), 2);
    EXPECT_NEAR(r[1], 0.25 - 6.25e-11, 1e-16);
}

TEST(SolveQuadratic, RandomsAreRoots) {
    // Roots built from random factors come back to 1e-9 relative accuracy.
    Rng rng(3);
    for (int i = 0; i < 1000; ++i) {
        const double r0 = rng.uniform(-2.0f, 2.0f), r1 = rng.uniform(-2.0f, 2.0f), k = rng.uniform(0.1f, 10.0f);
        double r[2];
        const int n = solveQuadratic({k, -k * (r0 + r1), k * r0 * r1}, r);
        ASSERT_GE(n, 1);
        const double lo = std::min(r0, r1), hi = std::max(r0, r1);
        EXPECT_NEAR(r[0], lo, 1e-6);
        if (n == 2) {
            EXPECT_NEAR(r[1], hi, 1e-6);
        }
    }
}

TEST(EvaluateHomogeneous, MatchesPerspectiveCorrectBarycentrics) {
    // The 3D midpoint of corners 0 and 1 has barycentrics (1/2, 1/2, 0) wherever it projects,
    // and its view depth is the mean of theirs.
    const std::array<glm::vec4, 3> clip{glm::vec4(-1, -1, 0, 1), glm::vec4(4, -4, 0, 4), glm::vec4(0, 2, 0, 2)};
    const glm::vec4 mid = 0.5f * (clip[0] + clip[1]);
    // Tolerance: the sample point is given in float.
    const HomogeneousSample s = evaluateHomogeneous(clip, {double(mid.x) / mid.w, double(mid.y) / mid.w});
    ASSERT_TRUE(s.isValid);
    EXPECT_NEAR(s.bary.x, 0.5, 1e-7);
    EXPECT_NEAR(s.bary.y, 0.5, 1e-7);
    EXPECT_NEAR(s.bary.z, 0.0, 1e-7);
    EXPECT_NEAR(s.viewDepth, 2.5, 1e-6);
    EXPECT_TRUE(s.isFrontFacing);
    EXPECT_FALSE(evaluateHomogeneous({clip[0], clip[2], clip[1]}, {0.0, 0.0}).isFrontFacing);
}

TEST(MovingEdgeFunction, RootIsWhenTheEdgePassesTheSample) {
    // A vertical edge at x = -0.5 moving to x = +0.5 (w = 2 throughout, NDC x = x / 2): it passes
    // NDC x = 0.1 when x = 0.2, i.e. at u = 0.7. Randomized: random moving edges and random u,
    // the sample placed on the edge at u, must give a root at u.
    const Quadratic q = movingEdgeFunction({-0.5f, -1, 0, 2}, {0.5f, -1, 0, 2}, {-0.5f, 1, 0, 2}, {0.5f, 1, 0, 2}, {0.1, 0.0});
    double r[2];
    const int n = solveQuadratic(q, r);
    ASSERT_GE(n, 1);
    EXPECT_NEAR(r[0], 0.7, 1e-9);

    Rng rng(5);
    for (int i = 0; i < 500; ++i) {
        auto randomClip = [&] { return glm::vec4(rng.uniform(-2, 2), rng.uniform(-2, 2), 0.0f, rng.uniform(0.5f, 3.0f)); };
        const glm::vec4 a0 = randomClip(), a1 = randomClip(), b0 = randomClip(), b1 = randomClip();
        const double u = rng.uniform(), s = rng.uniform();
        const glm::dvec4 a = glm::dvec4(a0) + u * glm::dvec4(a1 - a0), b = glm::dvec4(b0) + u * glm::dvec4(b1 - b0);
        const glm::dvec4 on = a + s * (b - a);
        const Quadratic e = movingEdgeFunction(a0, a1, b0, b1, {on.x / on.w, on.y / on.w});
        EXPECT_NEAR(e(u), 0.0, 1e-6 * (std::abs(e.a) + std::abs(e.b) + std::abs(e.c)));
    }
}

}  // namespace streak::raster
