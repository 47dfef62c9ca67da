#include "raster/swept_pieces.h"

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

namespace {

// The distance from p to the triangle (0 inside).
double distanceTo(const std::array<glm::dvec2, 3>& t, const glm::dvec2& p) {
    auto cross = [](const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; };
    const double d0 = cross(t[1] - t[0], p - t[0]), d1 = cross(t[2] - t[1], p - t[1]), d2 = cross(t[0] - t[2], p - t[2]);
    if ((d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0)) return 0.0;
    double best = 1e300;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 a = t[i], b = t[(i + 1) % 3];
        const double s = std::clamp(glm::dot(p - a, b - a) / std::max(glm::dot(b - a, b - a), 1e-300), 0.0, 1.0);
        best = std::min(best, glm::length(p - (a + s * (b - a))));
    }
    return best;
}

}  // namespace

// A small triangle translating diagonally (as in SweptHull's band test) while its corner 2
// crosses edge 0-1 at u = 0.4: no hull holds the whole segment, the pieces' hulls hold three
// quarters of it and piece 1 ([0.25, 0.5], where it turns over) the hull of its six corners. A
// row in piece 0's reach gets the band's width, and so does one in piece 1's (its box, which
// such a piece took before, is 0.26 wide there). A triangle whose corners lie on a line while
// it moves along it has six corners on a line: its pieces take their boxes.
TEST(SweptPieces, HullsThePieceWhereTheTriangleTurnsOverAroundItsCorners) {
    const std::array<glm::vec4, 3> open{glm::vec4(-0.5f, -0.5f, 0, 1), glm::vec4(-0.49f, -0.5f, 0, 1), glm::vec4(-0.5f, -0.49f, 0, 1)};
    std::array<glm::vec4, 3> close = open;
    for (glm::vec4& c : close) c += glm::vec4(1, 1, 0, 0);
    close[2].y -= 0.025f;  // corner 2 at height 0.01 - 0.025 u above edge 0-1: on it at u = 0.4
    SweptHull whole;
    EXPECT_FALSE(whole.build(open, close));
    SweptPieces pieces;
    ASSERT_TRUE(pieces.build(open, close));
    EXPECT_EQ(pieces.numHulls(), 3);
    EXPECT_EQ(pieces.numTurning(), 1);
    double xLo = 0.0, xHi = 0.0;
    // y = -0.4 is reached in piece 0 only (it covers heights -0.5 .. -0.24): the band there is
    // about the triangle's width around x = y.
    ASSERT_TRUE(pieces.rowRange(-0.4, xLo, xHi));
    EXPECT_LT(xHi - xLo, 0.05);
    EXPECT_LT(xLo, -0.4);
    EXPECT_GT(xHi, -0.41);
    // y = -0.1 is in piece 1's reach only. Its six corners' hull crosses it between the hull
    // edge from corner 2 at u = 0.25 to corner 0 at u = 0.5 ((-0.25, -0.24625) to (0, 0)) and
    // corner 1's path ((-0.24, -0.25) to (0.01, 0)). rowRange takes each edge over the rows
    // within the margin (kBoxMargin, and about 1e-6 for the pieces' float ends) and widens by
    // it again.
    ASSERT_TRUE(pieces.rowRange(-0.1, xLo, xHi));
    const double m = SweptPieces::kBoxMargin, leftSlope = 0.25 / 0.24625;
    EXPECT_NEAR(xLo, -0.25 + (-0.1 + 0.24625) * leftSlope - m * (1.0 + leftSlope), 5e-6);
    EXPECT_NEAR(xHi, -0.09 + 2.0 * m, 5e-6);
    EXPECT_LT(xHi - xLo, 0.013);
    // The triangle at u = 0.4 (corner 2 on edge 0-1, all three on y = x - 0.1 + ...) is inside.
    for (int k = 0; k < 3; ++k) {
        const glm::dvec2 p = glm::dvec2(open[std::size_t(k)]) + 0.4 * (glm::dvec2(close[std::size_t(k)]) - glm::dvec2(open[std::size_t(k)]));
        ASSERT_TRUE(pieces.rowRange(p.y, xLo, xHi));
        EXPECT_LE(xLo, p.x);
        EXPECT_GE(xHi, p.x);
    }
    EXPECT_FALSE(pieces.rowRange(0.6, xLo, xHi));
    // Corners on a line, moving along it: no piece has an area to hull, so each takes its box.
    const std::array<glm::vec4, 3> flat{glm::vec4(-0.5f, -0.5f, 0, 1), glm::vec4(-0.45f, -0.45f, 0, 1), glm::vec4(-0.4f, -0.4f, 0, 1)};
    std::array<glm::vec4, 3> flatClose = flat;
    for (glm::vec4& c : flatClose) c += glm::vec4(0.4f, 0.4f, 0, 0);
    SweptPieces line;
    ASSERT_TRUE(line.build(flat, flatClose));
    EXPECT_EQ(line.numHulls(), 0);
    EXPECT_EQ(line.numTurning(), 4);
    // y = -0.42 is in piece 0's box only (corners from -0.5 to -0.3): its whole width.
    ASSERT_TRUE(line.rowRange(-0.42, xLo, xHi));
    EXPECT_NEAR(xLo, -0.5 - SweptPieces::kBoxMargin, 1e-6);
    EXPECT_NEAR(xHi, -0.3 + SweptPieces::kBoxMargin, 1e-6);
    std::array<glm::vec4, 3> behind = close;
    behind[0].w = -1.0f;
    EXPECT_FALSE(pieces.build(open, behind));
}

// Every sample the triangle covers, or comes within the on-edge tolerance's reach of, at a time
// insideSpans finds it inside, lies in the pieces' row range: random segments that turn over
// (corners moving their own ways) under perspective, at random points and at points on and
// near the edges at random times. (Spans at samples far from the triangle at their mid time
// are the on-edge artefact along a collapsing triangle's line, which SweptPieces leaves out, as
// the motion box does; they are counted, and are rare and short.)
TEST(SweptPieces, HoldsEverySampleTheTriangleCovers) {
    Rng rng(4242);
    int covered = 0, turning = 0, artefacts = 0, outside = 0;
    for (int i = 0; i < 3000; ++i) {
        auto corner = [&](float spread) { return glm::vec4(rng.uniform(-spread, spread), rng.uniform(-spread, spread), 0.0f, 1.0f); };
        std::array<glm::vec4, 3> open{corner(0.6f), corner(0.6f), corner(0.6f)}, close;
        if (i % 3 == 0) open[1] = open[0] + corner(0.03f) * glm::vec4(1, 1, 0, 0), open[2] = open[0] + corner(0.03f) * glm::vec4(1, 1, 0, 0);
        const glm::vec4 motion = corner(0.8f) * glm::vec4(1, 1, 0, 0);
        for (int k = 0; k < 3; ++k) close[std::size_t(k)] = open[std::size_t(k)] + motion + corner(i % 3 == 0 ? 0.03f : 0.4f) * glm::vec4(1, 1, 0, 0);
        if (i % 2 == 1) {
            for (glm::vec4& c : open) c *= rng.uniform(0.5f, 3.0f);
            for (glm::vec4& c : close) c *= rng.uniform(0.5f, 3.0f);
        }
        SweptHull whole;
        if (whole.build(open, close)) continue;  // SweptHull's own test covers these
        ++turning;
        SweptPieces pieces;
        ASSERT_TRUE(pieces.build(open, close));
        const MovingTriangle moving(open, close);
        for (int k = 0; k < 300; ++k) {
            bool isOnEdge = false;
            const glm::dvec2 p = test::sweptTestPoint(rng, open, close, k, isOnEdge);
            if (std::abs(p.x) > 1.0 || std::abs(p.y) > 1.0) continue;
            std::array<double, 8> bounds;
            const int n = moving.insideSpans(p, 0.0, false, bounds);
            bool isNear = false;
            for (int j = 0; j + 1 < n; j += 2)
                isNear = isNear || distanceTo(poseAt(open, close, 0.5 * (bounds[j] + bounds[j + 1])), p) <= 1e-5;
            if (n == 0) continue;
            if (!isNear) {
                ++artefacts;
                continue;
            }
            ++covered;
            double xLo = 0.0, xHi = 0.0;
            const bool inRow = pieces.rowRange(p.y, xLo, xHi) && p.x >= xLo && p.x <= xHi;
            outside += !inRow;
            EXPECT_TRUE(inRow) << "segment " << i << " point " << k << " (" << p.x << ", " << p.y << ")";
            if (!inRow) break;
        }
    }
    EXPECT_EQ(outside, 0);
    EXPECT_GT(turning, 500);
    EXPECT_GT(covered, 50000);
    EXPECT_LT(artefacts, covered / 100);
}

}  // namespace streak::raster
