#pragma once

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace streak::raster {

// Fixed-point raster coordinates: 1/256 pixel, like GPU rasterizers, so that edge functions are
// exact integers and the fill rule is watertight.
constexpr int kSubpixelBits = 8;
constexpr std::int64_t kSubpixelScale = 1 << kSubpixelBits;

// SamplePattern is the set of sample positions inside every pixel, in fixed-point offsets from
// the pixel's top-left corner. stratified(n) is an n x n grid of cell centres (n = 1: the pixel
// centre), the box-filtered anti-aliasing of `--aa n`.
struct SamplePattern {
    std::vector<glm::i64vec2> offsets;  ///< each in [0, kSubpixelScale)

    static SamplePattern stratified(int n);
    int count() const { return int(offsets.size()); }
    // The NDC position of sample s of pixel (px, py) in a width x height image.
    glm::dvec2 ndcOf(int px, int py, int s, int width, int height) const;
};

}  // namespace streak::raster
