#pragma once

#include "gpu/gl_object.h"
#include "image/image.h"

namespace streak::gpu {

// GL methods render one texel per pixel sample: an image of (width N) x (height N) texels for
// --aa N, rows top first as in raster space (the vertex shaders flip y, so GL's row 0 is the
// top row). Texel (N px + i, N py + j) is sample (i, j) of pixel (px, py), the CPU methods'
// stratified sample j N + i.
struct SampleGrid {
    int width = 0, height = 0, aa = 1;
    int samplesWide() const { return width * aa; }
    int samplesHigh() const { return height * aa; }
    std::size_t numSamples() const { return std::size_t(samplesWide()) * std::size_t(samplesHigh()); }
};

// Reads an RGBA32F sample texture back and box-filters each pixel's N x N samples, scaled by
// `scale` (1/S for a sum over S passes): rgb the colour, alpha each sample's coverage.
Image readSampleGrid(const GlTexture& samples, const SampleGrid& grid, float scale = 1.0f);

}  // namespace streak::gpu
