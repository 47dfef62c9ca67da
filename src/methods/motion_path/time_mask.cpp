#include "methods/motion_path/time_mask.h"

#include <algorithm>
#include <cmath>

namespace streak::motion_path {

TimeMask TimeMask::span(float t0, float t1, int numBits) {
    TimeMask mask;
    // Slice i is in when t0 <= (i + 1/2)/n < t1, i.e. i in [ceil(t0 n - 1/2), ceil(t1 n - 1/2)).
    const int first = std::max(0, int(std::ceil(double(t0) * numBits - 0.5)));
    const int end = std::min(numBits, int(std::ceil(double(t1) * numBits - 0.5)));
    for (int word = 0; word < 4; ++word) {
        const int lo = std::max(first, word * 64), hi = std::min(end, word * 64 + 64);
        if (lo >= hi) continue;
        const int width = hi - lo;
        const std::uint64_t bits = width == 64 ? ~std::uint64_t(0) : ((std::uint64_t(1) << width) - 1);
        mask.m_words[word] = bits << (lo - word * 64);
    }
    return mask;
}

}  // namespace streak::motion_path
