#include "raster/edge_batch.h"

#include "raster/moving_triangle.h"
#include "util/random.h"
#include "util/simd.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace streak::raster {

namespace {

// Random moving triangles of every kind a scene has: large and small, fast and slow, deforming,
// under perspective (w changing), still, and turning over; a third of the samples on or within
// rounding of an edge at an end, where staysOutside's tolerance decides.
struct Case {
    std::array<glm::vec4, 3> open, close;
    std::vector<glm::dvec2> samples;
};

Case randomCase(Rng& rng, int i) {
    auto corner = [&](float spread) { return glm::vec4(rng.uniform(-spread, spread), rng.uniform(-spread, spread), 0.0f, 1.0f); };
    Case c;
    c.open = {corner(1.0f), corner(1.0f), corner(1.0f)};
    if (i % 3 == 0) c.open[1] = c.open[0] + corner(0.02f) * glm::vec4(1, 1, 0, 0), c.open[2] = c.open[0] + corner(0.02f) * glm::vec4(1, 1, 0, 0);
    const glm::vec4 motion = corner(i % 2 == 0 ? 1.0f : 0.05f) * glm::vec4(1, 1, 0, 0);
    for (int k = 0; k < 3; ++k) {
        c.close[std::size_t(k)] = c.open[std::size_t(k)] + motion;
        if (i % 4 == 1) c.close[std::size_t(k)] += corner(0.3f) * glm::vec4(1, 1, 0, 0);  // deforming, often turning over
    }
    if (i % 7 == 3) c.close = c.open;  // still
    if (i % 2 == 1) {
        for (glm::vec4& v : c.open) v *= rng.uniform(0.5f, 3.0f);
        for (glm::vec4& v : c.close) v *= rng.uniform(0.5f, 3.0f);
    }
    if (i % 50 == 7) {
        // Still and axis-aligned (legs along x and y, either orientation), with samples exactly
        // on its edges: where the top-left rule decides, on edges whose x or y term is zero.
        c.open = {glm::vec4(-0.5f, -0.5f, 0, 1), glm::vec4(0.5f, -0.5f, 0, 1), glm::vec4(-0.5f, 0.5f, 0, 1)};
        if (i % 100 == 57) std::swap(c.open[1], c.open[2]);
        c.close = c.open;
        for (int k = 0; k < 3 * EdgeBatch::kCapacity; ++k) {
            const double along = -0.5 + double(int(rng.uniform(0, 64))) / 64.0;
            const int edge = k % 4;
            c.samples.push_back(edge == 0 ? glm::dvec2(along, -0.5) : edge == 1 ? glm::dvec2(-0.5, along) : edge == 2 ? glm::dvec2(along, -along)
                                                                                                                 : glm::dvec2(along, 0.1));
        }
        return c;
    }
    for (int k = 0; k < 3 * EdgeBatch::kCapacity; ++k) {
        glm::dvec2 p(rng.uniform(-1.5f, 1.5f), rng.uniform(-1.5f, 1.5f));
        if (k % 3 == 1) {
            const auto& ends = rng.uniform(0, 1) < 0.5f ? c.open : c.close;
            const int e = k % 3;
            const glm::dvec2 a = glm::dvec2(ends[std::size_t(e)].x, ends[std::size_t(e)].y) / double(ends[std::size_t(e)].w);
            const glm::dvec2 b = glm::dvec2(ends[std::size_t((e + 1) % 3)].x, ends[std::size_t((e + 1) % 3)].y) / double(ends[std::size_t((e + 1) % 3)].w);
            p = a + double(rng.uniform(0, 1)) * (b - a) + glm::dvec2(rng.uniform(-1, 1), rng.uniform(-1, 1)) * 1e-7;
        }
        c.samples.push_back(p);
    }
    return c;
}

}  // namespace

// Every level (the scalar twin, baseline SSE2, and AVX2 where this CPU has it) gives the edge
// quadratics, staysOutside answers and (still triangles) inside tests of MovingTriangle's
// per-sample code, bit for bit, and so the same spans: 10,000 random moving triangles, each at 96 samples in runs of 32 (every
// sample, and every third as a box loop's row of one sample index takes them), in both
// orientations and with culling off (orientation 0).
TEST(EdgeBatch, EveryLevelEqualsThePerSampleCode) {
    std::vector<simd::Level> levels{simd::Level::scalar, simd::Level::sse2};
    if (simd::isSupported(simd::Level::avx2)) levels.push_back(simd::Level::avx2);
    std::printf("edge batch levels tested: %zu (best: %s)\n", levels.size(), simd::levelName(simd::bestLevel()));
    Rng rng(2028);
    std::int64_t compared = 0, culled = 0, withSpans = 0, stillInside = 0, stillOnEdge = 0;
    EdgeBatch batch;
    for (int i = 0; i < 10000; ++i) {
        const Case c = randomCase(rng, i);
        const MovingTriangle moving(c.open, c.close);
        const int orientation = i % 3 - 1;
        for (const simd::Level level : levels) {
            for (const std::ptrdiff_t stride : {std::ptrdiff_t(1), std::ptrdiff_t(3)}) {
                const int count = stride == 1 ? EdgeBatch::kCapacity : EdgeBatch::kCapacity - i % 5;  // short runs too
                evaluateEdgeBatch(moving, orientation, c.samples.data() + (stride == 1 ? i % 3 : 0), stride, count, batch, level);
                ASSERT_EQ(batch.count, count);
                for (int k = 0; k < count; ++k) {
                    const glm::dvec2 p = c.samples[std::size_t((stride == 1 ? i % 3 : 0) + k * stride)];
                    const std::array<Quadratic, 3> expected = moving.edgeFunctions(p);
                    for (int e = 0; e < 3; ++e) {
                        const Quadratic& q = batch.edges[std::size_t(k)][std::size_t(e)];
                        ASSERT_TRUE(q.a == expected[e].a && q.b == expected[e].b && q.c == expected[e].c)
                            << simd::levelName(level) << " triangle " << i << " sample " << k << " edge " << e;
                    }
                    const bool outside = moving.staysOutside(p, orientation);
                    ASSERT_EQ(batch.staysOutside[std::size_t(k)] != 0, outside) << simd::levelName(level) << " triangle " << i << " sample " << k;
                    if (moving.isStill() && !outside) {  // (asked only where the sample is not culled)
                        const Quadratic* q = expected.data();
                        const bool inside = isInsideByEdges(moving.edgeTerms().c, p, {q[0].c, q[1].c, q[2].c});
                        ASSERT_EQ(batch.isInsideStill[std::size_t(k)] != 0, inside) << simd::levelName(level) << " triangle " << i << " sample " << k;
                        stillInside += inside, stillOnEdge += std::abs(q[0].c) < 1e-6 || std::abs(q[1].c) < 1e-6 || std::abs(q[2].c) < 1e-6;
                    }
                    ++compared, culled += outside;
                    if (outside) continue;  // a box loop asks no spans there
                    std::array<double, 8> fromBatch, fromSample;
                    const int n = insideSpansOf(moving, batch, k, p, 0.1, i % 2 == 0, fromBatch);
                    ASSERT_EQ(n, moving.insideSpans(p, 0.1, i % 2 == 0, fromSample));
                    for (int j = 0; j < n; ++j) ASSERT_EQ(fromBatch[std::size_t(j)], fromSample[std::size_t(j)]);
                    withSpans += n > 0;
                }
            }
        }
    }
    EXPECT_GT(compared, 1000000);
    EXPECT_GT(culled, 100000);  // the cull is exercised, and so are spans
    EXPECT_GT(withSpans, 50000);
    EXPECT_GT(stillInside, 5000);  // still triangles' inside test, on their edges too
    EXPECT_GT(stillOnEdge, 5000);
}

}  // namespace streak::raster
