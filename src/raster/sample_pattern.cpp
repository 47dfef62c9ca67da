#include "raster/sample_pattern.h"

#include "raster/edge_equation.h"

#include <cassert>
#include <cmath>

namespace streak::raster {

SamplePattern SamplePattern::rooks(int n) {
    assert(n >= 1);
    SamplePattern pattern;
    pattern.m_samplesPerAxis = n;
    const double cells = double(n) * double(n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            pattern.offsets.emplace_back(std::int64_t(std::floor((double(i) * n + j + 0.5) / cells * kSubpixelScale)),
                                         std::int64_t(std::floor((double(j) * n + i + 0.5) / cells * kSubpixelScale)));
    return pattern;
}

SamplePattern SamplePattern::grid(int n) {
    assert(n >= 1);
    SamplePattern pattern;
    pattern.m_samplesPerAxis = n;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            pattern.offsets.emplace_back(std::int64_t(std::floor((i + 0.5) / n * kSubpixelScale)),
                                         std::int64_t(std::floor((j + 0.5) / n * kSubpixelScale)));
    return pattern;
}

SamplePattern samplePatternFor(int n, bool isGrid) { return isGrid ? SamplePattern::grid(n) : SamplePattern::rooks(n); }

glm::dvec2 SamplePattern::ndcOf(int px, int py, int s, int width, int height) const {
    const glm::i64vec2 offset = offsets[std::size_t(s)];
    return ndcFromRaster(double(std::int64_t(px) * kSubpixelScale + offset.x) / kSubpixelScale,
                         double(std::int64_t(py) * kSubpixelScale + offset.y) / kSubpixelScale, width, height);
}

}  // namespace streak::raster
