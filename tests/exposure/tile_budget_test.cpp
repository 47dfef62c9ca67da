// The memory budget's tile pieces: halving a rectangle until each piece fits, and a single
// pixel's cut to each sample's nearest items.

#include "exposure/tile_budget.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace streak::exposure {
namespace {

int area(const raster::PixelBounds& r) { return (r.x1 - r.x0 + 1) * (r.y1 - r.y0 + 1); }

TEST(RenderWithinShare, HalvesUntilEveryPieceFitsAndCoversTheTileOnce) {
    const raster::PixelBounds tile{16, 32, 31, 44};  // 16 x 13 pixels
    for (const int fits : {1, 5, 16, 100, 208}) {
        SCOPED_TRACE(fits);
        std::vector<int> rendered(std::size_t(area(tile)), 0);
        TileBudgetCounters counters;
        int attempts = 0;
        renderWithinShare(tile, counters, [&](const raster::PixelBounds& r, bool isPixel) {
            ++attempts;
            EXPECT_EQ(isPixel, area(r) == 1);
            if (area(r) > fits && !isPixel) return false;  // passed its share: nothing written
            for (int y = r.y0; y <= r.y1; ++y)
                for (int x = r.x0; x <= r.x1; ++x) ++rendered[std::size_t((y - tile.y0) * 16 + (x - tile.x0))];
            return true;
        });
        EXPECT_TRUE(std::all_of(rendered.begin(), rendered.end(), [](int n) { return n == 1; }));
        // Every refused attempt was split in two, and the halves were attempted.
        EXPECT_EQ(attempts, 2 * counters.splits + 1);
        if (fits >= area(tile)) { EXPECT_EQ(counters.splits, 0); }
        // Halving across the longer side: 208 pixels need at least ceil(208 / fits) pieces and
        // get under twice that.
        const int pieces = int(counters.splits) + 1;
        EXPECT_GE(pieces, (area(tile) + fits - 1) / fits);
        EXPECT_LT(pieces, 2 * ((area(tile) + fits - 1) / fits) + 1);
        EXPECT_EQ(counters.pixelsCut, 0);
    }
}

TEST(RenderWithinShare, GoesStraightToThePiecesARefusedAttemptAsksFor) {
    // 256 pixels where 8 fit: a refusal that says "32 shares" is cut into 32 pieces of 8 pixels
    // at once (16x16 -> 8x16 -> 8x8 -> 4x8 -> 4x4 -> 2x4), none of the sizes between attempted.
    const raster::PixelBounds tile{0, 0, 15, 15};
    std::vector<int> rendered(256, 0);
    TileBudgetCounters counters;
    int attempts = 0, refused = 0;
    renderWithinShare(tile, counters, [&](const raster::PixelBounds& r, bool isPixel) {
        ++attempts;
        if (area(r) > 8 && !isPixel) {
            ++refused;
            counters.refuse(std::size_t(area(r)), 8, 1, 1);
            return false;
        }
        EXPECT_EQ(area(r), 8);
        for (int y = r.y0; y <= r.y1; ++y)
            for (int x = r.x0; x <= r.x1; ++x) ++rendered[std::size_t(y * 16 + x)];
        return true;
    });
    EXPECT_TRUE(std::all_of(rendered.begin(), rendered.end(), [](int n) { return n == 1; }));
    EXPECT_EQ(refused, 1);
    EXPECT_EQ(attempts, 33);
    EXPECT_EQ(counters.splits, 31);  // the halvings of a binary tree with 32 leaves
}

TEST(TileBudgetCounters, ARefusalEstimatesTheWholeListFromHowFarItGot) {
    TileBudgetCounters c;
    c.refuse(150, 100, 25, 100);  // 1.5 shares after a quarter of the inputs: 6 for all of them
    EXPECT_DOUBLE_EQ(c.refusedOver, 6.0);
    c.refuse(150, 100, 0, 100);  // (none done is taken as one)
    EXPECT_DOUBLE_EQ(c.refusedOver, 150.0);
}

TEST(RenderWithinShare, CountsAPixelAsCutOnlyWhereItDropped) {
    TileBudgetCounters counters;
    renderWithinShare({0, 0, 1, 0}, counters, [&](const raster::PixelBounds& r, bool isPixel) {
        if (!isPixel) return false;
        if (r.x0 == 1) counters.dropped += 3;  // the second pixel cut its lists
        return true;
    });
    EXPECT_EQ(counters.splits, 1);
    EXPECT_EQ(counters.pixelsCut, 1);
    EXPECT_EQ(counters.dropped, 3);
}

struct Item {
    std::uint32_t sample = 0;
    float nearness = 0.0f;
    int order = 0;  ///< where it was made
};

TEST(KeepNearestPerSample, KeepsEachSamplesNearestInTheirOrder) {
    std::mt19937 rng(7);
    for (int round = 0; round < 200; ++round) {
        const std::size_t numSamples = 1 + rng() % 9, perSample = 1 + rng() % 6;
        std::vector<Item> items;
        const int n = int(rng() % 80);
        for (int i = 0; i < n; ++i)  // few distinct keys, so ties occur
            items.push_back({std::uint32_t(rng() % numSamples), float(rng() % 7), i});
        const std::vector<Item> made = items;
        std::vector<std::uint32_t> runs;
        std::vector<Item> grouped;
        std::vector<float> keys;
        const std::size_t dropped = keepNearestPerSample(items, numSamples, perSample, runs, grouped, keys,
                                                         [](std::span<Item> run) { return run.size(); }, [](const Item& x) { return x.nearness; });
        // Expected: per sample, stable-sorted by nearness (ties: the first made), the first
        // perSample, back in the order made; samples in turn.
        std::vector<Item> expected;
        for (std::uint32_t s = 0; s < numSamples; ++s) {
            std::vector<Item> mine;
            for (const Item& x : made)
                if (x.sample == s) mine.push_back(x);
            std::stable_sort(mine.begin(), mine.end(), [](const Item& a, const Item& b) { return a.nearness > b.nearness; });
            if (mine.size() > perSample) mine.resize(perSample);
            std::sort(mine.begin(), mine.end(), [](const Item& a, const Item& b) { return a.order < b.order; });
            expected.insert(expected.end(), mine.begin(), mine.end());
        }
        ASSERT_EQ(items.size(), expected.size());
        EXPECT_EQ(dropped, made.size() - expected.size());
        for (std::size_t i = 0; i < items.size(); ++i) {
            EXPECT_EQ(items[i].order, expected[i].order);
            EXPECT_EQ(items[i].sample, expected[i].sample);
        }
    }
}

TEST(KeepNearestPerSample, PrepareShortensARunBeforeTheCut) {
    // Repeats of one item are dropped by prepare first, and do not count as cut.
    std::vector<Item> items = {{0, 1.0f, 0}, {0, 1.0f, 0}, {0, 2.0f, 1}, {0, 2.0f, 1}, {0, 3.0f, 2}};
    std::vector<std::uint32_t> runs;
    std::vector<Item> grouped;
    std::vector<float> keys;
    const std::size_t dropped = keepNearestPerSample(items, 1, 2, runs, grouped, keys, [](std::span<Item> run) {
        return std::size_t(std::unique(run.begin(), run.end(), [](const Item& a, const Item& b) { return a.order == b.order; }) - run.begin());
    }, [](const Item& x) { return x.nearness; });
    ASSERT_EQ(items.size(), 2u);
    EXPECT_EQ(items[0].order, 1);
    EXPECT_EQ(items[1].order, 2);
    EXPECT_EQ(dropped, 1u);
}

TEST(TileBudget, ShareIsWhatTheBudgetLeavesOrTheFloor) {
    TileBudget fixed(1, 1000);
    fixed.measure();
    EXPECT_EQ(fixed.shareBytes(), 1000u);
    EXPECT_EQ(fixed.maxItems(100), 5u);  // an item counts twice: a vector may double
    EXPECT_EQ(fixed.maxItems(1000), 1u);  // never none

    // A budget below what is resident leaves the floor.
    TileBudget tight(1, 0);
    tight.measure();
    EXPECT_EQ(tight.shareBytes(), TileBudget::kMinShareBytes);
    // A large one leaves its rest above the resident memory, over the threads.
    TileBudget large(1 << 20, 0);
    large.measure();
    EXPECT_GT(large.shareBytes(), (std::uint64_t(1) << 40) / 1024);
    EXPECT_LE(large.shareBytes(), std::uint64_t(1) << 40);
}

}  // namespace
}  // namespace streak::exposure
