#pragma once

#include "raster/curved_triangle.h"
#include "raster/screen_triangle.h"
#include "scene/flat_geometry.h"
#include "scene/scene.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace streak::exposure {

// One triangle over one piece [t0, t1] of the shutter, its corners Bezier curves of order n in
// clip space (for the edge equations) and in world space (for shading), u in [0, 1] over the
// piece. boxes are its screen bounds over `intervals` equal sub-pieces (generalized INTERVAL,
// Gribel et al. 2013): each sub-piece's control points, found by subdivision, enclose it there.
struct CurvedSegment {
    std::uint32_t triangle = 0;
    float t0 = 0.0f, t1 = 0.0f;
    int order = 1;
    std::array<raster::CurvedTriangle::Corner, 3> clip{};
    std::array<std::array<glm::vec3, raster::CurvedTriangle::kMaxOrder + 1>, 3> world{}, normal{};
    float nearness = 0.0f;  ///< 1 / smallest control-point view depth; 0 if one is at or behind the eye

    double localTime(float t) const { return t1 > t0 ? (double(t) - t0) / (double(t1) - t0) : 0.0; }
    bool isInFront() const { return nearness > 0.0f; }
};

// CurvedGeometry is a scene's triangles as curved segments: the exact form of Bezier keys
// (a piece per Bezier piece, of its order <= 3) and of piecewise-linear keys (a piece per key
// segment, order 1) under a static camera, since projection is linear in homogeneous
// coordinates. Under a moving camera the clip-space path, object and camera motion together,
// is fitted per piece by the curve of order cameraOrder through cameraOrder + 1 evenly spaced
// times of it; so are keys whose segments or pieces do not all end on the pieces' ends (the
// pieces are the least common multiple of the meshes' counts, at most 64).
// Segments are triangle-major: piece s of triangle i is at i * numPieces + s.
class CurvedGeometry {
public:
    // Throws Error for Bezier keys of order above 3.
    CurvedGeometry(const Scene& scene, float aspect, int cameraOrder);

    const FlatGeometry& flat() const { return m_flat; }
    int numPieces() const { return m_numPieces; }
    int order() const { return m_order; }
    bool isFitted() const { return m_isFitted; }  ///< paths are fitted (a moving camera, capped pieces), not exact
    std::span<const CurvedSegment> segments() const { return m_segments; }
    const CurvedSegment& segmentAt(std::uint32_t triangle, float t) const;

    // The pixels each segment may cover, over each of `intervals` equal sub-pieces of it
    // (segment-major: intervals boxes per segment): a sub-piece whose control points are all in
    // front of the eye stays inside their projections' box (convex hull property); one reaching
    // behind the eye may cover anything.
    std::vector<raster::PixelBounds> screenBounds(const raster::Viewport& viewport, int intervals) const;

private:
    FlatGeometry m_flat;
    int m_numPieces = 1, m_order = 1;
    bool m_isFitted = false;
    LargeBuffer<CurvedSegment> m_segments;  ///< a dense frame's largest array: in huge pages (LargeVector)
};

}  // namespace streak::exposure
