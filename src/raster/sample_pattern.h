#pragma once

#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace streak::raster {

// Fixed-point raster coordinates: 1/256 pixel, like GPU rasterizers, so that edge functions are
// exact integers and the fill rule is watertight.
constexpr int kSubpixelBits = 8;
constexpr std::int64_t kSubpixelScale = 1 << kSubpixelBits;

// SamplePattern is the set of sample positions inside every pixel, in fixed-point offsets from
// the pixel's top-left corner, for the box-filtered anti-aliasing of `--aa n` (n x n samples).
// rooks(n), the default, puts the sample of stratum (i, j) of the n x n strata at
// x = (i n + a + 1/2) / n^2, y = (j n + a + 1/2) / n^2 with a = (j - i) mod n: each stratum
// holds one sample, and every sample has its own column and row (n-rooks), so an axis-aligned
// edge is resolved to 1/n^2 of a pixel instead of 1/n. Of the n-rooks sets it is the rank-1
// lattice of generator (1, n + 1) / n^2, whose points lie far apart (0.88 / n at n = 8, where
// the sheared grid x = (i n + j + 1/2) / n^2 has 0.18 / n), so an edge at any angle is
// resolved about as well as by the grid. grid(n) is the n x n grid of cell centres. n = 1 is
// the pixel centre in both.
struct SamplePattern {
    std::vector<glm::i64vec2> offsets;  ///< each in [0, kSubpixelScale)

    static SamplePattern rooks(int n);
    static SamplePattern grid(int n);
    // r samples down the pixel's middle column, sample k at y = (k + 1/2) / r: the rows of line
    // samples (exposure/line_samples.h), whose x is the whole pixel. rows(n * n) has the rows of
    // rooks(n), in order from the top; its footprint is rooks(n)'s, a pixel over round(sqrt(r)).
    static SamplePattern rows(int r);
    int count() const { return int(offsets.size()); }
    int samplesPerAxis() const { return m_samplesPerAxis; }
    bool isGrid() const { return m_isGrid; }  ///< grid(n) (n-rooks or rows otherwise)
    // The spacing of the samples along each axis in fixed-point units (a pixel over n): the
    // texture footprint of one sample, since the box filter integrates the samples.
    std::int64_t footprintStep() const { return std::max<std::int64_t>(1, std::llround(double(kSubpixelScale) / double(m_samplesPerAxis))); }
    // The raster position (pixels, y down) of sample s of pixel (px, py).
    glm::dvec2 rasterOf(int px, int py, int s) const;
    // The NDC position of sample s of pixel (px, py) in a width x height image.
    glm::dvec2 ndcOf(int px, int py, int s, int width, int height) const;

private:
    template <class Offset>
    static SamplePattern build(int n, Offset offset);

    int m_samplesPerAxis = 1;
    bool m_isGrid = false;
};

// The positions of --aa n: rooks(n), or grid(n) when isGrid.
SamplePattern samplePatternFor(int n, bool isGrid);

}  // namespace streak::raster
