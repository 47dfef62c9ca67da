#include "raster/sample_pattern.h"

#include <cassert>
#include <cmath>

namespace streak::raster {

SamplePattern SamplePattern::stratified(int n) {
    assert(n >= 1);
    SamplePattern pattern;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            pattern.offsets.emplace_back(std::int64_t(std::floor((i + 0.5) / n * kSubpixelScale)),
                                         std::int64_t(std::floor((j + 0.5) / n * kSubpixelScale)));
    return pattern;
}

}  // namespace streak::raster
