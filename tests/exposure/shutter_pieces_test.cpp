#include "exposure/shutter_pieces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace streak::exposure {

namespace {

struct Piece {
    float a, b;
    std::vector<std::size_t> covering;
    bool operator==(const Piece&) const = default;
};

template <class Enumerate>
std::vector<Piece> piecesOf(std::span<const ExposureInterval> intervals, Enumerate&& enumerate) {
    std::vector<Piece> out;
    enumerate(intervals, [&](float a, float b, std::span<std::size_t> covering) { out.push_back({a, b, {covering.begin(), covering.end()}}); });
    return out;
}

// A dense sample's list: many short spans (a sliver of the shutter each), their ends often on
// a coarse grid (shared ends, spans that abut, equal starts), depth lines that cross, some the
// same line twice (a tie, which the lower index wins), and some empty spans.
std::vector<ExposureInterval> denseList(std::mt19937& rng, std::size_t n) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<ExposureInterval> list(n);
    for (ExposureInterval& x : list) {
        const float length = unit(rng) < 0.1f ? 0.5f * unit(rng) : 0.08f * unit(rng);
        float t0 = unit(rng) * (1.0f - length);
        if (unit(rng) < 0.3f) t0 = std::round(t0 * 16.0f) / 16.0f;
        x.t0 = t0, x.t1 = std::min(1.0f, unit(rng) < 0.05f ? t0 : t0 + length);
        x.depth0 = 1.0f + 9.0f * unit(rng), x.depth1 = 1.0f + 9.0f * unit(rng);
    }
    for (std::size_t k = 0; k + 1 < n; k += 7) list[k + 1].depth0 = list[k].depth0, list[k + 1].depth1 = list[k].depth1, list[k + 1].t0 = list[k].t0,
                                                  list[k + 1].t1 = std::max(list[k + 1].t1, list[k].t0);
    return list;
}

}  // namespace

TEST(ShutterPieces, TheSweepFindsThePairsPiecesToTheBit) {
    // The same cuts (every end and crossing), the same covering in the same order, for lists
    // from a few intervals to a dense sample's hundreds.
    std::mt19937 rng(7);
    auto byPairs = [](std::span<const ExposureInterval> l, auto&& f) { pieces::byPairs(l, f); };
    auto bySweep = [](std::span<const ExposureInterval> l, auto&& f) { pieces::bySweep(l, f); };
    std::size_t numPieces = 0;
    for (const std::size_t n : {2u, 5u, 9u, 17u, 40u, 161u, 400u})
        for (int trial = 0; trial < 20; ++trial) {
            const std::vector<ExposureInterval> list = denseList(rng, n);
            ASSERT_TRUE(pieces::isInsideShutter(list));
            const std::vector<Piece> pairs = piecesOf(list, byPairs), sweep = piecesOf(list, bySweep);
            ASSERT_EQ(pairs.size(), sweep.size()) << n << " intervals, trial " << trial;
            for (std::size_t k = 0; k < pairs.size(); ++k) ASSERT_EQ(pairs[k], sweep[k]) << n << " intervals, trial " << trial << ", piece " << k;
            numPieces += pairs.size();
        }
    EXPECT_GT(numPieces, 20000u);  // the lists did cut the shutter finely
}

TEST(ShutterPieces, ADenseListsOpaqueSharesAreWhereEachIntervalIsNearest) {
    // Against the shutter sampled at a million instants: at each, the covering interval of least
    // depth (the lower index on a tie) takes the instant. The sampled shares carry an error of
    // about one instant per cut.
    std::mt19937 rng(11);
    const std::vector<ExposureInterval> list = denseList(rng, 161);
    std::vector<float> weights(list.size());
    const float background = resolveOpaque(list, weights);
    constexpr int kInstants = 1 << 20;
    std::vector<double> sampled(list.size(), 0.0);
    double sampledBackground = 0.0;
    for (int k = 0; k < kInstants; ++k) {
        const float t = (float(k) + 0.5f) / float(kInstants);
        std::size_t nearest = list.size();
        for (std::size_t i = 0; i < list.size(); ++i)
            if (list[i].t0 <= t && t < list[i].t1 && (nearest == list.size() || list[i].depthAt(t) < list[nearest].depthAt(t))) nearest = i;
        (nearest == list.size() ? sampledBackground : sampled[nearest]) += 1.0 / kInstants;
    }
    int numVisible = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
        EXPECT_NEAR(weights[i], sampled[i], 2e-5) << "interval " << i;
        numVisible += weights[i] > 0.0f;
    }
    EXPECT_NEAR(background, sampledBackground, 2e-5);
    EXPECT_GT(numVisible, 40);  // most of the list shows at some time: the resolve had work to do
}

TEST(ShutterPieces, ListsReachingPastTheShutterKeepThePairs) {
    // The sweep is for spans inside the shutter; a list with one outside it, or not a number,
    // takes the pairs, so its pieces are theirs.
    std::mt19937 rng(3);
    std::vector<ExposureInterval> list = denseList(rng, 30);
    list[4].t0 = -0.25f;
    EXPECT_FALSE(pieces::isInsideShutter(list));
    list[4].t0 = 0.5f, list[4].t1 = 1.5f;
    EXPECT_FALSE(pieces::isInsideShutter(list));
    list[4].t1 = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(pieces::isInsideShutter(list));
    list[4].t1 = 0.25f;  // ends before it starts
    EXPECT_FALSE(pieces::isInsideShutter(list));
    list[4].t1 = 0.75f;
    list[9].t0 = -0.1f;
    auto byPairs = [](std::span<const ExposureInterval> l, auto&& f) { pieces::byPairs(l, f); };
    auto any = [](std::span<const ExposureInterval> l, auto&& f) { forEachPiece(l, f); };
    EXPECT_EQ(piecesOf(list, byPairs), piecesOf(list, any));
}

}  // namespace streak::exposure
