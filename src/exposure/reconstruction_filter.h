#pragma once

#include "image/image.h"
#include "util/options.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace streak::exposure {

// The games' motion-blur filter, shared by post-filter and post-filter-gl. What it reads: one render at shutter centre with, per pixel, its
// colour, view depth and screen-space velocity (pixels; half the displacement over the
// shutter, McGuire et al.'s V, so a point sweeps X - V to X + V).
struct VelocityFrame {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> color;
    std::vector<float> coverage;     ///< alpha, filtered as the colour is
    std::vector<float> depth;        ///< view depth; infinity where the background shows
    std::vector<glm::vec2> velocity;

    std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(width) + std::size_t(x); }
};

// The reconstruction filter of McGuire, Hennessy, Bukowski & Osman 2012 ("A reconstruction
// filter for plausible motion blur"), with the jitter and centre weighting of Guertin, McGuire
// & Nowrouzezahrai 2014 ("A fast and stable feature-aware motion blur filter"): the largest
// velocity per k x k tile (TileMax), its 3x3 neighbourhood's largest (NeighborMax), then a
// gather of `samples` taps along the neighbourhood's velocity, each weighted by whether the
// tap's surface is in front and spreads over the pixel, or the pixel's own surface spreads
// over the tap (cone and cylinder weights, soft depth comparison).
struct ReconstructionOptions {
    int tile = 20;             ///< k: tile side in pixels, the largest blur radius the tiles see
    int samples = 15;          ///< gather taps per pixel (odd: the centre is its own)
    float maxRadius = 20.0f;   ///< velocities are clamped to this many pixels (<= tile)
    float softDepth = 0.01f;   ///< soft depth comparison extent, as a share of the depth
    std::uint64_t seed = 0;    ///< of the per-pixel jitter
    float velocityScale = 1.0f;  ///< the shutter's share each row sees: a rolling shutter's D (not an option)

    // The post-filter methods' options: tile, samples, max-radius (default: tile), soft-depth.
    static ReconstructionOptions read(OptionMap& options);
};

// The per-pixel offset of the gather taps along the line, in [-1/2, 1/2) tap spacings: one
// definition, so the CPU and GL filters agree.
float gatherJitter(std::uint64_t seed, std::size_t pixel);

// Velocities scaled by velocityScale, clamped to maxRadius and zeroed below half a pixel, as
// the filter uses them.
void clampVelocities(VelocityFrame& frame, const ReconstructionOptions& options);

// TileMax and NeighborMax: per tile, the velocity of largest magnitude.
std::vector<glm::vec2> tileMax(const VelocityFrame& frame, int tile);
std::vector<glm::vec2> neighborMax(const std::vector<glm::vec2>& tiles, int tilesWide, int tilesHigh);

// The filtered image, its alpha the filtered coverage.
Image reconstruct(const VelocityFrame& frame, const ReconstructionOptions& options);

}  // namespace streak::exposure
