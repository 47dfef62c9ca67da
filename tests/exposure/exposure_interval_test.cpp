#include "exposure/exposure_interval.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

namespace streak::exposure {

namespace {

ExposureInterval interval(float t0, float t1, float depth0, float depth1, glm::vec3 color = glm::vec3(1.0f), float alpha = 1.0f) {
    ExposureInterval x;
    x.t0 = t0, x.t1 = t1, x.depth0 = depth0, x.depth1 = depth1, x.color = color, x.alpha = alpha, x.isShaded = true;
    return x;
}

}  // namespace

TEST(Oracle, HandComputed) {
    // a [0, 0.2] at depth 5, b [0.3, 0.4] from depth 5 to 6, colours 0.1 apart in red:
    // gap 0.1, relative mean depth |5 - 5.5| / 5.5, relative slope |0 - 10| / 5.5, durations
    // 0.3, colour 0.1.
    const ExposureInterval a = interval(0.0f, 0.2f, 5.0f, 5.0f, {0.5f, 0.0f, 0.0f});
    const ExposureInterval b = interval(0.3f, 0.4f, 5.0f, 6.0f, {0.6f, 0.0f, 0.0f});
    const OracleWeights h{1.0f, 2.0f, 3.0f, 4.0f, 5.0f};
    const float expected = 1.0f * 0.1f + 2.0f * 0.5f / 5.5f + 3.0f * 10.0f / 5.5f + 4.0f * 0.3f + 5.0f * 0.1f;
    EXPECT_NEAR(oracle(a, b, h), expected, 1e-4f);
    EXPECT_NEAR(oracle(b, a, h), expected, 1e-4f);
}

TEST(Compression, KeepsTheBudgetAndMergesTheMostSimilarPair) {
    // A and B: the same red surface at the same depth, a short gap apart. C: blue, far, all
    // shutter. D: green, near, mid shutter. With room for three, A and B become one interval
    // over [0, 0.45]; C and D are untouched.
    std::vector<ExposureInterval> list{interval(0.0f, 0.2f, 5.0f, 5.0f, {1, 0, 0}), interval(0.5f, 0.7f, 3.0f, 3.0f, {0, 1, 0}),
                                       interval(0.0f, 1.0f, 10.0f, 10.0f, {0, 0, 1}), interval(0.25f, 0.45f, 5.0f, 5.0f, {1, 0, 0})};
    EXPECT_EQ(compressIntervals(list, 3, OracleWeights{}), 1);
    ASSERT_EQ(list.size(), 3u);
    EXPECT_FLOAT_EQ(list[0].t0, 0.0f);
    EXPECT_FLOAT_EQ(list[0].t1, 0.45f);
    EXPECT_TRUE(list[0].isMerged);
    EXPECT_EQ(list[0].color, glm::vec3(1, 0, 0));
    EXPECT_EQ(list[1].color, glm::vec3(0, 1, 0));
    EXPECT_EQ(list[2].color, glm::vec3(0, 0, 1));
    // A budget of one merges everything, a budget of 0 means unlimited.
    EXPECT_EQ(compressIntervals(list, 1, OracleWeights{}), 2);
    EXPECT_EQ(list.size(), 1u);
    std::vector<ExposureInterval> unlimited(5, interval(0.0f, 1.0f, 1.0f, 1.0f));
    EXPECT_EQ(compressIntervals(unlimited, 0, OracleWeights{}), 0);
}

TEST(MergeIntervals, UnionsCoverageAndBlendsByDuration) {
    const ExposureInterval m = mergeIntervals(interval(0.6f, 0.7f, 2.0f, 3.0f, {1, 0, 0}, 1.0f), interval(0.1f, 0.4f, 4.0f, 5.0f, {0, 0, 1}, 0.2f));
    EXPECT_FLOAT_EQ(m.t0, 0.1f);
    EXPECT_FLOAT_EQ(m.t1, 0.7f);
    EXPECT_FLOAT_EQ(m.depth0, 4.0f);
    EXPECT_FLOAT_EQ(m.depth1, 3.0f);
    EXPECT_NEAR(m.color.x, 0.25f, 1e-6f);
    EXPECT_NEAR(m.color.z, 0.75f, 1e-6f);
    EXPECT_NEAR(m.alpha, 0.25f * 1.0f + 0.75f * 0.2f, 1e-6f);
}

TEST(Resolve, OpaqueHandMadeLists) {
    // A far surface all shutter, a near one over [0.5, 0.7]: 0.8 and 0.2, no background.
    std::vector<ExposureInterval> list{interval(0.0f, 1.0f, 10.0f, 10.0f), interval(0.5f, 0.7f, 3.0f, 3.0f)};
    std::vector<float> w(2);
    EXPECT_NEAR(resolveOpaque(list, w), 0.0f, 1e-6f);
    EXPECT_NEAR(w[0], 0.8f, 1e-6f);
    EXPECT_NEAR(w[1], 0.2f, 1e-6f);
    // Two surfaces crossing in depth at t = 0.25 (2 -> 4 and 3 -> 1 over [0, 1]... at 0.25 both
    // are 2.5): the first is nearer before, the second after; the background shows nowhere.
    list = {interval(0.0f, 1.0f, 2.0f, 4.0f), interval(0.0f, 1.0f, 3.0f, 1.0f)};
    EXPECT_NEAR(resolveOpaque(list, w), 0.0f, 1e-6f);
    EXPECT_NEAR(w[0], 0.25f, 1e-6f);
    EXPECT_NEAR(w[1], 0.75f, 1e-6f);
    // A gap: background.
    list = {interval(0.1f, 0.3f, 1.0f, 1.0f), interval(0.6f, 0.8f, 1.0f, 1.0f)};
    EXPECT_NEAR(resolveOpaque(list, w), 0.6f, 1e-6f);
    // The linearised order against a true depth that says otherwise over [0, 0.5].
    list = {interval(0.0f, 1.0f, 2.0f, 2.0f), interval(0.0f, 1.0f, 3.0f, 3.0f)};
    const ExactDepth exact = [](std::size_t i, float t) { return i == 0 ? 2.0 : (t < 0.5f ? 1.0 : 3.0); };
    double misordered = 0.0;
    resolveOpaque(list, w, {}, &exact, &misordered);
    EXPECT_NEAR(misordered, 0.0, 1e-9);  // no cut at 0.5: the middle (t = 0.5) decides the one piece
    list.push_back(interval(0.25f, 0.5f, 9.0f, 9.0f));  // adds cuts at 0.25 and 0.5
    w.resize(3);
    resolveOpaque(list, w, {}, &exact, &misordered);
    EXPECT_NEAR(misordered, 0.5, 1e-6);
}

// Where each interval shows: a near surface over [0.5, 0.7] splits the far one's visible time
// in two spans, [0, 0.5] and [0.7, 1]; consecutive pieces of one interval are one span.
TEST(Resolve, VisibleSpansAreWhereEachIntervalIsNearest) {
    std::vector<ExposureInterval> list{interval(0.0f, 1.0f, 10.0f, 10.0f), interval(0.5f, 0.7f, 3.0f, 3.0f),
                                       interval(0.1f, 0.3f, 12.0f, 12.0f)};  // hidden: adds cuts at 0.1 and 0.3
    std::vector<float> w(3);
    std::vector<VisibleSpan> visible;
    resolveOpaque(list, w, {}, nullptr, nullptr, nullptr, &visible);
    ASSERT_EQ(visible.size(), 3u);
    EXPECT_EQ(visible[0].interval, 0u);
    EXPECT_FLOAT_EQ(visible[0].t0, 0.0f);
    EXPECT_FLOAT_EQ(visible[0].t1, 0.5f);
    EXPECT_NEAR(visible[0].weight, 0.5f, 1e-6f);
    EXPECT_EQ(visible[1].interval, 1u);
    EXPECT_FLOAT_EQ(visible[1].t0, 0.5f);
    EXPECT_FLOAT_EQ(visible[1].t1, 0.7f);
    EXPECT_EQ(visible[2].interval, 0u);
    EXPECT_FLOAT_EQ(visible[2].t0, 0.7f);
    EXPECT_FLOAT_EQ(visible[2].t1, 1.0f);
    EXPECT_NEAR(visible[0].weight + visible[2].weight, w[0], 1e-6f);
    EXPECT_EQ(w[2], 0.0f);
}

TEST(Resolve, SharesAreTheRowsExposure) {
    // Under the triangle curve exposure up to t is 2t^2 (t <= 1/2): a near surface over [0, 0.25]
    // takes 1/8 of the sample, the far one all shutter the other 7/8.
    const ShutterCurve triangle = ShutterCurve::parse("triangle");
    const ShutterWindow window{0.0f, 1.0f, &triangle};
    std::vector<ExposureInterval> list{interval(0.0f, 1.0f, 10.0f, 10.0f), interval(0.0f, 0.25f, 3.0f, 3.0f)};
    std::vector<float> w(2);
    EXPECT_NEAR(resolveOpaque(list, w, window), 0.0f, 1e-6f);
    EXPECT_NEAR(w[1], 0.125f, 1e-6f);
    EXPECT_NEAR(w[0], 0.875f, 1e-6f);
    // A rolling row open over [0.5, 0.75] (box) sees none of a surface over [0, 0.5] and half of
    // one over [0.25, 0.625]; the rest of its window is background.
    const ShutterWindow row{0.5f, 0.25f, nullptr};
    list = {interval(0.0f, 0.5f, 1.0f, 1.0f), interval(0.25f, 0.625f, 2.0f, 2.0f)};
    EXPECT_NEAR(resolveOpaque(list, w, row), 0.5f, 1e-6f);
    EXPECT_NEAR(w[0], 0.0f, 1e-6f);
    EXPECT_NEAR(w[1], 0.5f, 1e-6f);
    list[1].alpha = 0.5f;
    EXPECT_NEAR(resolveTranslucent(list, w, row), 0.75f, 1e-6f);
    EXPECT_NEAR(w[1], 0.25f, 1e-6f);
}

TEST(Resolve, ALoneIntervalTakesTheSharesTheSweepGivesIt) {
    // A lone interval's cuts are written in order, not sorted; the same interval with a second one
    // wholly behind it over the same times takes the sorted cuts, at the same times: the
    // shares, the background and the visible span must be the same to the bit. Inside the
    // shutter, at its ends, reaching past them, under a curve and in a rolling row.
    const ShutterCurve triangle = ShutterCurve::parse("triangle");
    for (const ShutterWindow window : {ShutterWindow{}, ShutterWindow{0.0f, 1.0f, &triangle}, ShutterWindow{0.3f, 0.4f, nullptr}}) {
        for (const auto& [t0, t1] : {std::pair{0.0f, 1.0f}, std::pair{0.2f, 0.7f}, std::pair{0.0f, 0.35f}, std::pair{0.6f, 1.0f},
                                     std::pair{-0.5f, 0.4f}, std::pair{0.45f, 1.5f}, std::pair{0.1f, 0.1f}}) {
            std::vector<ExposureInterval> lone{interval(t0, t1, 2.0f, 3.0f)}, swept{lone[0], interval(t0, t1, 50.0f, 60.0f)};
            std::vector<float> wLone(1), wSwept(2);
            std::vector<VisibleSpan> vLone, vSwept;
            const float bLone = resolveOpaque(lone, wLone, window, nullptr, nullptr, nullptr, &vLone);
            const float bSwept = resolveOpaque(swept, wSwept, window, nullptr, nullptr, nullptr, &vSwept);
            EXPECT_EQ(bLone, bSwept) << t0 << ".." << t1;
            EXPECT_EQ(wLone[0], wSwept[0]) << t0 << ".." << t1;
            EXPECT_EQ(wSwept[1], 0.0f);
            ASSERT_EQ(vLone.size(), vSwept.size()) << t0 << ".." << t1;
            for (std::size_t k = 0; k < vLone.size(); ++k) {
                EXPECT_EQ(vLone[k].interval, vSwept[k].interval);
                EXPECT_EQ(vLone[k].t0, vSwept[k].t0);
                EXPECT_EQ(vLone[k].t1, vSwept[k].t1);
                EXPECT_EQ(vLone[k].weight, vSwept[k].weight);
            }
            // And the closed form: the window's measure of the clamped interval, the rest
            // background.
            const float c0 = std::clamp(t0, 0.0f, 1.0f), c1 = std::clamp(t1, 0.0f, 1.0f);
            EXPECT_NEAR(wLone[0], window.measure(c0, c1), 1e-6f);
            EXPECT_NEAR(bLone + wLone[0], window.measure(0.0f, 1.0f), 1e-6f);
        }
    }
}

TEST(Resolve, TranslucentHandMadeLists) {
    // Glass (alpha 0.5) over [0, 0.5] in front of an opaque surface all shutter: the glass takes
    // 0.5 * 0.5, the surface 0.5 * 0.5 behind it plus 0.5 alone.
    std::vector<ExposureInterval> list{interval(0.0f, 1.0f, 5.0f, 5.0f), interval(0.0f, 0.5f, 1.0f, 1.0f, glm::vec3(1.0f), 0.5f)};
    std::vector<float> w(2);
    EXPECT_NEAR(resolveTranslucent(list, w), 0.0f, 1e-6f);
    EXPECT_NEAR(w[0], 0.75f, 1e-6f);
    EXPECT_NEAR(w[1], 0.25f, 1e-6f);
    // Two glasses over the background: 0.5, then 0.5 * 0.4, and 0.5 * 0.6 through to the back.
    list = {interval(0.0f, 1.0f, 2.0f, 2.0f, glm::vec3(1.0f), 0.4f), interval(0.0f, 1.0f, 1.0f, 1.0f, glm::vec3(1.0f), 0.5f)};
    EXPECT_NEAR(resolveTranslucent(list, w), 0.3f, 1e-6f);
    EXPECT_NEAR(w[1], 0.5f, 1e-6f);
    EXPECT_NEAR(w[0], 0.2f, 1e-6f);
}

}  // namespace streak::exposure
