#include "raster/moving_triangle.h"
#include "raster/edge_batch.h"
#include "util/simd.h"
#include "util/random.h"

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

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

namespace {

std::array<glm::vec4, 3> atW1(glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    return {glm::vec4(a, 0.0f, 1.0f), glm::vec4(b, 0.0f, 1.0f), glm::vec4(c, 0.0f, 1.0f)};
}

}  // namespace

TEST(MovingTriangleInsideSpans, TranslatingTriangleEntersWhenItsEdgeArrives) {
    // The right triangle x >= -1, y >= -1, x + y <= 0 moving +1 in x: at (1.2, -0.9) the
    // hypotenuse arrives when 1.2 - u - 0.9 = 0, u = 0.3, and the sample stays inside to the end.
    const MovingTriangle moving(atW1({-1, -1}, {1, -1}, {-1, 1}), atW1({0, -1}, {2, -1}, {0, 1}));
    std::array<double, 8> b;
    ASSERT_EQ(moving.insideSpans({1.2, -0.9}, 0.1, false, b), 2);
    EXPECT_NEAR(b[0], 0.3, 1e-12);
    EXPECT_EQ(b[1], 1.0);
    // A sample it never reaches, and one it covers throughout.
    EXPECT_EQ(moving.insideSpans({3.0, 0.5}, 0.1, false, b), 0);
    ASSERT_EQ(moving.insideSpans({0.0, -0.5}, 0.1, false, b), 2);
    EXPECT_EQ(b[0], 0.0);
    EXPECT_EQ(b[1], 1.0);
}

TEST(MovingTriangleInsideSpans, RotatingEdgeLeavesAtTheClosedFormTime) {
    // A = (0, 0) and C = (1, 1) fixed, B sliding from (1, 0) to (0, 1): edge AB turns about A and
    // passes the sample (a, b) when (1 - u) b = u a, u = b / (a + b) (for these samples, before
    // edge BC, which turns too, reaches them).
    const MovingTriangle moving(atW1({0, 0}, {1, 0}, {1, 1}), atW1({0, 0}, {0, 1}, {1, 1}));
    for (const glm::dvec2 p : {glm::dvec2(0.3, 0.1), glm::dvec2(0.5, 0.2), glm::dvec2(0.9, 0.05)}) {
        std::array<double, 8> b;
        ASSERT_EQ(moving.insideSpans(p, 0.1, false, b), 2);
        EXPECT_EQ(b[0], 0.0);
        EXPECT_NEAR(b[1], p.y / (p.x + p.y), 1e-12);
    }
}

TEST(MovingTriangleInsideSpans, TriangleTurningOverIsInsideOnBothSides) {
    // C falls from (0, 1) through the edge AB (y = -1) to (0, -3): the triangle flips at u = 1/2.
    // (0, 0) is inside while C.y = 1 - 4u > 0 (u < 1/4); (0, -2) is inside, clockwise, once
    // C.y < -2 (u > 3/4); a tangent sample on AB's line outside the edge never is.
    const MovingTriangle moving(atW1({-1, -1}, {1, -1}, {0, 1}), atW1({-1, -1}, {1, -1}, {0, -3}));
    std::array<double, 8> b;
    ASSERT_EQ(moving.insideSpans({0.0, 0.0}, 0.1, false, b), 2);
    EXPECT_EQ(b[0], 0.0);
    EXPECT_NEAR(b[1], 0.25, 1e-12);
    ASSERT_EQ(moving.insideSpans({0.0, -2.0}, 0.1, false, b), 2);
    EXPECT_NEAR(b[0], 0.75, 1e-12);
    EXPECT_EQ(b[1], 1.0);
    EXPECT_FALSE(moving.isFrontFacing(0.9));
    EXPECT_TRUE(moving.isFrontFacing(0.1));
}

TEST(MovingTriangleInsideSpans, RandomsMatchPointInTriangleAtManyTimes) {
    // Random moving triangles and samples: inside at a time strictly within a span, outside
    // strictly between spans, checked against a 2D point-in-triangle test of the corners at
    // that time (away from the span ends, where rounding decides).
    Rng rng(23);
    int checked = 0;
    for (int i = 0; i < 300; ++i) {
        auto randomCorner = [&] { return glm::vec2(rng.uniform(-1, 1), rng.uniform(-1, 1)); };
        const auto open = atW1(randomCorner(), randomCorner(), randomCorner());
        const auto close = atW1(randomCorner(), randomCorner(), randomCorner());
        const MovingTriangle moving(open, close);
        const glm::dvec2 p(rng.uniform(-1, 1), rng.uniform(-1, 1));
        std::array<double, 8> b;
        const int n = moving.insideSpans(p, 0.1, false, b);
        ASSERT_EQ(n % 2, 0);
        for (int k = 0; k < 64; ++k) {
            const double u = (k + 0.5) / 64.0;
            bool nearEnd = false, inSpan = false;
            for (int j = 0; j < n; ++j) nearEnd = nearEnd || std::abs(u - b[j]) < 1e-6;
            for (int j = 0; j + 1 < n; j += 2) inSpan = inSpan || (u > b[j] && u < b[j + 1]);
            if (nearEnd) continue;
            const auto c = cornersAt(open, close, float(u));
            auto side = [&](int e) {
                const glm::dvec2 a(c[e].x, c[e].y), d(c[(e + 1) % 3].x, c[(e + 1) % 3].y);
                return (d.x - a.x) * (p.y - a.y) - (d.y - a.y) * (p.x - a.x);
            };
            const double s0 = side(0), s1 = side(1), s2 = side(2);
            if (std::min({std::abs(s0), std::abs(s1), std::abs(s2)}) < 1e-5) continue;
            const bool inside = (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0);
            EXPECT_EQ(inside, inSpan) << "triangle " << i << " u " << u;
            ++checked;
        }
    }
    EXPECT_GT(checked, 15000);
}

TEST(MovingTriangleStaysOutside, NeverSkipsASampleWithASpan) {
    // Random moving triangles of one orientation, at random points and at points on or within
    // rounding of an edge or a corner at the shutter's ends: wherever staysOutside holds,
    // insideSpans finds nothing, and it holds for most points far outside.
    Rng rng(29);
    int outside = 0, nearEdge = 0;
    for (int i = 0; i < 400; ++i) {
        auto randomCorner = [&] { return glm::vec2(rng.uniform(-1, 1), rng.uniform(-1, 1)); };
        const auto open = atW1(randomCorner(), randomCorner(), randomCorner());
        const auto close = atW1(randomCorner(), randomCorner(), randomCorner());
        const int orientation = isBackFacingThroughout(open, close) ? -1
                                : isBackFacingThroughout({open[0], open[2], open[1]}, {close[0], close[2], close[1]}) ? 1
                                                                                                                     : 0;
        const MovingTriangle moving(open, close);
        for (int k = 0; k < 40; ++k) {
            glm::dvec2 p(rng.uniform(-3, 3), rng.uniform(-3, 3));
            if (k % 2 == 1) {
                // On the edge from corner e to e + 1 at u = 0 or 1, nudged by about the tolerance.
                const auto& c = rng.uniform(0, 1) < 0.5 ? open : close;
                const int e = int(rng.uniform(0, 3)) % 3;
                const double s = k % 4 == 1 ? rng.uniform(0, 1) : 0.0;
                const glm::dvec2 a(c[e].x, c[e].y), b(c[(e + 1) % 3].x, c[(e + 1) % 3].y);
                p = a + s * (b - a) + glm::dvec2(rng.uniform(-1, 1), rng.uniform(-1, 1)) * 1e-7;
                ++nearEdge;
            }
            if (!moving.staysOutside(p, orientation)) continue;
            ASSERT_NE(orientation, 0);
            std::array<double, 8> b;
            EXPECT_EQ(moving.insideSpans(p, 0.1, false, b), 0) << "triangle " << i << " point " << k;
            ++outside;
        }
    }
    EXPECT_GT(outside, 1000);
    EXPECT_GT(nearEdge, 7000);
}

// solvedSpans's shortcut (two edges beyond their tolerance bound with opposite signs put a piece
// outside without building its edge vectors) changes nothing: over random moving triangles and
// samples on and near their edges, it gives bit for bit the spans of the plain rule, every
// piece between sorted breaks tested at its midpoint by isInsideByEdges, written out here.
TEST(MovingTriangleInsideSpans, SolvedSpansEqualThePlainBreakMidpointRule) {
    Rng rng(77);
    int spans = 0;
    for (int i = 0; i < 3000; ++i) {
        auto randomCorner = [&] { return glm::vec2(rng.uniform(-1, 1), rng.uniform(-1, 1)); };
        std::array<glm::vec4, 3> open = atW1(randomCorner(), randomCorner(), randomCorner());
        std::array<glm::vec4, 3> close = i % 2 == 0 ? atW1(randomCorner(), randomCorner(), randomCorner()) : open;
        for (glm::vec4& c : close) c += glm::vec4(rng.uniform(-0.3f, 0.3f), rng.uniform(-0.3f, 0.3f), 0.0f, 0.0f);
        if (i % 3 == 0)
            for (glm::vec4& c : close) c *= rng.uniform(0.5f, 2.0f);
        const MovingTriangle moving(open, close);
        const MovingTriangle::EdgeTerms terms = moving.edgeTerms();
        for (int k = 0; k < 60; ++k) {
            glm::dvec2 p(rng.uniform(-1.2f, 1.2f), rng.uniform(-1.2f, 1.2f));
            if (k % 2 == 1) {
                const auto& c = k % 4 == 1 ? open : close;
                const int e = k % 3;
                const glm::dvec2 a(c[e].x, c[e].y), b(c[(e + 1) % 3].x, c[(e + 1) % 3].y);
                p = a + double(rng.uniform(0, 1)) * (b - a) + glm::dvec2(rng.uniform(-1, 1), rng.uniform(-1, 1)) * 1e-7;
            }
            const std::array<Quadratic, 3> q = moving.edgeFunctions(p);
            std::vector<double> breaks{0.0, 1.0};
            for (const Quadratic& edge : q) {
                double roots[2];
                const int m = solveQuadratic(edge, roots);
                for (int r = 0; r < m; ++r)
                    if (roots[r] > 0.0 && roots[r] < 1.0) breaks.push_back(roots[r]);
            }
            std::sort(breaks.begin(), breaks.end());
            std::vector<double> expected;
            bool wasInside = false;
            for (std::size_t j = 0; j + 1 < breaks.size(); ++j) {
                if (!(breaks[j + 1] > breaks[j])) continue;
                const double u = 0.5 * (breaks[j] + breaks[j + 1]);
                std::array<glm::dvec3, 3> edges;
                for (int e = 0; e < 3; ++e) edges[std::size_t(e)] = (terms.a[e] * u + terms.b[e]) * u + terms.c[e];
                const bool inside = isInsideByEdges(edges, p, {q[0](u), q[1](u), q[2](u)});
                if (inside != wasInside) expected.push_back(breaks[j]);
                wasInside = inside;
            }
            if (wasInside) expected.push_back(1.0);
            std::array<double, 8> bounds;
            const int n = moving.solvedSpans(p, 0.0, false, bounds);
            ASSERT_EQ(std::size_t(n), expected.size()) << "triangle " << i << " sample " << k;
            for (int j = 0; j < n; ++j) ASSERT_EQ(bounds[std::size_t(j)], expected[std::size_t(j)]);
            spans += n / 2;
        }
    }
    EXPECT_GT(spans, 10000);
}

// A still triangle's row range holds every sample that staysOutside does not cull: random
// triangles (both orientations, axis-aligned edges), random rows, and points inside, on edges
// and near them; beyond the range staysOutside holds, so a box loop may skip those samples.
TEST(MovingTriangleStill, RowRangesHoldEverySampleNotCulled) {
    Rng rng(57);
    int inRange = 0, outOfRange = 0;
    for (int i = 0; i < 500; ++i) {
        auto randomCorner = [&] { return glm::vec2(rng.uniform(-1, 1), rng.uniform(-1, 1)); };
        std::array<glm::vec4, 3> corners = atW1(randomCorner(), randomCorner(), randomCorner());
        if (i % 7 == 0) corners[1] = glm::vec4(corners[0].x, corners[2].y, 0.0f, corners[0].w);
        if (i % 11 == 0) corners[2].y = corners[0].y;  // a horizontal edge: rows along it
        if (i % 3 == 0)
            for (glm::vec4& c : corners) c *= rng.uniform(0.5f, 3.0f);
        const MovingTriangle still(corners, corners);
        for (const int orientation : {1, -1}) {
            for (int k = 0; k < 40; ++k) {
                const int e = k % 3;
                const glm::dvec2 a(corners[e].x / corners[e].w, corners[e].y / corners[e].w);
                const glm::dvec2 b(corners[(e + 1) % 3].x / corners[(e + 1) % 3].w, corners[(e + 1) % 3].y / corners[(e + 1) % 3].w);
                // On an edge, near one, or anywhere.
                glm::dvec2 p = a + double(rng.uniform(0, 1)) * (b - a);
                if (k % 4 == 1) p += glm::dvec2(rng.uniform(-1, 1), rng.uniform(-1, 1)) * 1e-6;
                if (k % 4 == 2) p = glm::dvec2(rng.uniform(-1, 1), rng.uniform(-1, 1));
                if (k % 4 == 3) p.y = a.y;
                p = glm::clamp(p, -0.999, 0.999);
                double xLo = 0.0, xHi = 0.0;
                const bool hasRange = still.stillRowRange(p.y, orientation, xLo, xHi);
                if (still.staysOutside(p, orientation)) continue;
                ASSERT_TRUE(hasRange) << "triangle " << i << " point " << k;
                ASSERT_GE(p.x, xLo) << "triangle " << i << " point " << k;
                ASSERT_LE(p.x, xHi) << "triangle " << i << " point " << k;
                ++inRange;
            }
            // Beyond the range, every point of the row stays outside.
            for (int k = 0; k < 10; ++k) {
                const double y = rng.uniform(-1, 1);
                double xLo = 0.0, xHi = 0.0;
                if (!still.stillRowRange(y, orientation, xLo, xHi)) xLo = 2.0, xHi = -2.0;
                for (int j = 0; j < 50; ++j) {
                    const double x = rng.uniform(-0.999, 0.999);
                    if (x >= xLo && x <= xHi) continue;
                    EXPECT_TRUE(still.staysOutside({x, y}, orientation)) << "triangle " << i;
                    ++outOfRange;
                }
            }
        }
    }
    EXPECT_GT(inRange, 10000);
    EXPECT_GT(outOfRange, 50000);
}

TEST(MovingTriangleStill, TakesTheRasterizersPathWithTheMovingPathsResults) {
    // A triangle with no motion (open == close) takes the still path: its spans must be the
    // solved path's bit for bit, with the same root counts, at random points, at points on its
    // edges and corners (exact and within the on-edge tolerance, where the top-left rule
    // decides), and with the near plane cutting it; and staysOutside must stay conservative.
    Rng rng(31);
    int inside = 0, onEdge = 0, culled = 0;
    for (int i = 0; i < 500; ++i) {
        auto randomCorner = [&] { return glm::vec2(rng.uniform(-1, 1), rng.uniform(-1, 1)); };
        std::array<glm::vec4, 3> corners = atW1(randomCorner(), randomCorner(), randomCorner());
        if (i % 5 == 0)  // corners behind and before a near plane at w = 0.1
            for (glm::vec4& c : corners) c *= rng.uniform(0.05f, 0.4f);
        if (i % 7 == 0) corners[1] = glm::vec4(corners[0].x, corners[2].y, 0.0f, corners[0].w);  // axis-aligned edges
        const MovingTriangle still(corners, corners);
        ASSERT_TRUE(still.isStill());
        const int orientation = isBackFacingThroughout(corners, corners) ? -1
                                : isBackFacingThroughout({corners[0], corners[2], corners[1]}, {corners[0], corners[2], corners[1]}) ? 1
                                                                                                                                     : 0;
        for (int k = 0; k < 20; ++k) {
            glm::dvec2 p(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
            if (k % 2 == 1) {
                const int e = int(rng.uniform(0, 3)) % 3;
                const double s = k % 4 == 1 ? rng.uniform(0, 1) : (k % 8 == 3 ? 0.0 : 0.5);
                const glm::dvec2 a(corners[e].x / corners[e].w, corners[e].y / corners[e].w);
                const glm::dvec2 b(corners[(e + 1) % 3].x / corners[(e + 1) % 3].w, corners[(e + 1) % 3].y / corners[(e + 1) % 3].w);
                p = a + s * (b - a);
                if (k % 3 == 0) p += glm::dvec2(rng.uniform(-1, 1), rng.uniform(-1, 1)) * 1e-7;
                ++onEdge;
            }
            for (const bool checkNear : {false, true}) {
                std::array<double, 8> fast{}, solved{};
                RootCaseCounts fastCounts, solvedCounts;
                const int n = still.insideSpans(p, 0.1, checkNear, fast, &fastCounts);
                ASSERT_EQ(n, still.solvedSpans(p, 0.1, checkNear, solved, &solvedCounts)) << "triangle " << i << " point " << k;
                for (int j = 0; j < n; ++j) ASSERT_EQ(fast[std::size_t(j)], solved[std::size_t(j)]);
                EXPECT_EQ(fastCounts.constant, solvedCounts.constant);
                inside += n > 0;
                if (!checkNear && still.staysOutside(p, orientation)) {
                    EXPECT_EQ(n, 0) << "triangle " << i << " point " << k;
                    ++culled;
                }
            }
        }
    }
    EXPECT_GT(inside, 2000);
    EXPECT_GT(onEdge, 4000);
    EXPECT_GT(culled, 1000);
    // A corner that moves by the least float step is not still.
    std::array<glm::vec4, 3> open = atW1({0, 0}, {1, 0}, {0, 1}), close = open;
    close[2].x = std::nextafter(close[2].x, 1.0f);
    EXPECT_FALSE(MovingTriangle(open, close).isStill());
}

TEST(MovingTriangleStill, SamplesAreThePlainHomogeneousEvaluationAtEveryTime) {
    // A still triangle's barycentrics, depth and facing (sample, and the centre and neighbours
    // of sampleWithNeighbours, which the shading of every still span takes, and stillSample from
    // the edge values) are the plain
    // homogeneous evaluation of its corners (evaluateHomogeneousXyw: what a rasterizer
    // computes) bit for bit, whatever time is asked: with no motion, nothing depends on u.
    Rng rng(47);
    int valid = 0;
    for (int i = 0; i < 300; ++i) {
        auto randomCorner = [&] { return glm::vec2(rng.uniform(-1, 1), rng.uniform(-1, 1)); };
        std::array<glm::vec4, 3> corners = atW1(randomCorner(), randomCorner(), randomCorner());
        for (glm::vec4& c : corners) c *= rng.uniform(0.05f, 3.0f);  // corners at other depths
        if (i % 9 == 0) corners[2] = corners[0] + (corners[1] - corners[0]) * 0.5f;  // degenerate: in a line
        const MovingTriangle still(corners, corners);
        ASSERT_TRUE(still.isStill());
        const std::array<glm::dvec3, 3> xyw{glm::dvec3(corners[0].x, corners[0].y, corners[0].w), glm::dvec3(corners[1].x, corners[1].y, corners[1].w),
                                            glm::dvec3(corners[2].x, corners[2].y, corners[2].w)};
        for (int k = 0; k < 10; ++k) {
            const glm::dvec2 p(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
            const std::array<glm::dvec2, 2> offsets{glm::dvec2(rng.uniform(0, 0.01), 0.0), glm::dvec2(0.0, -rng.uniform(0, 0.01))};
            const double u = k % 3 == 0 ? 0.0 : k % 3 == 1 ? 1.0 : rng.uniform(0, 1);
            HomogeneousSample centre;
            std::array<HomogeneousSample, 2> neighbours;
            still.sampleWithNeighbours<2>(u, p, offsets, centre, neighbours);
            // stillSample: from the edge values found already, by the sample's own edge
            // functions or by a batch at every SIMD level this CPU runs (analytic's intervals).
            std::vector<std::pair<HomogeneousSample, glm::dvec2>> cases{
                std::pair{still.sample(u, p), p}, std::pair{centre, p}, std::pair{neighbours[0], p + offsets[0]},
                std::pair{neighbours[1], p + offsets[1]}, std::pair{still.stillSample(still.edgeFunctions(p)), p}};
            for (const simd::Level level : {simd::Level::scalar, simd::bestLevel()}) {
                EdgeBatch batch;
                evaluateEdgeBatch(still, 1, &p, 1, 1, batch, level);
                cases.emplace_back(still.stillSample(batch.edges[0]), p);
            }
            for (const auto& [got, at] : cases) {
                const HomogeneousSample want = evaluateHomogeneousXyw(xyw, at);
                ASSERT_EQ(got.isValid, want.isValid) << "triangle " << i << " point " << k;
                EXPECT_EQ(got.isFrontFacing, want.isFrontFacing);
                if (!want.isValid) continue;
                ++valid;
                EXPECT_EQ(got.bary, want.bary) << "triangle " << i << " point " << k << " u " << u;
                EXPECT_EQ(got.viewDepth, want.viewDepth);
            }
        }
    }
    EXPECT_GT(valid, 15000);
}

// A still triangle's facing throughout (one determinant) is what its Bernstein coefficients
// say (eight determinants): on random triangles at any depths, edge-on ones (in a line) and ones
// with a corner at the eye's plane (w 0), both orientations.
TEST(MovingTriangleStill, IsBackFacingThroughoutIsItsBernsteinCoefficientsSign) {
    Rng rng(53);
    int back = 0, front = 0;
    for (int i = 0; i < 2000; ++i) {
        std::array<glm::vec4, 3> c;
        for (glm::vec4& p : c) p = glm::vec4(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(0, 1), rng.uniform(0.01f, 3.0f));
        if (i % 7 == 0) c[2] = c[0] + (c[1] - c[0]) * 0.25f;
        if (i % 11 == 0) c[1].w = 0.0f;
        const std::array<double, 4> b = orientationBernstein(c, c);
        const bool expected = b[0] < 0.0 && b[1] < 0.0 && b[2] < 0.0 && b[3] < 0.0;
        EXPECT_EQ(isBackFacingThroughout(c, c), expected) << i;
        back += expected, front += b[0] > 0.0;
    }
    EXPECT_GT(back, 500);
    EXPECT_GT(front, 500);
}

}  // namespace streak::raster
