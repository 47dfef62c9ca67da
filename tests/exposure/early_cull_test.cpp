#include "exposure/early_cull.h"

#include "util/random.h"

#include <gtest/gtest.h>

#include <algorithm>
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

}  // namespace streak::exposure
