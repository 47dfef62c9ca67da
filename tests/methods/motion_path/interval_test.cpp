#include "methods/motion_path/interval.h"
#include "methods/motion_path/resolve.h"
#include "util/random.h"

#include <gtest/gtest.h>

namespace streak::motion_path {

namespace {

Interval make(float t0, float t1, float d0, float d1, std::uint32_t id, glm::vec3 color = glm::vec3(0.0f), float alpha = 1.0f) {
    Interval i;
    i.t0 = t0, i.t1 = t1, i.depth0 = d0, i.depth1 = d1, i.source = id, i.color = color, i.alpha = alpha;
    return i;
}

// One to six opaque intervals at least minLength long, at random times and depths in [1, 10],
// interval i coloured (i + 1, 0, 0).
std::vector<Interval> randomIntervals(Rng& rng, float minLength) {
    std::vector<Interval> list;
    const int n = 1 + int(rng.next() % 6);
    for (int i = 0; i < n; ++i) {
        float t0 = rng.uniform(), t1 = rng.uniform();
        if (t0 > t1) std::swap(t0, t1);
        if (t1 - t0 < minLength) t1 = std::min(1.0f, t0 + minLength);
        list.push_back(make(t0, t1, rng.uniform(1, 10), rng.uniform(1, 10), std::uint32_t(i), glm::vec3(float(i + 1), 0, 0)));
    }
    return list;
}

}  // namespace

TEST(Interval, SplitAtDepthTimeCrossing) {
    // a goes from depth 1 to 3 over [0, 1]; b from 3 to 1 over [0, 1]: they cross at t = 1/2,
    // depth 2.
    Interval a = make(0, 1, 1, 3, 0), b = make(0, 1, 3, 1, 1), aTail, bTail;
    ASSERT_TRUE(splitAtCrossing(a, b, aTail, bTail));
    EXPECT_FLOAT_EQ(a.t1, 0.5f);
    EXPECT_FLOAT_EQ(a.depth1, 2.0f);
    EXPECT_FLOAT_EQ(aTail.t0, 0.5f);
    EXPECT_FLOAT_EQ(aTail.depth0, 2.0f);
    EXPECT_FLOAT_EQ(aTail.depth1, 3.0f);
    EXPECT_FLOAT_EQ(bTail.depth1, 1.0f);
    // Parallel or touching segments do not split.
    Interval c = make(0, 1, 1, 2, 2), d = make(0, 1, 2, 3, 3);
    EXPECT_FALSE(splitAtCrossing(c, d, aTail, bTail));
    Interval e = make(0, 0.5f, 1, 2, 4), f = make(0.5f, 1, 2, 1, 5);
    EXPECT_FALSE(splitAtCrossing(e, f, aTail, bTail));
}

TEST(Interval, FourTests) {
    // (1) no depth overlap.
    EXPECT_TRUE(canStayBefore(make(0, 1, 1, 2, 0), make(0, 1, 3, 4, 1)));
    EXPECT_FALSE(canStayBefore(make(0, 1, 3, 4, 1), make(0, 1, 1, 2, 0)));
    // (2) no time overlap, whatever the depths.
    EXPECT_TRUE(canStayBefore(make(0.6f, 1, 5, 6, 0), make(0, 0.5f, 1, 2, 1)));
    // (3)/(4): overlapping in both depth and time, k behind h over the common span [0.5, 1].
    const Interval h = make(0, 1, 1, 3, 0), k = make(0.5f, 1, 2.5f, 3.5f, 1);
    EXPECT_TRUE(canStayBefore(h, k));
    EXPECT_FALSE(canStayBefore(k, h));
}

TEST(Interval, SortOrdersFrontToBackAndSplitsCrossings) {
    // The crossing pair of the first test plus one interval behind both: after sorting, at
    // every time the list meets the nearest interval first.
    std::vector<Interval> list{make(0, 1, 5, 5, 2), make(0, 1, 3, 1, 1), make(0, 1, 1, 3, 0)};
    SortCounters counters;
    sortDepthTime(list, 90, counters);
    EXPECT_EQ(counters.splits, 1);
    ASSERT_EQ(list.size(), 5u);
    for (float t : {0.1f, 0.4f, 0.6f, 0.9f}) {
        // The first interval covering t must be the nearest at t.
        const Interval* first = nullptr;
        float nearest = 1e9f;
        for (const Interval& i : list)
            if (i.t0 <= t && t < i.t1) {
                if (!first) first = &i;
                nearest = std::min(nearest, i.depthAt(t));
            }
        ASSERT_NE(first, nullptr);
        EXPECT_FLOAT_EQ(first->depthAt(t), nearest) << "t = " << t;
    }
    // The budget stops splitting and counts it.
    std::vector<Interval> small{make(0, 1, 3, 1, 1), make(0, 1, 1, 3, 0)};
    SortCounters tight;
    sortDepthTime(small, 3, tight);
    EXPECT_EQ(tight.overflow, 1);
    EXPECT_EQ(small.size(), 2u);
}

TEST(Interval, RandomSortsResolveLikeABruteForceTimeSweep) {
    // Random opaque intervals: resolving the sorted list must give, slice by slice, the colour
    // of the interval nearest at the slice centre (what a per-slice depth test computes).
    // Trials whose order has a cycle (counted by the sort) are beyond any list order.
    Rng rng(21);
    const int bits = 64;
    int numCycles = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<Interval> list = randomIntervals(rng, 0.05f);
        glm::vec3 expected(0.0f);
        for (int b = 0; b < bits; ++b) {
            const float t = (float(b) + 0.5f) / bits;
            float nearest = 1e9f;
            glm::vec3 color(0.0f);  // background black
            for (const Interval& i : list)
                if (i.t0 <= t && t < i.t1 && i.depthAt(t) < nearest) nearest = i.depthAt(t), color = i.color;
            expected += color / float(bits);
        }
        SortCounters counters;
        sortDepthTime(list, 90, counters);
        const glm::vec3 got = resolveIntervals(list, bits, glm::vec3(0.0f));
        if (counters.cycles > 0) {
            ++numCycles;
            continue;
        }
        EXPECT_NEAR(got.x, expected.x, 1e-4f) << "trial " << trial;
    }
    EXPECT_LT(numCycles, 10);  // cycles are rare: the comparison above covers almost every trial
}

TEST(Resolve, HandMadeIntervals) {
    // Red in front over [0, 1/2), green behind over [1/4, 1): green shows for 1/2 of the
    // shutter, red for 1/2, no background. 128 slices: exact for these times.
    const std::vector<Interval> sorted{make(0, 0.5f, 1, 1, 0, {1, 0, 0}), make(0.25f, 1, 2, 2, 1, {0, 1, 0})};
    const glm::vec3 c = resolveIntervals(sorted, 128, glm::vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(c.x, 0.5f);
    EXPECT_FLOAT_EQ(c.y, 0.5f);
    EXPECT_FLOAT_EQ(c.z, 0.0f);
    // Only red: background blue fills the other half.
    const glm::vec3 d = resolveIntervals(std::span(sorted).first(1), 128, glm::vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(d.z, 0.5f);
    // Translucent red (alpha 1/2) over [0, 1/2) in front of opaque green over the whole
    // shutter: first half 0.5 red + 0.5 green, second half green.
    const std::vector<Interval> glass{make(0, 0.5f, 1, 1, 0, {1, 0, 0}, 0.5f), make(0, 1, 2, 2, 1, {0, 1, 0})};
    const glm::vec3 e = resolveIntervals(glass, 64, glm::vec3(0.0f));
    EXPECT_FLOAT_EQ(e.x, 0.25f);
    EXPECT_FLOAT_EQ(e.y, 0.75f);
}

// Exact weights: a sorted random list resolves to the time-integral of the nearest interval's
// colour, by a sweep over every time where something starts, ends or crosses (exact between
// them), to float precision; mask slices are off by up to a slice per piece.
TEST(Resolve, ExactWeightsAreTheTimeIntegralOfTheNearest) {
    Rng rng(5);
    int numCompared = 0;
    double worstSlices = 0.0;
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<Interval> list = randomIntervals(rng, 0.01f);
        // Breakpoints: ends and pairwise crossings; between two, the nearest is one interval.
        std::vector<double> times{0.0, 1.0};
        for (const Interval& a : list) {
            times.push_back(a.t0), times.push_back(a.t1);
            for (const Interval& b : list) {
                const double da = a.depth1 - a.depth0, db = b.depth1 - b.depth0;
                const double sa = da / (a.t1 - a.t0), sb = db / (b.t1 - b.t0);
                if (sa == sb) continue;
                const double t = (b.depth0 - sb * b.t0 - (a.depth0 - sa * a.t0)) / (sa - sb);
                if (t > 0.0 && t < 1.0) times.push_back(t);
            }
        }
        std::sort(times.begin(), times.end());
        double expected = 0.0;
        for (std::size_t k = 0; k + 1 < times.size(); ++k) {
            const float t = float(0.5 * (times[k] + times[k + 1]));
            float nearest = 1e9f, color = 0.0f;
            for (const Interval& i : list)
                if (i.t0 <= t && t < i.t1 && i.depthAt(t) < nearest) nearest = i.depthAt(t), color = i.color.x;
            expected += color * (times[k + 1] - times[k]);
        }
        SortCounters counters;
        sortDepthTime(list, 90, counters);
        if (counters.cycles > 0) continue;
        ++numCompared;
        EXPECT_NEAR(resolveIntervals(list, 128, glm::vec3(0.0f), OpaqueWeights::Exact).x, expected, 2e-4) << "trial " << trial;
        worstSlices = std::max(worstSlices, std::abs(double(resolveIntervals(list, 32, glm::vec3(0.0f)).x) - expected));
    }
    EXPECT_GT(numCompared, 250);
    EXPECT_GT(worstSlices, 0.05) << "32 slices must be visibly coarser than exact weights";
}

}  // namespace streak::motion_path

namespace streak::motion_path {

// The paper's sort by its definition: split every crossing pair, then place at each position
// the first remaining interval that every other remaining one lets stay in front, checking them
// all. sortDepthTime scans only the candidates' depth neighbours; it must choose the same.
TEST(DepthTimeSort, ChoosesAsTheFullSelectionDoes) {
    auto reference = [](std::vector<Interval> list, int maxIntervals) {
        std::sort(list.begin(), list.end(), [](const Interval& a, const Interval& b) { return a.minDepth() < b.minDepth(); });
        for (std::size_t i = 0; i < list.size(); ++i)
            for (std::size_t j = i + 1; j < list.size(); ++j) {
                Interval a = list[i], b = list[j], aTail, bTail;
                if (!splitAtCrossing(a, b, aTail, bTail) || int(list.size()) + 2 > maxIntervals) continue;
                list[i] = a, list[j] = b;
                list.push_back(aTail), list.push_back(bTail);
            }
        for (std::size_t i = 0; i + 1 < list.size(); ++i) {
            std::size_t front = i;
            for (std::size_t c = i; c < list.size(); ++c) {
                bool ok = true;
                for (std::size_t k = i; k < list.size() && ok; ++k) ok = k == c || canStayBefore(list[c], list[k]);
                if (ok) {
                    front = c;
                    break;
                }
            }
            std::swap(list[i], list[front]);
        }
        return list;
    };
    Rng rng(5);
    int cycles = 0, splits = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        // Dense lists: up to 40 intervals over a narrow depth band, so most overlap in depth.
        std::vector<Interval> list;
        const int n = 2 + int(rng.next() % 39);
        for (int i = 0; i < n; ++i) {
            float t0 = rng.uniform(), t1 = rng.uniform();
            if (t0 > t1) std::swap(t0, t1);
            list.push_back(make(t0, std::max(t1, t0 + 0.01f), rng.uniform(1.0f, 3.0f), rng.uniform(1.0f, 3.0f), std::uint32_t(i)));
        }
        const std::vector<Interval> expected = reference(list, 90);
        SortCounters counters;
        sortDepthTime(list, 90, counters);
        cycles += counters.cycles, splits += counters.splits;
        ASSERT_EQ(list.size(), expected.size()) << "trial " << trial;
        for (std::size_t i = 0; i < list.size(); ++i) {
            EXPECT_EQ(list[i].source, expected[i].source) << "trial " << trial << " place " << i;
            EXPECT_EQ(list[i].t0, expected[i].t0) << "trial " << trial << " place " << i;
            EXPECT_EQ(list[i].depth0, expected[i].depth0) << "trial " << trial << " place " << i;
        }
    }
    EXPECT_GT(splits, 1000);  // crossings were split and sorted, not only disjoint lists
    EXPECT_GT(cycles, 0);     // and the cycle fallback was met
}

}  // namespace streak::motion_path

namespace streak::motion_path {

namespace {

// A random surface at one sample: `pieces` abutting linear intervals over a random time span,
// its depth a random polyline in [1, 4] (a finely keyed motion), all with the surface's id.
void addRandomSurface(Rng& rng, std::uint32_t id, int pieces, std::vector<Interval>& list) {
    float t0 = rng.uniform(), t1 = rng.uniform();
    if (t0 > t1) std::swap(t0, t1);
    t0 = std::min(t0, 0.95f), t1 = std::max(t1, t0 + 0.05f);
    float depth = rng.uniform(1.0f, 4.0f);
    for (int p = 0; p < pieces; ++p) {
        const float a = t0 + (t1 - t0) * float(p) / float(pieces), b = p + 1 == pieces ? t1 : t0 + (t1 - t0) * float(p + 1) / float(pieces);
        const float next = std::clamp(depth + rng.uniform(-0.6f, 0.6f), 1.0f, 4.0f);
        list.push_back(make(a, b, depth, next, id, glm::vec3(float(id + 1), 0, 0)));
        depth = next;
    }
}

// The exact time integral of the nearest piece's id + 1, and which id is nearest where: a sweep
// over every end and every crossing of two linear pieces (in double); between two such times
// the nearest piece is one piece.
struct Sweep {
    std::vector<double> times;
    std::vector<int> nearest;  ///< per piece of time: the nearest id, -1 for none
    double integral = 0.0;
};

Sweep sweepNearest(const std::vector<Interval>& pieces) {
    Sweep sweep;
    sweep.times = {0.0, 1.0};
    for (const Interval& a : pieces) {
        sweep.times.push_back(a.t0), sweep.times.push_back(a.t1);
        for (const Interval& b : pieces) {
            const double sa = (double(a.depth1) - a.depth0) / (double(a.t1) - a.t0), sb = (double(b.depth1) - b.depth0) / (double(b.t1) - b.t0);
            if (sa == sb) continue;
            const double t = (b.depth0 - sb * b.t0 - (a.depth0 - sa * a.t0)) / (sa - sb);
            if (t > 0.0 && t < 1.0) sweep.times.push_back(t);
        }
    }
    std::sort(sweep.times.begin(), sweep.times.end());
    for (std::size_t k = 0; k + 1 < sweep.times.size(); ++k) {
        const double t = 0.5 * (sweep.times[k] + sweep.times[k + 1]);
        double nearest = 1e9;
        int id = -1;
        for (const Interval& i : pieces)
            if (i.t0 <= t && t < i.t1) {
                const double d = i.depth0 + (double(i.depth1) - i.depth0) * (t - i.t0) / (double(i.t1) - i.t0);
                if (d < nearest) nearest = d, id = int(i.source);
            }
        sweep.nearest.push_back(id);
        sweep.integral += (id + 1) * (sweep.times[k + 1] - sweep.times[k]);
    }
    return sweep;
}

}  // namespace

// Merging: one run per surface, its joints as corners; gaps, other surfaces, depth jumps and
// translucent intervals end a run; corners where nothing bends are left out.
TEST(MergedIntervals, MergeRunsOfOneSurfaceOnly) {
    std::vector<Interval> list{make(0.0f, 0.2f, 2, 3, 0), make(0.2f, 0.4f, 3, 2, 0), make(0.4f, 0.6f, 2, 2, 0),
                               make(0.6f, 0.8f, 2, 2, 0), make(0.8f, 0.9f, 2, 5, 0),   // one run, 3 corners (0.6 is straight)
                               make(0.95f, 1.0f, 5, 5, 0),                             // a gap
                               make(0.0f, 0.5f, 4, 4, 1), make(0.5f, 1.0f, 6, 6, 1),   // a depth jump
                               make(0.0f, 0.5f, 7, 7, 2), make(0.5f, 1.0f, 7, 8, 3)};  // another surface
    std::vector<DepthKnot> knots;
    const int merged = mergeAbuttingIntervals(list, 0, knots, [](std::uint32_t a, std::uint32_t b) { return a == b; });
    EXPECT_EQ(merged, 4);
    ASSERT_EQ(list.size(), 6u);
    EXPECT_EQ(list[0].t0, 0.0f);
    EXPECT_EQ(list[0].t1, 0.9f);
    EXPECT_EQ(list[0].depth1, 5.0f);
    ASSERT_EQ(list[0].numKnots, 3u);
    EXPECT_EQ(knots[list[0].firstKnot].t, 0.2f);
    EXPECT_EQ(knots[list[0].firstKnot + 2].t, 0.8f);
    EXPECT_EQ(list[0].minDepth(), 2.0f);
    EXPECT_EQ(list[0].maxDepth(), 5.0f);
    EXPECT_FLOAT_EQ(depthAt(list[0], knots, 0.2f), 3.0f);
    EXPECT_FLOAT_EQ(depthAt(list[0], knots, 0.7f), 2.0f);
    EXPECT_FLOAT_EQ(depthAt(list[0], knots, 0.85f), 3.5f);
    EXPECT_EQ(list[1].t0, 0.95f);
    EXPECT_EQ(list[2].t1, 0.5f);
    EXPECT_EQ(list[3].t0, 0.5f);
    EXPECT_EQ(list[4].source, 2u);
    EXPECT_EQ(list[5].source, 3u);

    std::vector<Interval> translucent{make(0.0f, 0.5f, 2, 2, 0, glm::vec3(1), 0.5f), make(0.5f, 1.0f, 2, 2, 0, glm::vec3(1), 0.5f)};
    EXPECT_EQ(mergeAbuttingIntervals(translucent, 0, knots, [](std::uint32_t, std::uint32_t) { return true; }), 0);
}

// A V-shaped polyline crosses a flat interval twice; the sort splits both crossings, and the
// exact resolve shows the V in its middle and the flat line either side, each span where it
// shows.
TEST(MergedIntervals, PolylineCrossingsAreSplitAndShownWhereTheyShow) {
    std::vector<Interval> list{make(0.0f, 0.5f, 5, 1, 0), make(0.5f, 1.0f, 1, 5, 0)};
    std::vector<DepthKnot> knots;
    mergeAbuttingIntervals(list, 0, knots, [](std::uint32_t a, std::uint32_t b) { return a == b; });
    ASSERT_EQ(list.size(), 1u);
    list.push_back(make(0.0f, 1.0f, 3, 3, 1));
    SortCounters counters;
    sortDepthTime(list, 90, counters, knots);
    EXPECT_EQ(counters.splits, 2);
    std::vector<float> weights(list.size());
    std::vector<exposure::VisibleSpan> visible;
    EXPECT_FLOAT_EQ(resolveOpaqueSpans(list, weights, ShutterWindow(), visible), 0.0f);
    float v = 0.0f, flat = 0.0f;
    for (const exposure::VisibleSpan& s : visible) {
        const bool isV = list[s.interval].source == 0;
        (isV ? v : flat) += s.weight;
        if (isV) {
            EXPECT_NEAR(s.t0, 0.25f, 1e-6f);
            EXPECT_NEAR(s.t1, 0.75f, 1e-6f);
        } else {
            EXPECT_TRUE(std::abs(s.t1 - 0.25f) < 1e-6f || std::abs(s.t0 - 0.75f) < 1e-6f) << s.t0 << " " << s.t1;
        }
    }
    EXPECT_NEAR(v, 0.5f, 1e-6f);
    EXPECT_NEAR(flat, 0.5f, 1e-6f);
}

// Random stacks of finely pieced surfaces: merged into polylines, sorted and resolved, they
// give the exact integral of the nearest surface (the sweep over their pieces), and every
// visible span lies where its surface is the nearest.
TEST(MergedIntervals, RandomPolylinesResolveToTheExactNearest) {
    Rng rng(77);
    int numCompared = 0, numMerged = 0;
    for (int trial = 0; trial < 400; ++trial) {
        std::vector<Interval> pieces;
        const int surfaces = 1 + int(rng.next() % 5);
        for (int s = 0; s < surfaces; ++s) addRandomSurface(rng, std::uint32_t(s), 1 + int(rng.next() % 12), pieces);
        const Sweep sweep = sweepNearest(pieces);
        std::vector<Interval> list = pieces;
        std::vector<DepthKnot> knots;
        numMerged += mergeAbuttingIntervals(list, 0, knots, [](std::uint32_t a, std::uint32_t b) { return a == b; });
        EXPECT_EQ(int(list.size()), surfaces);
        SortCounters counters;
        sortDepthTime(list, 2048, counters, knots);
        if (counters.cycles > 0) continue;
        ++numCompared;
        std::vector<float> weights(list.size());
        std::vector<exposure::VisibleSpan> visible;
        const float background = resolveOpaqueSpans(list, weights, ShutterWindow(), visible);
        double got = 0.0, none = 0.0;
        for (std::size_t i = 0; i < list.size(); ++i) got += double(weights[i]) * (list[i].source + 1);
        for (std::size_t k = 0; k < sweep.nearest.size(); ++k)
            if (sweep.nearest[k] < 0) none += sweep.times[k + 1] - sweep.times[k];
        EXPECT_NEAR(got, sweep.integral, 2e-4) << "trial " << trial;
        EXPECT_NEAR(background, none, 1e-4) << "trial " << trial;
        // Each visible span: its interval's surface is the nearest at its middle, and the spans
        // of an interval add up to its weight.
        std::vector<double> spanSum(list.size(), 0.0);
        for (const exposure::VisibleSpan& s : visible) {
            spanSum[s.interval] += s.weight;
            const double t = 0.5 * (double(s.t0) + s.t1);
            const std::size_t k = std::size_t(std::upper_bound(sweep.times.begin(), sweep.times.end(), t) - sweep.times.begin()) - 1;
            if (s.t1 - s.t0 > 1e-4f) { EXPECT_EQ(sweep.nearest[k], int(list[s.interval].source)) << "trial " << trial << " at " << t; }
        }
        for (std::size_t i = 0; i < list.size(); ++i) EXPECT_NEAR(spanSum[i], weights[i], 1e-5) << "trial " << trial;
    }
    EXPECT_GT(numCompared, 360);
    EXPECT_GT(numMerged, 1000);
}

}  // namespace streak::motion_path
