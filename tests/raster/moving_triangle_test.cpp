#include "raster/moving_triangle.h"
#include "util/random.h"

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace streak::raster {

namespace {

std::array<glm::vec4, 3> cornersAt(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, float u) {
    return {glm::mix(open[0], close[0], u), glm::mix(open[1], close[1], u), glm::mix(open[2], close[2], u)};
}

}  // namespace

TEST(MovingTriangle, TranslatingTriangleHandComputed) {
    // A right triangle at w = 1 moving 1 NDC unit right: at u = 0.5 its corner 0 sits at
    // (-0.5, -1); the point (0, -0.5) is 1/4 along both legs: barycentrics (1/2, 1/4, 1/4).
    const std::array<glm::vec4, 3> open{glm::vec4(-1, -1, 0, 1), glm::vec4(1, -1, 0, 1), glm::vec4(-1, 1, 0, 1)};
    std::array<glm::vec4, 3> close = open;
    for (glm::vec4& c : close) c.x += 1.0f;
    const MovingTriangle moving(open, close);
    const HomogeneousSample s = moving.sample(0.5, {0.0, -0.5});
    ASSERT_TRUE(s.isValid);
    EXPECT_NEAR(s.bary.x, 0.5, 1e-12);
    EXPECT_NEAR(s.bary.y, 0.25, 1e-12);
    EXPECT_NEAR(s.bary.z, 0.25, 1e-12);
    EXPECT_NEAR(s.viewDepth, 1.0, 1e-12);
    EXPECT_TRUE(s.isFrontFacing);
    // The hypotenuse (edge 1, corners 1 and 2: x + y = u) passes (0.25, 0) at u = 0.25.
    double roots[2];
    ASSERT_EQ(solveQuadratic(moving.edgeFunction(1, {0.25, 0.0}), roots), 1);
    EXPECT_NEAR(roots[0], 0.25, 1e-12);
}

TEST(MovingTriangle, RandomsMatchEvaluationAtEachTime) {
    // Random moving triangles, times and points: sample() equals evaluateHomogeneous() of the
    // corners at u, and edgeFunction() equals movingEdgeFunction(). The corners at u are
    // rounded to float for evaluateHomogeneous, hence the relative tolerance.
    Rng rng(17);
    auto randomClip = [&] { return glm::vec4(rng.uniform(-2, 2), rng.uniform(-2, 2), 0.0f, rng.uniform(0.5f, 3.0f)); };
    int facingChecked = 0;
    for (int i = 0; i < 2000; ++i) {
        const std::array<glm::vec4, 3> open{randomClip(), randomClip(), randomClip()};
        const std::array<glm::vec4, 3> close{randomClip(), randomClip(), randomClip()};
        const MovingTriangle moving(open, close);
        const float u = rng.uniform();
        const glm::dvec2 ndc(rng.uniform(-1, 1), rng.uniform(-1, 1));
        const HomogeneousSample want = evaluateHomogeneous(cornersAt(open, close, u), ndc);
        const HomogeneousSample got = moving.sample(u, ndc);
        ASSERT_EQ(want.isValid, got.isValid);
        // Near-degenerate triangles amplify rounding; compare where the evaluation is stable.
        if (std::abs(want.bary.x) + std::abs(want.bary.y) + std::abs(want.bary.z) < 20.0) {
            EXPECT_NEAR(got.bary.x, want.bary.x, 1e-4);
            EXPECT_NEAR(got.bary.y, want.bary.y, 1e-4);
            EXPECT_NEAR(got.viewDepth, want.viewDepth, 1e-4 * std::abs(want.viewDepth) + 1e-4);
            if (got.isFrontFacing == want.isFrontFacing) ++facingChecked;
            else ADD_FAILURE() << "facing differs at triangle " << i;
        }
        for (int e = 0; e < 3; ++e) {
            const int f = (e + 1) % 3;
            const Quadratic a = moving.edgeFunction(e, ndc), b = movingEdgeFunction(open[e], close[e], open[f], close[f], ndc);
            EXPECT_NEAR(a(u), b(u), 1e-9 * (std::abs(b.a) + std::abs(b.b) + std::abs(b.c) + 1.0));
        }
    }
    EXPECT_GT(facingChecked, 1500);
}

}  // namespace streak::raster
