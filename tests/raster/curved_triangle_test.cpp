// Generalized edge equations (Gribel et al. 2013) against MovingTriangle, point-in-triangle
// tests at many times, and a closed-form covered fraction.
#include "raster/curved_triangle.h"
#include "util/random.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace streak::raster {

namespace {

using Corners = std::array<CurvedTriangle::Corner, 3>;

// The corners (x, y) at w = 1 of a triangle whose corner i follows control points path[i].
Corners atW1(const std::array<std::array<glm::vec2, 4>, 3>& path, int order) {
    Corners c{};
    for (std::size_t i = 0; i < 3; ++i)
        for (int j = 0; j <= order; ++j) c[i][std::size_t(j)] = glm::vec4(path[i][std::size_t(j)], 0.0f, 1.0f);
    return c;
}

// 2D point-in-triangle of the corners at u: +1 inside, -1 outside, 0 too close to an edge.
int pointInTriangle(const CurvedTriangle& t, double u, const glm::dvec2& p) {
    const std::array<glm::dvec3, 3> c = t.cornersAt(u);
    double s[3];
    for (int e = 0; e < 3; ++e) {
        const glm::dvec2 a = glm::dvec2(c[e]) / c[e].z, d = glm::dvec2(c[(e + 1) % 3]) / c[(e + 1) % 3].z;
        s[e] = (d.x - a.x) * (p.y - a.y) - (d.y - a.y) * (p.x - a.x);
    }
    if (std::min({std::abs(s[0]), std::abs(s[1]), std::abs(s[2])}) < 1e-5) return 0;
    return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0) ? 1 : -1;
}

}  // namespace

TEST(CurvedTriangle, OrderOneIsMovingTrianglesQuadratic) {
    // The generalized control vectors for n = 1 (c0 = p0 x q0, c1 = (p0 x q1 + p1 x q0) / 2,
    // c2 = p1 x q1) are MovingTriangle's quadratic in the Bernstein basis; and its spans are
    // MovingTriangle's bit for bit (order 1 is handed to it).
    Rng rng(3);
    for (int i = 0; i < 200; ++i) {
        std::array<glm::vec4, 3> open, close;
        for (int k = 0; k < 3; ++k) {
            open[std::size_t(k)] = {rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0f, rng.uniform(0.5f, 2.0f)};
            close[std::size_t(k)] = {rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0f, rng.uniform(0.5f, 2.0f)};
        }
        const CurvedTriangle curved(1, {CurvedTriangle::Corner{open[0], close[0]}, CurvedTriangle::Corner{open[1], close[1]},
                                        CurvedTriangle::Corner{open[2], close[2]}});
        const MovingTriangle moving(open, close);
        const glm::dvec2 p(rng.uniform(-1, 1), rng.uniform(-1, 1));
        for (int e = 0; e < 3; ++e) {
            const Bernstein b = curved.edgeFunction(e, p);
            const Quadratic q = moving.edgeFunction(e, p);
            const auto power = b.toPower();
            const double scale = std::abs(q.a) + std::abs(q.b) + std::abs(q.c);
            EXPECT_NEAR(power[0], q.c, 1e-12 * scale);
            EXPECT_NEAR(power[1], q.b, 1e-12 * scale);
            EXPECT_NEAR(power[2], q.a, 1e-12 * scale);
        }
        std::array<double, CurvedTriangle::kMaxSpanBounds> a;
        std::array<double, 8> b;
        const int n = curved.insideSpans(p, 0.1, true, RootSolver::ClosedForm, a);
        ASSERT_EQ(n, moving.insideSpans(p, 0.1, true, b));
        for (int k = 0; k < n; ++k) EXPECT_EQ(a[std::size_t(k)], b[std::size_t(k)]);
    }
}

TEST(CurvedTriangle, RandomQuadraticMotionMatchesPointInTriangleAtManyTimes) {
    // 500 random triangles whose corners move on quadratic (and cubic) Bezier curves: inside at
    // a time strictly within a span, outside strictly between spans, by a 2D point-in-triangle
    // test of the corners at that time, away from span ends and edges (where rounding decides).
    // Both root solvers.
    for (const RootSolver solver : {RootSolver::ClosedForm, RootSolver::BezierClipping})
        for (int order : {2, 3}) {
            Rng rng(29 + std::uint64_t(order));
            int checked = 0, inside = 0;
            for (int i = 0; i < 500; ++i) {
                std::array<std::array<glm::vec2, 4>, 3> path{};
                for (auto& corner : path)
                    for (int j = 0; j <= order; ++j) corner[std::size_t(j)] = {rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f)};
                const CurvedTriangle curved(order, atW1(path, order));
                const glm::dvec2 p(rng.uniform(-0.7f, 0.7f), rng.uniform(-0.7f, 0.7f));
                std::array<double, CurvedTriangle::kMaxSpanBounds> b;
                const int n = curved.insideSpans(p, 0.1, false, solver, b);
                ASSERT_EQ(n % 2, 0);
                for (int k = 0; k < 64; ++k) {
                    const double u = (k + 0.5) / 64.0;
                    bool nearEnd = false, inSpan = false;
                    for (int j = 0; j < n; ++j) nearEnd = nearEnd || std::abs(u - b[std::size_t(j)]) < 1e-6;
                    for (int j = 0; j + 1 < n; j += 2) inSpan = inSpan || (u > b[std::size_t(j)] && u < b[std::size_t(j + 1)]);
                    const int truth = pointInTriangle(curved, u, p);
                    if (nearEnd || truth == 0) continue;
                    EXPECT_EQ(truth > 0, inSpan) << "order " << order << " triangle " << i << " u " << u;
                    ++checked, inside += truth > 0;
                }
            }
            EXPECT_GT(checked, 25000);
            EXPECT_GT(inside, 2000);  // the test sees both answers
        }
}

TEST(CurvedTriangle, RotatingWedgeCoversASampleForTheClosedFormFraction) {
    // A 30-degree wedge with its apex on the view axis turns by 90 degrees about it. A sample at
    // 45 degrees is covered from when the leading edge reaches it (the wedge starts at 0..30:
    // t = 15/90) until the trailing edge does (t = 45/90): 1/3 of the shutter, exactly for the
    // true rotation. Cubic Bezier corners through four poses of the rotation follow the circle
    // to ~1e-3 of its angle; the chords of linear motion are far off.
    const double wedge = std::numbers::pi / 6, turn = std::numbers::pi / 2;
    const auto corner = [&](double angle, double t) {
        return glm::vec2(float(0.9 * std::cos(angle + turn * t)), float(0.9 * std::sin(angle + turn * t)));
    };
    const glm::dvec2 sample(0.5 * std::cos(std::numbers::pi / 4), 0.5 * std::sin(std::numbers::pi / 4));
    const auto coveredFraction = [&](int order) {
        // Samples of the rotation at t = j / order, then the control points through them.
        const auto w = bezierThroughSamples(order);
        std::array<std::array<glm::vec2, 4>, 3> path{};
        for (int j = 0; j <= order; ++j) {
            for (int i = 0; i <= order; ++i) {
                const double t = double(i) / order;
                path[1][std::size_t(j)] += float(w[std::size_t(j)][std::size_t(i)]) * corner(0.0, t);
                path[2][std::size_t(j)] += float(w[std::size_t(j)][std::size_t(i)]) * corner(wedge, t);
            }
        }
        const CurvedTriangle curved(order, atW1(path, order));
        std::array<double, CurvedTriangle::kMaxSpanBounds> b;
        const int n = curved.insideSpans(sample, 0.1, false, RootSolver::ClosedForm, b);
        double covered = 0.0;
        for (int k = 0; k + 1 < n; k += 2) covered += b[std::size_t(k + 1)] - b[std::size_t(k)];
        return covered;
    };
    EXPECT_NEAR(coveredFraction(3), 1.0 / 3.0, 2e-3);
    EXPECT_NEAR(coveredFraction(2), 1.0 / 3.0, 2e-2);
    EXPECT_GT(std::abs(coveredFraction(1) - 1.0 / 3.0), 0.03);  // linear motion: the chord
}

TEST(CurvedTriangle, EdgeTileTestNeverCullsACoveredRectangle) {
    // Random quadratic triangles and rectangles: where missesRectangle says missed, no point of
    // a 5 x 5 grid over the rectangle is inside at any of 64 times (point-in-triangle); and it
    // does cull (a test that cannot cull proves nothing).
    Rng rng(31);
    int culled = 0, kept = 0;
    for (int i = 0; i < 400; ++i) {
        std::array<std::array<glm::vec2, 4>, 3> path{};
        for (auto& corner : path)
            for (int j = 0; j <= 2; ++j) corner[std::size_t(j)] = {rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)};
        const CurvedTriangle curved(2, atW1(path, 2));
        const glm::dvec2 centre(rng.uniform(-1.2f, 1.2f), rng.uniform(-1.2f, 1.2f)), half(rng.uniform(0.01f, 0.2f), rng.uniform(0.01f, 0.2f));
        if (!curved.missesRectangle(centre, half)) {
            ++kept;
            continue;
        }
        ++culled;
        for (int k = 0; k < 64; ++k)
            for (int a = 0; a < 5; ++a)
                for (int b = 0; b < 5; ++b) {
                    const glm::dvec2 p = centre + half * glm::dvec2(a / 2.0 - 1.0, b / 2.0 - 1.0);
                    EXPECT_LT(pointInTriangle(curved, (k + 0.5) / 64.0, p), 1) << "triangle " << i;
                }
    }
    EXPECT_GT(culled, 50);
    EXPECT_GT(kept, 50);
}

}  // namespace streak::raster
