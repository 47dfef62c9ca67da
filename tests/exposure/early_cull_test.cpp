#include "exposure/early_cull.h"

#include "util/random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace streak::exposure {

// A tile's items go nearest first: by nearness, largest first, and at equal nearness in index
// order. Nearness values drawn from a few (so that many tie), with 0 (a corner at or behind the
// eye) and +inf among them, the items a shuffled subset. The order is what std::sort gives with
// that comparison written out.
TEST(EarlyCull, NearestFirstOrdersByNearnessThenIndex) {
    const float values[] = {0.0f, 1e-30f, 0.25f, 0.5f, 0.5000001f, 3.0f, 1e30f, std::numeric_limits<float>::infinity()};
    std::vector<TriangleSegment> segments(5000);
    for (std::size_t i = 0; i < segments.size(); ++i) segments[i].nearness = values[hashValues(i, 1) % std::size(values)];
    std::vector<std::uint32_t> items;
    for (std::uint32_t i = 0; i < segments.size(); ++i)
        if (hashValues(i, 2) % 3 != 0) items.push_back(i);
    for (std::size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[hashValues(i, 3) % i]);

    std::vector<std::uint32_t> expected = items;
    std::sort(expected.begin(), expected.end(), [&](std::uint32_t a, std::uint32_t b) {
        return segments[a].nearness != segments[b].nearness ? segments[a].nearness > segments[b].nearness : a < b;
    });
    std::vector<std::uint32_t> order;
    std::vector<std::uint64_t> keys;
    nearestFirst(items, segments, order, keys);
    EXPECT_EQ(order, expected);
}

namespace {

constexpr raster::Viewport kView{100, 100};

// A segment whose corners are at `pixels` (x right, y down) at depth w, moving by `move`
// pixels (corner i by move[i]) over the whole shutter.
TriangleSegment screenSegment(const std::array<glm::dvec2, 3>& pixels, const std::array<glm::dvec2, 3>& move, float w = 2.0f) {
    auto clip = [&](const glm::dvec2& p) {
        return glm::vec4(float((p.x / (0.5 * kView.width) - 1.0) * w), float((1.0 - p.y / (0.5 * kView.height)) * w), 0.0f, w);
    };
    TriangleSegment s;
    s.t0 = 0.0f, s.t1 = 1.0f, s.nearness = 1.0f / w;
    for (int i = 0; i < 3; ++i) s.clip0[std::size_t(i)] = clip(pixels[std::size_t(i)]), s.clip1[std::size_t(i)] = clip(pixels[std::size_t(i)] + move[std::size_t(i)]);
    s.isStill = move == std::array<glm::dvec2, 3>{};
    return s;
}

bool isInside(const std::array<glm::dvec2, 3>& t, const glm::dvec2& p) {
    auto edge = [&](int i) {
        const glm::dvec2 a = t[std::size_t(i)], b = t[std::size_t((i + 1) % 3)];
        return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    };
    const double e0 = edge(0), e1 = edge(1), e2 = edge(2);
    return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

}  // namespace

// A translating triangle covers a point for its chord along the motion over the distance: where
// the estimate says no point is covered for kShortestStretch of the shutter, none is, found by
// stepping points of its path through 1024 instants. Random small triangles, moved 4 to 40
// times their size; both answers occur.
TEST(EarlyCull, ATranslatingTriangleCoversAStretchOnlyWhereTheEstimateAllowsIt) {
    int numMay = 0, numCannot = 0;
    for (int k = 0; k < 60; ++k) {
        auto unit = [&](int salt) { return double(hashValues(std::size_t(k), std::size_t(salt)) % 10000) / 10000.0; };
        const glm::dvec2 origin(30.0, 40.0);
        const std::array<glm::dvec2, 3> corners{origin, origin + glm::dvec2(0.3 + 2.0 * unit(1), 0.5 * unit(2)),
                                                origin + glm::dvec2(0.5 * unit(3), 0.3 + 2.0 * unit(4))};
        const double angle = 6.283 * unit(5), size = 2.5 * (1.0 + unit(6));
        const glm::dvec2 move = glm::dvec2(std::cos(angle), std::sin(angle)) * size * (4.0 + 36.0 * unit(7));
        const bool may = EarlyCull::mayCoverAStretch(screenSegment(corners, {move, move, move}), kView);
        (may ? numMay : numCannot) += 1;
        if (may) continue;
        constexpr int kInstants = 1024;
        double longest = 0.0;
        for (int a = 0; a <= 30; ++a)
            for (int b = 0; b <= 30; ++b) {
                // Points halfway along the path, which the whole triangle passes.
                const glm::dvec2 p = origin + glm::dvec2(-0.5 + 3.5 * a / 30.0, -0.5 + 3.5 * b / 30.0) + 0.5 * move;
                int covered = 0;
                for (int i = 0; i < kInstants; ++i)
                    covered += isInside(corners, p - move * ((double(i) + 0.5) / kInstants));
                longest = std::max(longest, double(covered) / kInstants);
            }
        EXPECT_LT(longest, EarlyCull::kShortestStretch) << "triangle " << k;
    }
    EXPECT_GT(numMay, 5);
    EXPECT_GT(numCannot, 5);
}

TEST(EarlyCull, StillTurningAndNearTrianglesMayCoverAStretch) {
    const std::array<glm::dvec2, 3> corners{glm::dvec2(50.0, 50.0), glm::dvec2(51.0, 50.0), glm::dvec2(50.0, 51.0)};
    EXPECT_TRUE(EarlyCull::mayCoverAStretch(screenSegment(corners, {}), kView));
    // Spun half a turn about its centre: its corners travel far, the centre not at all.
    const glm::dvec2 centre = (corners[0] + corners[1] + corners[2]) / 3.0;
    std::array<glm::dvec2, 3> spin;
    for (int i = 0; i < 3; ++i) spin[std::size_t(i)] = 2.0 * (centre - corners[std::size_t(i)]);
    EXPECT_TRUE(EarlyCull::mayCoverAStretch(screenSegment(corners, spin), kView));
    // The same spin carried 60 pixels: every point travels far.
    for (glm::dvec2& m : spin) m += glm::dvec2(60.0, 0.0);
    EXPECT_FALSE(EarlyCull::mayCoverAStretch(screenSegment(corners, spin), kView));
    // Half the shutter's segment moving 20 times its size sweeps a point for a fortieth of the
    // shutter; all of it, for a twentieth (more than a sixteenth, the estimate allowing the
    // diagonal).
    TriangleSegment half = screenSegment(corners, {glm::dvec2(20.0, 0.0), glm::dvec2(20.0, 0.0), glm::dvec2(20.0, 0.0)});
    EXPECT_TRUE(EarlyCull::mayCoverAStretch(half, kView));
    half.t1 = 0.5f;
    EXPECT_FALSE(EarlyCull::mayCoverAStretch(half, kView));
}

TEST(EarlyCull, ATileMayHideOnlyWhatLiesBeyondWhatMayCoverIt) {
    // A big slow quad's triangle at depth 2 hides a small one at depth 5 behind it, not one at 1
    // in front; tiny fast triangles hide nothing, wherever they lie.
    const std::array<glm::dvec2, 3> big{glm::dvec2(10.0, 10.0), glm::dvec2(90.0, 10.0), glm::dvec2(10.0, 90.0)};
    const std::array<glm::dvec2, 3> tiny{glm::dvec2(50.0, 50.0), glm::dvec2(50.5, 50.0), glm::dvec2(50.0, 50.5)};
    const std::array<glm::dvec2, 3> slow{glm::dvec2(3.0, 0.0), glm::dvec2(3.0, 0.0), glm::dvec2(3.0, 0.0)};
    const std::array<glm::dvec2, 3> fast{glm::dvec2(40.0, 0.0), glm::dvec2(40.0, 0.0), glm::dvec2(40.0, 0.0)};
    const std::vector<TriangleSegment> segments{screenSegment(big, slow, 2.0f), screenSegment(tiny, fast, 5.0f), screenSegment(tiny, fast, 1.0f),
                                                screenSegment(tiny, fast, 9.0f)};
    // occluderDepths: the farthest corner of what may cover a stretch, infinity elsewhere.
    for (std::size_t i = 0; i < segments.size(); ++i) EXPECT_EQ(EarlyCull::mayCoverAStretch(segments[i], kView), i == 0) << i;
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> depths{2.0f, inf, inf, inf};
    auto hides = [&](std::vector<std::uint32_t> items) { return EarlyCull::mayHideAny(items, segments, depths); };
    EXPECT_TRUE(hides({0, 1}));
    EXPECT_TRUE(hides({2, 0, 3}));
    EXPECT_FALSE(hides({0, 2}));
    EXPECT_FALSE(hides({1, 2, 3}));
    EXPECT_FALSE(hides({}));
}

}  // namespace streak::exposure
