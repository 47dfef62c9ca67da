#pragma once

#include "scene/barycentric.h"
#include "scene/texture.h"

#include <glm/vec2.hpp>
#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <span>

namespace streak::exposure {

// One sample of a shared shading whose texture is looked up at each of its samples
// (ShadingSite::samples): where it lies and how much of its exposure it gives the shading.
struct SiteSample {
    glm::dvec2 ndc{0.0};
    float weight = 0.0f;
};

// Where a span is shaded, for the surface points of span shading (TriangleSurfacePoint,
// CurvedSurfacePoint): the point under it, the texture footprint around it, and whether the
// point is held to its triangle.
struct ShadingSite {
    glm::dvec2 ndc{0.0};
    // The footprint's extent in pixels along x and y: one sample spacing (1/N at --aa N) when a
    // sample shades alone, up to one pixel when a pixel's samples share the shading.
    glm::dvec2 footprintPixels{1.0};
    // A shared shading's point lies anywhere among its samples, and at some of the span's times
    // outside the triangle that they see: held to the triangle (barycentrics clamped), it
    // shades the nearest part of that triangle, never the texels of its neighbours in a texture
    // atlas that extrapolated barycentrics would reach.
    bool clampToTriangle = false;
    // The footprint is a region of the screen whose samples share the shading, so its texels are
    // averaged alike (a box, MovingSurfacePoint::hasBoxFootprint), not a sample's bell.
    bool boxFootprint = false;
    // The fewest taps a box takes a side (Texture::boxGrid): as many as the samples sharing it
    // span (boxTapsOf), so that a box over a magnified texture, less than a texel wide, still
    // integrates the bilinear surface across it as its samples' own lookups did, and is no
    // coarser a filter than they were. One where the box stands for no samples.
    glm::ivec2 boxTaps{1};
    // The most taps a box takes over its span, all its times together, a quarter of them at one
    // time (Texture::boxGrid's budget): Texture::kMaxSweptBoxTaps, but where a pixel of 2 x 2
    // samples shares one box (boxBudgetOf).
    int boxBudget = Texture::kMaxSweptBoxTaps;
    // A still textured triangle's shading shared by the samples of a pixel that see it
    // (PixelShading, Sharing::StillTextured): the point at `ndc` (one of them) gives the texture
    // footprint of one sample spacing, found once, and the surface is shaded (looked up and lit)
    // at each sample's own point with it, the shadings weighted by the samples' exposures.
    // Nothing still moves between the samples' times, so this is per-sample shading but for the
    // footprint's change across the pixel. Empty everywhere else.
    std::span<const SiteSample> samples{};
};

// A box's fewest taps a side (ShadingSite::boxTaps) over footprintPixels at --aa samplesPerAxis:
// the samples it spans a side, 1 to kMaxBoxTapsASide (Texture::kMaxBoxTaps = 64, 8 x 8). (floor of
// x + 1/2, not round: the GL twin's GLSL round() may break ties either way.)
inline constexpr int kMaxBoxTapsASide = 8;
inline glm::ivec2 boxTapsOf(const glm::dvec2& footprintPixels, int samplesPerAxis) {
    const glm::dvec2 samples = glm::floor(footprintPixels * double(samplesPerAxis) + 0.5);
    return glm::clamp(glm::ivec2(samples), glm::ivec2(1), glm::ivec2(kMaxBoxTapsASide));
}

// A box's budget of taps (ShadingSite::boxBudget) where a pixel of samplesPerAxis x
// samplesPerAxis samples is shaded in cellsPerAxis x cellsPerAxis cells: a pixel of 2 x 2
// samples that shares one box takes a quarter of the budget (16 taps at a time, 64 in all), about
// what its four samples' own lookups took. With the whole budget one box a pixel was 0.8x as fast
// as the four lookups on minified textures (builtin:cubes at 1024x768); with a quarter it is
// 1.4-1.5x as fast as them there, and closer to Cycles on the textured models (cubes +0.9 dB,
// Fox +1.1, AnimatedCube +0.5, CesiumMan +0.2; docs/BENCHMARKS.md, "One cell at --aa 2"). More
// samples keep the whole budget: a box over 3 x 3 samples with less (36 at a time, 144 in all)
// lost CesiumMan and Fox 0.4-0.6 dB.
inline constexpr int kPixelOfFourBoxTaps = Texture::kMaxSweptBoxTaps / 4;
inline int boxBudgetOf(int samplesPerAxis, int cellsPerAxis) {
    return cellsPerAxis == 1 && samplesPerAxis == 2 ? kPixelOfFourBoxTaps : Texture::kMaxSweptBoxTaps;
}

// Where one sample shades alone, at --aa samplesPerAxis: its own point and sample spacing.
inline ShadingSite sampleSite(const glm::dvec2& ndc, int samplesPerAxis) { return {ndc, glm::dvec2(1.0 / samplesPerAxis), false, false, glm::ivec2(1)}; }

// The uv at barycentrics b held to the triangle, into `uv`, when b lies outside it; false (uv
// untouched) when b is inside and the caller's own exact uv stands.
inline bool heldUvOutside(const glm::dvec3& b, const std::array<glm::vec2, 3>& corners, glm::vec2& uv) {
    if (b.x >= 0.0 && b.y >= 0.0 && b.z >= 0.0) return false;
    const glm::dvec3 held = clampedBarycentrics(b);
    uv = glm::vec2(held.x * glm::dvec2(corners[0]) + held.y * glm::dvec2(corners[1]) + held.z * glm::dvec2(corners[2]));
    return true;
}

}  // namespace streak::exposure
