#include "raster/swept_hull.h"

#include "raster/moving_triangle.h"
#include "support/swept_points.h"
#include "util/random.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace streak::raster {

using test::poseAt;

// A small triangle translating diagonally sweeps a thin band: the Minkowski sum of the triangle
// (legs 0.01) and its path from (-0.5, -0.5) to (0.5, 0.5). At height y = 0 its x range is
// q.x - q.y over the triangle's points q, [-0.01, 0.01]; the box would be [-0.5, 0.51].
TEST(SweptHull, IsTheBandOfADiagonalSweep) {
    const std::array<glm::vec4, 3> open{glm::vec4(-0.5f, -0.5f, 0, 1), glm::vec4(-0.49f, -0.5f, 0, 1), glm::vec4(-0.5f, -0.49f, 0, 1)};
    std::array<glm::vec4, 3> close = open;
    for (glm::vec4& c : close) c += glm::vec4(1, 1, 0, 0);
    SweptHull hull;
    ASSERT_TRUE(hull.build(open, close));
    EXPECT_EQ(hull.numVertices(), 5);  // the closing pose's right-angle corner lies inside
    // The triangle's area plus the path's length times the triangle's width across it.
    EXPECT_NEAR(hull.area(), 0.00005 + std::sqrt(2.0) * (0.02 / std::sqrt(2.0)), 1e-7);  // float corners
    // The right angle and two of 45 degrees at every time (a translation): the margin's bound
    // of the smallest half-angle sine is sin(45 deg) / 2 (it takes sin(theta / 2) >=
    // sin(theta) / 2), a little under sin(22.5 deg).
    EXPECT_NEAR(hull.margin(), 4.0 * kOnEdgeTolerance / (0.5 * std::sin(M_PI / 4.0)), 1e-10);
    double xLo = 0.0, xHi = 0.0;
    ASSERT_TRUE(hull.rowRange(0.0, xLo, xHi));
    EXPECT_NEAR(xLo, -0.01 - 2.0 * hull.margin(), 1e-7);
    EXPECT_NEAR(xHi, 0.01 + 2.0 * hull.margin(), 1e-7);
    EXPECT_TRUE(hull.rowRange(0.509, xLo, xHi));
    EXPECT_FALSE(hull.rowRange(0.511, xLo, xHi));
    EXPECT_FALSE(hull.rowRange(-0.501, xLo, xHi));
    // A corner behind the eye at an end: no hull.
    std::array<glm::vec4, 3> behind = close;
    behind[1].w = -0.5f;
    EXPECT_FALSE(hull.build(open, behind));
}

// Every sample a moving triangle covers at some time, as insideSpans finds it (the on-edge
// tolerance included), lies in the hull's row range: random segments under perspective (w
// changing), fast and slow, with thin triangles and sharp corners, at random points and at
// points on and near the edges at random times and along a sharp corner's extension.
TEST(SweptHull, HoldsEverySampleTheTriangleCovers) {
    Rng rng(91);
    int covered = 0, onEdge = 0, noHull = 0, outside = 0;
    for (int i = 0; i < 4000; ++i) {
        auto corner = [&](float spread) { return glm::vec4(rng.uniform(-spread, spread), rng.uniform(-spread, spread), 0.0f, 1.0f); };
        std::array<glm::vec4, 3> open{corner(1.0f), corner(1.0f), corner(1.0f)};
        if (i % 3 == 0) {  // small triangles, as a dense mesh has
            open[1] = open[0] + corner(0.02f), open[2] = open[0] + corner(0.02f);
            open[1].w = open[2].w = 1.0f;
        }
        if (i % 5 == 0) {  // thin: corner 2 near edge 0-1, a corner down to about 0.1 degree
            const float t = rng.uniform(0.0f, 1.0f), lift = std::pow(10.0f, rng.uniform(-3.0f, -1.0f));
            const glm::vec4 along = open[1] - open[0];
            open[2] = open[0] + t * along + lift * glm::vec4(-along.y, along.x, 0.0f, 0.0f);
            open[2].w = 1.0f;
        }
        const glm::vec4 motion = corner(i % 2 == 0 ? 1.0f : 0.05f);
        std::array<glm::vec4, 3> close;
        for (int k = 0; k < 3; ++k) {
            close[k] = open[k] + glm::vec4(motion.x, motion.y, 0.0f, 0.0f);
            if (i % 4 == 1) close[k] += corner(0.01f) * glm::vec4(1, 1, 0, 0);  // deforming
        }
        if (i % 2 == 1) {  // perspective: each corner at its own depth at each end
            for (glm::vec4& c : open) c *= rng.uniform(0.5f, 3.0f);
            for (glm::vec4& c : close) c *= rng.uniform(0.5f, 3.0f);
        }
        SweptHull hull;
        if (!hull.build(open, close)) {
            ++noHull;
            continue;
        }
        const MovingTriangle moving(open, close);
        for (int k = 0; k < 200; ++k) {
            bool isOnEdge = false;
            const glm::dvec2 p = test::sweptTestPoint(rng, open, close, k, isOnEdge);
            onEdge += isOnEdge;
            if (std::abs(p.x) > 1.0 || std::abs(p.y) > 1.0) continue;
            std::array<double, 8> bounds;
            if (moving.insideSpans(p, 0.0, false, bounds) == 0) continue;
            ++covered;
            double xLo = 0.0, xHi = 0.0;
            const bool inRow = hull.rowRange(p.y, xLo, xHi) && p.x >= xLo && p.x <= xHi;
            outside += !inRow;
            EXPECT_TRUE(inRow) << "segment " << i << " point " << k << " (" << p.x << ", " << p.y << ")";
            if (!inRow) break;
        }
    }
    EXPECT_EQ(outside, 0);
    EXPECT_GT(covered, 100000);
    EXPECT_GT(onEdge, 300000);
    // Only the sharpest corners go without (the thin fifth, and perspective segments whose
    // depths change severalfold, where the margin's bound of the angle over time is loose).
    EXPECT_LT(noHull, 700);
}

// The margin holds the sharpest corner of the triangle at every time of its segment, not only
// at its ends: margin >= 4 kOnEdgeTolerance / sin(theta(u) / 2) on a fine grid of u, over
// random deforming segments under perspective, many of which are sharper in between than at
// either end (where a margin from the end poses alone falls short).
TEST(SweptHull, MarginHoldsTheSharpestCornerAtEveryTime) {
    auto halfAngleSine = [](const std::array<glm::dvec2, 3>& p) {
        double least = 1.0;
        for (int i = 0; i < 3; ++i) {
            const glm::dvec2 a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
            const double cosine = std::clamp(glm::dot(a, b) / (glm::length(a) * glm::length(b)), -1.0, 1.0);
            least = std::min(least, std::sqrt(0.5 * (1.0 - cosine)));
        }
        return least;
    };
    Rng rng(17);
    int built = 0, sharperInBetween = 0;
    for (int i = 0; i < 3000; ++i) {
        auto corner = [&](float spread) { return glm::vec4(rng.uniform(-spread, spread), rng.uniform(-spread, spread), 0.0f, 1.0f); };
        std::array<glm::vec4, 3> open{corner(0.5f), corner(0.5f), corner(0.5f)}, close;
        for (int k = 0; k < 3; ++k) close[k] = open[k] + corner(0.5f) * glm::vec4(1, 1, 0, 0);  // each corner its own way
        if (i % 2 == 1) {
            for (glm::vec4& c : open) c *= rng.uniform(0.5f, 3.0f);
            for (glm::vec4& c : close) c *= rng.uniform(0.5f, 3.0f);
        }
        SweptHull hull;
        if (!hull.build(open, close)) continue;
        ++built;
        const double ends = std::min(halfAngleSine(poseAt(open, close, 0.0)), halfAngleSine(poseAt(open, close, 1.0)));
        double sharpest = 1.0;
        for (int k = 0; k <= 256; ++k) sharpest = std::min(sharpest, halfAngleSine(poseAt(open, close, k / 256.0)));
        sharperInBetween += sharpest < 0.9 * ends;
        EXPECT_GE(hull.margin(), 4.0 * kOnEdgeTolerance / sharpest) << "segment " << i;
    }
    EXPECT_GT(built, 1000);
    EXPECT_GT(sharperInBetween, 50);
}

}  // namespace streak::raster
