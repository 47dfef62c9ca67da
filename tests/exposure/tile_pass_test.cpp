// The shared tile pass of the exact methods: a sample's records put back in their sources'
// order after a method found them in another.

#include "exposure/tile_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace streak::exposure {
namespace {

TEST(SortRunsBySource, EachSamplesRecordsTakeTheirSourcesOrderKeepingOneSourcesOwn) {
    // Records of 50 samples from 12 sources, several per source and sample (a segment can
    // cover a sample in more than one span, in time order), shuffled as a nearest-first visit
    // leaves them; the reference is the records stably sorted by sample, then source. Every
    // other round puts them on 3 samples from 60 sources: runs of a hundred or more, as a dense
    // mesh under fast motion leaves them, which take the other sort.
    std::mt19937 rng(7);
    for (int round = 0; round < 20; ++round) {
        SCOPED_TRACE(round);
        std::vector<TileRecord> records;
        const bool isDense = round % 2 == 1;
        const std::size_t numSamples = isDense ? 3 : 50;
        for (int i = 0; i < 400; ++i) {
            TileRecord r;
            r.sample = std::uint32_t(rng() % numSamples);
            r.interval.source = std::uint32_t(rng() % (isDense ? 60 : 12));
            r.interval.t0 = float(i);  // tells records apart: their order of finding
            records.push_back(r);
        }
        std::vector<TileRecord> expected = records;
        std::stable_sort(expected.begin(), expected.end(), [](const TileRecord& a, const TileRecord& b) {
            return a.sample != b.sample ? a.sample < b.sample : a.interval.source < b.interval.source;
        });
        std::vector<std::uint32_t> runs;
        std::vector<TileRecord> bySample;
        raster::groupBySample(std::span<const TileRecord>(records), numSamples, runs, bySample);
        sortRunsBySource(runs, bySample);
        ASSERT_EQ(bySample.size(), expected.size());
        for (std::size_t k = 0; k < expected.size(); ++k) {
            EXPECT_EQ(bySample[k].sample, expected[k].sample);
            EXPECT_EQ(bySample[k].interval.source, expected[k].interval.source);
            EXPECT_EQ(bySample[k].interval.t0, expected[k].interval.t0);
        }
    }
}

}  // namespace
}  // namespace streak::exposure
