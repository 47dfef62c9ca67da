// Generalized edge equations (Gribel et al. 2013) against MovingTriangle, point-in-triangle
// tests at many times, and a closed-form covered fraction.
#include "raster/curved_triangle.h"
#include "util/random.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <bit>
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

namespace {

// Whether some point of a 5 x 5 grid over the rectangle is inside the triangle at one of 16
// times spread over piece `piece` of 4 of the shutter.
bool coversDuringPiece(const CurvedTriangle& curved, int piece, const glm::dvec2& centre, const glm::dvec2& half) {
    for (int k = 0; k < 16; ++k)
        for (int a = 0; a < 5; ++a)
            for (int b = 0; b < 5; ++b)
                if (pointInTriangle(curved, (piece + (k + 0.5) / 16.0) / 4.0, centre + half * glm::dvec2(a / 2.0 - 1.0, b / 2.0 - 1.0)) > 0)
                    return true;
    return false;
}

// A random quadratic triangle with perspective (w in [0.5, 2]) whose corners lie within
// `size` of a centre that swings across the screen.
CurvedTriangle randomCurvedTriangle(Rng& rng, float size) {
    std::array<glm::vec4, 3> centre;
    for (glm::vec4& c : centre) c = {rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), 0.0f, 1.0f};
    Corners corners{};
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) {
            const float w = rng.uniform(0.5f, 2.0f);
            const glm::vec2 xy = glm::vec2(centre[j]) + glm::vec2(rng.uniform(-size, size), rng.uniform(-size, size));
            corners[i][j] = glm::vec4(xy * w, 0.0f, w);
        }
    return CurvedTriangle(2, corners);
}

}  // namespace

TEST(CurvedTriangle, TileTestsNeverCullACoveredPiece) {
    // Random quadratic triangles in perspective, large and small, and rectangles within the
    // viewport: on each quarter of the shutter that the Edge-Tile or the Triangle-Tile test
    // proves missed, no point of a 5 x 5 grid over the rectangle is inside at 16 times of it
    // (point-in-triangle). And each test culls pieces (a test that cannot cull proves nothing).
    Rng rng(31);
    int byEdges = 0, byCorners = 0, kept = 0;
    for (int i = 0; i < 600; ++i) {
        const CurvedTriangle curved = randomCurvedTriangle(rng, i % 2 == 0 ? 1.0f : 0.05f);
        const CurvedTriangle::FrustumSlefes frustum = curved.frustumSlefes(4);
        const glm::dvec2 half(rng.uniform(0.01f, 0.2f), rng.uniform(0.01f, 0.2f));
        const glm::dvec2 centre(rng.uniform(-1.0f, 1.0f) * (1.0 - half.x), rng.uniform(-1.0f, 1.0f) * (1.0 - half.y));
        const CurvedTriangle::PieceMask edges = curved.piecesMissedByEdges(centre, half, 4);
        const CurvedTriangle::PieceMask corners = CurvedTriangle::piecesMissedByCorners(frustum, centre, half);
        for (int piece = 0; piece < 4; ++piece) {
            const bool isEdgeCulled = edges >> piece & 1, isCornerCulled = corners >> piece & 1;
            byEdges += isEdgeCulled, byCorners += isCornerCulled;
            if (!isEdgeCulled && !isCornerCulled) {
                ++kept;
                continue;
            }
            EXPECT_FALSE(coversDuringPiece(curved, piece, centre, half)) << "triangle " << i << " piece " << piece << " edges " << isEdgeCulled;
        }
    }
    EXPECT_GT(byEdges, 200);
    EXPECT_GT(byCorners, 200);
    EXPECT_GT(kept, 200);
}

TEST(CurvedTriangle, TriangleTileTestCullsSmallFastTrianglesTheEdgeTestKeeps) {
    // Gribel et al.'s reason for two tests: a small triangle sweeping far past a tile has edge
    // functions whose padding swamps their values, so the Edge-Tile test proves little, while
    // its corners are provably outside one tile plane.
    Rng rng(7);
    int onlyByCorners = 0, onlyByEdges = 0;
    for (int i = 0; i < 400; ++i) {
        const CurvedTriangle curved = randomCurvedTriangle(rng, 0.01f);
        const glm::dvec2 half(0.02, 0.02), centre(rng.uniform(-0.9f, 0.9f), rng.uniform(-0.9f, 0.9f));
        const CurvedTriangle::PieceMask edges = curved.piecesMissedByEdges(centre, half, 4);
        const CurvedTriangle::PieceMask corners = CurvedTriangle::piecesMissedByCorners(curved.frustumSlefes(4), centre, half);
        onlyByCorners += std::popcount(corners & ~edges), onlyByEdges += std::popcount(edges & ~corners);
    }
    EXPECT_GT(onlyByCorners, 10 * std::max(onlyByEdges, 1));
}

TEST(CurvedTriangle, CornerBoundsAtATilePlaneEncloseTheDistance) {
    // The blend of the frustum planes' slefes (x - a w from x + w and x - w) encloses each
    // corner's distance to the plane x = a w (and y = a w) at 1000 times.
    Rng rng(11);
    for (int i = 0; i < 50; ++i) {
        const CurvedTriangle curved = randomCurvedTriangle(rng, 0.5f);
        const CurvedTriangle::FrustumSlefes s = curved.frustumSlefes(4);
        const double a = rng.uniform(-1.0f, 1.0f);
        for (int k = 0; k <= 1000; ++k) {
            const double u = k / 1000.0, position = u * 4.0;
            const int piece = std::min(3, int(position));
            const double f = position - piece;
            for (std::size_t corner = 0; corner < 3; ++corner) {
                const glm::dvec3 c = curved.corner(int(corner), u);
                for (int axis = 0; axis < 2; ++axis) {
                    const Slefe& plus = s.corner[corner][std::size_t(2 * axis)];
                    const Slefe& minus = s.corner[corner][std::size_t(2 * axis + 1)];
                    const auto at = [&](const std::array<double, Slefe::kMaxSegments + 1>& p, const std::array<double, Slefe::kMaxSegments + 1>& m) {
                        const double left = 0.5 * (1 - a) * p[std::size_t(piece)] + 0.5 * (1 + a) * m[std::size_t(piece)];
                        const double right = 0.5 * (1 - a) * p[std::size_t(piece + 1)] + 0.5 * (1 + a) * m[std::size_t(piece + 1)];
                        return left + f * (right - left);
                    };
                    const double distance = c[axis] - a * c.z;
                    EXPECT_LE(at(plus.lower, minus.lower), distance + 1e-12);
                    EXPECT_GE(at(plus.upper, minus.upper), distance - 1e-12);
                }
            }
        }
    }
}

}  // namespace streak::raster
