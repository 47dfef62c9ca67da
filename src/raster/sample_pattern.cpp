#include "raster/sample_pattern.h"

#include "raster/edge_equation.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace streak::raster {

// The n x n samples, cell (i, j) at offset(i, j) in pixel fractions.
template <class Offset>
SamplePattern SamplePattern::build(int n, Offset offset) {
    assert(n >= 1);
    SamplePattern pattern;
    pattern.m_samplesPerAxis = n;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const glm::dvec2 p = offset(double(i), double(j));
            pattern.offsets.emplace_back(std::int64_t(std::floor(p.x * kSubpixelScale)), std::int64_t(std::floor(p.y * kSubpixelScale)));
        }
    return pattern;
}

SamplePattern SamplePattern::rooks(int n) {
    const double cells = double(n) * double(n);
    return build(n, [&](double i, double j) {
        const double a = double(((int(j) - int(i)) % n + n) % n);
        return glm::dvec2((i * n + a + 0.5) / cells, (j * n + a + 0.5) / cells);
    });
}

SamplePattern SamplePattern::grid(int n) {
    SamplePattern pattern = build(n, [&](double i, double j) { return glm::dvec2((i + 0.5) / n, (j + 0.5) / n); });
    pattern.m_isGrid = true;
    return pattern;
}

SamplePattern SamplePattern::rows(int r) {
    assert(r >= 1);
    SamplePattern pattern;
    pattern.m_samplesPerAxis = std::max(1, int(std::lround(std::sqrt(double(r)))));
    for (int k = 0; k < r; ++k)
        pattern.offsets.emplace_back(kSubpixelScale / 2, std::int64_t(std::floor((double(k) + 0.5) / double(r) * kSubpixelScale)));
    return pattern;
}

SamplePattern samplePatternFor(int n, bool isGrid) { return isGrid ? SamplePattern::grid(n) : SamplePattern::rooks(n); }

glm::dvec2 SamplePattern::rasterOf(int px, int py, int s) const {
    const glm::i64vec2 offset = offsets[std::size_t(s)];
    return {double(std::int64_t(px) * kSubpixelScale + offset.x) / kSubpixelScale, double(std::int64_t(py) * kSubpixelScale + offset.y) / kSubpixelScale};
}

glm::dvec2 SamplePattern::ndcOf(int px, int py, int s, int width, int height) const {
    const glm::dvec2 raster = rasterOf(px, py, s);
    return ndcFromRaster(raster.x, raster.y, width, height);
}

}  // namespace streak::raster
