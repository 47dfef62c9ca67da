#pragma once

#include "raster/screen_triangle.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>

namespace streak::raster {

// Clip-space x and y are clipped to |x|, |y| <= kGuardBand * w, so snapped raster coordinates
// stay within about 8.5 image sizes of the origin and 64-bit edge functions cannot overflow
// for images up to kMaxImageSize. Almost every triangle lies inside and is never clipped there.
constexpr float kGuardBand = 16.0f;
constexpr int kMaxImageSize = 16384;

// A vertex of a clipped polygon: its clip position and its barycentrics in the source triangle,
// through which every attribute of the source triangle is interpolated.
struct ClipVertex {
    glm::vec4 clip{0.0f};
    glm::vec3 sourceBary{0.0f};
};

// A triangle clipped by the near plane and four guard-band planes: at most 3 + 5 vertices.
struct ClippedPolygon {
    std::array<ClipVertex, 8> vertices{};
    int count = 0;
};

// True when some corner lies outside the near plane (w < zNear) or the guard band.
bool needsClipping(const std::array<glm::vec4, 3>& clip, float zNear);

// Sutherland-Hodgman against w >= zNear and the guard band; empty when nothing remains.
ClippedPolygon clipTriangle(const std::array<glm::vec4, 3>& clip, float zNear);

enum class CullMode : std::uint8_t { None, Back };

// Source-triangle barycentrics at a sample and one sample spacing right and down of it: the
// texture footprint. Past the triangle's horizon a neighbour has no barycentrics; it then takes the
// sample's own (a zero footprint).
struct SourceFootprint {
    glm::vec3 bary{0.0f};
    glm::vec3 right{0.0f};
    glm::vec3 down{0.0f};
};

// RasterTriangle is a screen triangle made from (part of) a source triangle.
struct RasterTriangle {
    ScreenTriangle screen;
    glm::mat3 sourceFromLocal{1.0f};  ///< columns: source barycentrics of the three corners
    bool isClipped = false;           ///< false: local barycentrics are the source's
    std::uint32_t source = 0;         ///< the caller's index of the source triangle

    glm::vec3 sourceBary(const glm::vec3& localBary) const { return isClipped ? sourceFromLocal * localBary : localBary; }
    // step: the sample spacing in fixed-point units (SamplePattern::footprintStep).
    SourceFootprint sourceFootprint(const EdgeValues& e, std::int64_t step) const {
        SourceFootprint f;
        f.bary = sourceBary(screen.interpolate(e).bary);
        const PerspectiveSample right = screen.interpolateRight(e, step), down = screen.interpolateDown(e, step);
        f.right = right.invW > 0.0f ? sourceBary(right.bary) : f.bary;
        f.down = down.invW > 0.0f ? sourceBary(down.bary) : f.bary;
        return f;
    }
};

// The screen triangles of one source triangle: one, or a fan of up to six after clipping.
struct TriangleSetup {
    std::array<RasterTriangle, 6> triangles;
    int count = 0;
};

// Clips (when needed), projects, snaps and culls one triangle given by its clip-space corners.
// Back faces are culled by their screen orientation when cull is Back; triangles of zero screen
// area and triangles wholly behind the near plane give nothing.
void setupTriangle(const std::array<glm::vec4, 3>& clip, std::uint32_t source, float zNear,
                   const Viewport& viewport, CullMode cull, TriangleSetup& out);

}  // namespace streak::raster
