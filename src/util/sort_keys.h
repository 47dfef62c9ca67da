#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace streak {

// A float's bits made to order as the numbers do (negatives below positives, -0 just below +0,
// NaNs past the infinities), so a sort by value can compare integers.
inline std::uint32_t orderedBits(float value) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
    return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

// A key that sorts by value, then by index: the index of an item in a list sorted by one of its
// floats, sorted as plain integers (an indirect comparison reads the item at every step; a
// resolve sorts a dense sample's hundreds of intervals several times).
inline std::uint64_t sortKey(float value, std::uint32_t index) { return std::uint64_t(orderedBits(value)) << 32 | index; }

// The index a sortKey holds.
inline std::uint32_t indexOf(std::uint64_t key) { return std::uint32_t(key); }

// Sorts `keys` (sortKeys) and writes their indices, in order, to `order`.
template <class Index>
void sortedIndices(std::vector<std::uint64_t>& keys, std::vector<Index>& order) {
    std::sort(keys.begin(), keys.end());
    order.resize(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) order[i] = Index(indexOf(keys[i]));
}

}  // namespace streak
