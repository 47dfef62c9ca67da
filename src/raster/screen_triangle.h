#pragma once

#include "raster/sample_pattern.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>

namespace streak::raster {

// The image a rasterizer writes: pixel (x, y) covers [x, x+1) x [y, y+1), y down.
struct Viewport {
    int width = 0;
    int height = 0;
};

// Inclusive pixel bounds; empty when x0 > x1 or y0 > y1.
struct PixelBounds {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
    bool empty() const { return x0 > x1 || y0 > y1; }
};

// The pixels holding raster points in [lo, hi] (raster coordinates: pixels, y down), clipped to
// the viewport (a pixel's samples lie in [x, x + 1)).
PixelBounds pixelBoundsOfRaster(const glm::dvec2& lo, const glm::dvec2& hi, const Viewport& viewport);

using EdgeValues = std::array<std::int64_t, 3>;

// Perspective-correct barycentrics of a sample and its 1/w (larger is nearer).
struct PerspectiveSample {
    glm::vec3 bary{0.0f};
    float invW = 0.0f;
};

// ScreenTriangle is a triangle set up for rasterization: snapped to the fixed-point grid, with
// integer edge functions oriented positive inside. Edge i is opposite vertex i, so E_i / sum(E)
// is the screen-space barycentric of vertex i. The top-left fill rule (D3D/GL) is folded into a
// bias so that triangles sharing an edge cover each sample on it exactly once.
struct ScreenTriangle {
    std::array<std::int64_t, 3> a{}, b{}, c{};  ///< E_i(X, Y) = a_i X + b_i Y + c_i, X, Y fixed-point
    std::array<std::int64_t, 3> bias{};         ///< 0 on top-left edges, -1 elsewhere
    std::array<float, 3> invW{};                ///< 1 / clip w of each vertex
    double invEdgeSum = 0.0;                    ///< 1 / (E_0 + E_1 + E_2), constant over the plane
    PixelBounds bounds;                         ///< pixels that may hold a covered sample, clipped to the viewport
    bool isFrontFacing = true;                  ///< counter-clockwise in normalized device coordinates

    EdgeValues edgesAt(std::int64_t X, std::int64_t Y) const {
        return {a[0] * X + b[0] * Y + c[0], a[1] * X + b[1] * Y + c[1], a[2] * X + b[2] * Y + c[2]};
    }
    bool isInside(const EdgeValues& e) const {
        return (e[0] + bias[0]) >= 0 && (e[1] + bias[1]) >= 0 && (e[2] + bias[2]) >= 0;
    }
    bool covers(std::int64_t X, std::int64_t Y) const { return isInside(edgesAt(X, Y)); }

    // Barycentrics at a point given its edge values (any point of the plane, inside or not).
    // invW <= 0 means the point lies beyond the triangle's horizon.
    PerspectiveSample interpolate(const EdgeValues& e) const;
    // The same `step` fixed-point units to the right and down: texture footprints.
    PerspectiveSample interpolateRight(const EdgeValues& e, std::int64_t step) const {
        return interpolate({e[0] + a[0] * step, e[1] + a[1] * step, e[2] + a[2] * step});
    }
    PerspectiveSample interpolateDown(const EdgeValues& e, std::int64_t step) const {
        return interpolate({e[0] + b[0] * step, e[1] + b[1] * step, e[2] + b[2] * step});
    }
};

// Widens a set-up triangle into a conservative cover: every sample within 1/256 pixel of the
// triangle's unsnapped edges is covered, boundaries included (no fill rule). For regions that
// must contain every sample an exact test may find inside (motion paths): with the fill rule, a
// sample on an edge two path faces share, or between a snapped and an exact edge, belongs to
// neither.
void makeConservative(ScreenTriangle& tri, const Viewport& viewport);

// A triangle thinner than the fixed-point grid snaps to no area, so setupScreenTriangle sets up
// nothing and there is no cover to widen, though the exact triangle may hold samples no other
// triangle does. Its conservative cover is then the samples within two grid units of the
// unsnapped triangle (twice the snapping's reach, as makeConservative widens one).
class SnappedAwayTriangle {
public:
    // False where the corners snap to an area (the triangle was set aside for another reason,
    // as lying off the screen) or are not finite.
    bool setup(const std::array<glm::vec4, 3>& clip, const Viewport& viewport);
    // The pixels the cover may reach.
    const PixelBounds& bounds() const { return m_bounds; }
    bool covers(const glm::dvec2& raster) const;

private:
    static constexpr double kReach = 2.0 / double(kSubpixelScale);  ///< pixels
    std::array<glm::dvec2, 3> m_corners{};  ///< raster, unsnapped
    double m_area = 0.0;                    ///< twice the signed area; 0 where the corners are in line
    PixelBounds m_bounds;
};

// Raster position of a clip-space point (x right, y down, in pixels). Precondition: w > 0.
glm::dvec2 rasterFromClip(const glm::vec4& clip, const Viewport& viewport);

// Sets up the triangle with the given clip-space corners, all of which must have w > 0 and lie
// within the guard band (see clip.h). Returns false for a triangle of zero area after snapping.
bool setupScreenTriangle(const std::array<glm::vec4, 3>& clip, const Viewport& viewport, ScreenTriangle& out);

}  // namespace streak::raster
