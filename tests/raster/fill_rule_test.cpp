#include "raster/clip.h"
#include "raster/tile_grid.h"
#include "util/random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace streak::raster {

namespace {

// Clip coordinates (w = 1) of a raster position, the inverse of rasterFromClip.
glm::vec4 clipAt(const Viewport& vp, float x, float y) { return {2.0f * x / vp.width - 1.0f, 1.0f - 2.0f * y / vp.height, 0.0f, 1.0f}; }

// Counts, per sample, how many of the triangles cover it.
std::vector<int> coverageCounts(const Viewport& vp, const SamplePattern& pattern, const std::vector<ScreenTriangle>& tris) {
    std::vector<int> counts(std::size_t(vp.width) * vp.height * pattern.count(), 0);
    const PixelBounds all{0, 0, vp.width - 1, vp.height - 1};
    for (const ScreenTriangle& tri : tris)
        scanTriangle(tri, all, pattern, [&](int px, int py, int s, const EdgeValues&) {
            ++counts[(std::size_t(py) * vp.width + px) * pattern.count() + s];
        });
    return counts;
}

}  // namespace

TEST(FillRule, SharedEdgesCoverEverySampleExactlyOnce) {
    // A triangulated lattice overhanging the image: every sample lies in exactly one triangle.
    // Half the lattice points sit exactly on sample positions (pixel centres), so edges and
    // vertices pass through samples, horizontally and vertically too: the top-left rule must
    // give each such sample to exactly one triangle.
    const Viewport vp{48, 40};
    Rng rng(11);
    const int n = 16;
    const float step = 3.5f;
    std::vector<glm::vec2> points;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            glm::vec2 p(-4.5f + step * float(i), -4.5f + step * float(j));
            if ((i + j) % 2) p += glm::vec2(rng.uniform(-1.2f, 1.2f), rng.uniform(-1.2f, 1.2f));
            points.push_back(p);
        }
    std::vector<ScreenTriangle> tris;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const glm::vec2 a = points[j * (n + 1) + i], b = points[j * (n + 1) + i + 1];
            const glm::vec2 c = points[(j + 1) * (n + 1) + i], d = points[(j + 1) * (n + 1) + i + 1];
            const bool flip = rng.next() % 2;
            // Mixed orientations too: the rule must not depend on winding.
            const std::array<std::array<glm::vec2, 3>, 2> halves =
                flip ? std::array<std::array<glm::vec2, 3>, 2>{{{a, b, d}, {a, c, d}}}
                     : std::array<std::array<glm::vec2, 3>, 2>{{{a, b, c}, {c, d, b}}};
            for (const auto& h : halves) {
                ScreenTriangle tri;
                if (setupScreenTriangle({clipAt(vp, h[0].x, h[0].y), clipAt(vp, h[1].x, h[1].y), clipAt(vp, h[2].x, h[2].y)}, vp, tri))
                    tris.push_back(tri);
            }
        }
    for (int aa : {1, 3, 4}) {
        const std::vector<int> counts = coverageCounts(vp, SamplePattern::grid(aa), tris);
        int wrong = 0;
        for (int c : counts) wrong += c != 1;
        EXPECT_EQ(wrong, 0) << "aa " << aa;
    }
}

TEST(FillRule, TopLeftOwnership) {
    // A square from (2,2) to (6,6) through pixel centres split along its diagonal. Samples on
    // its left and top edges are inside, those on its right and bottom edges are not.
    const Viewport vp{8, 8};
    std::vector<ScreenTriangle> tris(2);
    ASSERT_TRUE(setupScreenTriangle({clipAt(vp, 2.5f, 2.5f), clipAt(vp, 2.5f, 6.5f), clipAt(vp, 6.5f, 6.5f)}, vp, tris[0]));
    ASSERT_TRUE(setupScreenTriangle({clipAt(vp, 2.5f, 2.5f), clipAt(vp, 6.5f, 6.5f), clipAt(vp, 6.5f, 2.5f)}, vp, tris[1]));
    const std::vector<int> counts = coverageCounts(vp, SamplePattern::grid(1), tris);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) EXPECT_EQ(counts[y * 8 + x], (x >= 2 && x < 6 && y >= 2 && y < 6) ? 1 : 0) << x << "," << y;
}

TEST(ScanTriangle, RowSpansVisitTheSamplesAndEdgeValuesOfTestingEveryPixel) {
    // scanTriangle finds a wide row's covered pixels from the edges (narrowToEdge) instead of
    // testing each: it must call back with exactly the samples, in the same order, and the same
    // edge values as testing every pixel of the row does. Random triangles of every size and
    // shape (long slivers at every angle, ones with level or upright edges, ones whose corners
    // sit on sample positions), exact and conservative (makeConservative's bias), under regions
    // that clip them, at 1, 4 and 9 samples a pixel.
    const Viewport vp{200, 150};
    Rng rng(64);
    struct Visit {
        int px, py, s;
        EdgeValues e;
        bool operator==(const Visit&) const = default;
    };
    int wide = 0, visits = 0;
    for (int i = 0; i < 3000; ++i) {
        auto point = [&] {
            glm::vec2 p(rng.uniform(-20.0f, 220.0f), rng.uniform(-20.0f, 170.0f));
            if (i % 5 == 0) p = glm::floor(p) + 0.5f;  // on a pixel centre
            return p;
        };
        std::array<glm::vec2, 3> c{point(), point(), point()};
        if (i % 3 == 1) c[1] = c[0] + glm::vec2(rng.uniform(-150.0f, 150.0f), rng.uniform(-3.0f, 3.0f)), c[2] = c[0] + glm::vec2(rng.uniform(-2.0f, 2.0f), rng.uniform(-2.0f, 2.0f));
        if (i % 7 == 2) c[1].y = c[0].y;                  // a level edge
        if (i % 11 == 3) c[2].x = c[0].x;                 // an upright one
        ScreenTriangle tri;
        if (!setupScreenTriangle({clipAt(vp, c[0].x, c[0].y), clipAt(vp, c[1].x, c[1].y), clipAt(vp, c[2].x, c[2].y)}, vp, tri)) continue;
        if (i % 2 == 1) makeConservative(tri, vp);
        const int x0 = int(rng.uniform(0.0f, 150.0f)), y0 = int(rng.uniform(0.0f, 100.0f));
        const PixelBounds region = i % 4 == 0 ? PixelBounds{0, 0, vp.width - 1, vp.height - 1}
                                              : PixelBounds{x0, y0, x0 + int(rng.uniform(0.0f, 60.0f)), y0 + int(rng.uniform(0.0f, 40.0f))};
        const SamplePattern pattern = SamplePattern::rooks(1 + i % 3);
        std::vector<Visit> got, want;
        scanTriangle(tri, region, pattern, [&](int px, int py, int s, const EdgeValues& e) { got.push_back({px, py, s, e}); });
        // Every pixel tested, as the loop did before row spans.
        const int rx0 = std::max(region.x0, tri.bounds.x0), rx1 = std::min(region.x1, tri.bounds.x1);
        const int ry0 = std::max(region.y0, tri.bounds.y0), ry1 = std::min(region.y1, tri.bounds.y1);
        for (int py = ry0; py <= ry1; ++py)
            for (int s = 0; s < pattern.count(); ++s)
                for (int px = rx0; px <= rx1; ++px) {
                    const EdgeValues e = tri.edgesAt(std::int64_t(px) * kSubpixelScale + pattern.offsets[std::size_t(s)].x,
                                                     std::int64_t(py) * kSubpixelScale + pattern.offsets[std::size_t(s)].y);
                    if (tri.isInside(e)) want.push_back({px, py, s, e});
                }
        wide += rx1 - rx0 + 1 >= kScanSpanMinWidth;
        visits += int(want.size());
        ASSERT_EQ(got.size(), want.size()) << "triangle " << i;
        ASSERT_TRUE(got == want) << "triangle " << i;
    }
    EXPECT_GT(wide, 1000);
    EXPECT_GT(visits, 100000);
}

TEST(ScanTriangle, NarrowToEdgeFindsTheExactEnds) {
    // Against counting pixel by pixel, at values and steps near the ends' rounding (values that
    // are exact multiples of the step, one either side of them, and ones past 2^40).
    Rng rng(7);
    for (int i = 0; i < 200000; ++i) {
        const std::int64_t step = (i % 2 ? 1 : -1) * (1 + std::int64_t(rng.next() % (i % 3 ? 1000u : 1u << 30)));
        const std::int64_t last = std::int64_t(rng.next() % 300);
        std::int64_t value = std::int64_t(rng.next() % 2000000) - 1000000;
        if (i % 5 == 0) value = -step * std::int64_t(rng.next() % 400) + std::int64_t(rng.next() % 3) - 1;
        if (i % 7 == 0) value *= std::int64_t(1) << 20;
        std::int64_t first = 0, end = last;
        const bool isAny = narrowToEdge(value, step, first, end);
        std::int64_t wantFirst = -1, wantLast = -1;
        for (std::int64_t k = 0; k <= last; ++k)
            if (value + step * k >= 0) {
                if (wantFirst < 0) wantFirst = k;
                wantLast = k;
            }
        ASSERT_EQ(isAny, wantFirst >= 0) << value << " " << step << " " << last;
        if (!isAny) continue;
        ASSERT_EQ(first, wantFirst) << value << " " << step << " " << last;
        ASSERT_EQ(end, wantLast) << value << " " << step << " " << last;
    }
}

TEST(ScreenTriangle, OrientationAndPerspectiveBarycentrics) {
    const Viewport vp{100, 100};
    // Counter-clockwise in NDC (y up) is front facing.
    const std::array<glm::vec4, 3> ccw{glm::vec4(-0.5f, -0.5f, 0, 1), glm::vec4(0.5f, -0.5f, 0, 1), glm::vec4(0, 0.5f, 0, 1)};
    ScreenTriangle tri;
    ASSERT_TRUE(setupScreenTriangle(ccw, vp, tri));
    EXPECT_TRUE(tri.isFrontFacing);
    ASSERT_TRUE(setupScreenTriangle({ccw[0], ccw[2], ccw[1]}, vp, tri));
    EXPECT_FALSE(tri.isFrontFacing);

    // Corners at different depths: the 3D midpoint of edge 0-1 projects off the 2D midpoint,
    // and there the perspective-correct barycentrics are exactly (1/2, 1/2, 0) with 1/w the
    // reciprocal of the midpoint's depth. Tolerance: 1/256 pixel snapping of the corners.
    const glm::vec4 v0(-1.0f, -1.0f, 0, 1.0f), v1(4.0f, -4.0f, 0, 4.0f), v2(0.0f, 2.0f, 0, 2.0f);
    ASSERT_TRUE(setupScreenTriangle({v0, v1, v2}, vp, tri));
    const glm::vec4 mid = 0.5f * (v0 + v1);
    const glm::dvec2 p = rasterFromClip(mid, vp);
    const EdgeValues e = tri.edgesAt(std::llround(p.x * kSubpixelScale), std::llround(p.y * kSubpixelScale));
    const PerspectiveSample s = tri.interpolate(e);
    EXPECT_NEAR(s.bary.x, 0.5f, 2e-3f);
    EXPECT_NEAR(s.bary.y, 0.5f, 2e-3f);
    EXPECT_NEAR(s.bary.z, 0.0f, 2e-3f);
    EXPECT_NEAR(s.invW, 1.0f / mid.w, 2e-3f);
}

TEST(Clip, NearPlaneKeepsTheVisiblePartWithSourceBarycentrics) {
    const float zNear = 0.1f;
    // One corner behind the camera (w < 0), one in front, one far beyond the guard band.
    const std::array<glm::vec4, 3> clip{glm::vec4(0.0f, 0.0f, 0, -1.0f), glm::vec4(0.5f, 0.2f, 0, 2.0f), glm::vec4(-200.0f, 1.0f, 0, 3.0f)};
    ASSERT_TRUE(needsClipping(clip, zNear));
    const ClippedPolygon poly = clipTriangle(clip, zNear);
    ASSERT_GE(poly.count, 3);
    for (int i = 0; i < poly.count; ++i) {
        const ClipVertex& v = poly.vertices[i];
        EXPECT_GE(v.clip.w, zNear - 1e-5f);
        EXPECT_LE(std::abs(v.clip.x), kGuardBand * v.clip.w + 1e-3f);
        const glm::vec4 fromBary = v.sourceBary.x * clip[0] + v.sourceBary.y * clip[1] + v.sourceBary.z * clip[2];
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(fromBary[c], v.clip[c], 1e-3f);
        EXPECT_NEAR(v.sourceBary.x + v.sourceBary.y + v.sourceBary.z, 1.0f, 1e-5f);
    }
    // Wholly behind the near plane: nothing.
    const std::array<glm::vec4, 3> behind{glm::vec4(0, 0, 0, -1), glm::vec4(1, 0, 0, 0.05f), glm::vec4(0, 1, 0, -2)};
    EXPECT_EQ(clipTriangle(behind, zNear).count, 0);
    TriangleSetup setup;
    setupTriangle(behind, 0, zNear, Viewport{64, 64}, CullMode::None, setup);
    EXPECT_EQ(setup.count, 0);
}

TEST(TileGrid, BinsByBoundsInSubmissionOrder) {
    TileGrid grid(Viewport{100, 50}, 32);
    EXPECT_EQ(grid.numTiles(), 4 * 2);
    const std::vector<PixelBounds> bounds{{0, 0, 40, 10}, {90, 40, 99, 49}, {10, 10, 10, 10}, {5, 5, 4, 4}};
    grid.bin(bounds.size(), [&](std::size_t i) { return bounds[i]; });
    ASSERT_EQ(grid.items(0).size(), 2u);
    EXPECT_EQ(grid.items(0)[0], 0u);
    EXPECT_EQ(grid.items(0)[1], 2u);
    EXPECT_EQ(grid.items(1).size(), 1u);
    EXPECT_EQ(grid.items(7).size(), 1u);
    EXPECT_EQ(grid.items(7)[0], 1u);
}

}  // namespace streak::raster
