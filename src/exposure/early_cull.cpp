#include "exposure/early_cull.h"

#include "raster/screen_triangle.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <limits>

namespace streak::exposure {

namespace {

// Distance from the origin to the segment [a, b].
double distanceToSegment(const glm::dvec2& a, const glm::dvec2& b) {
    const glm::dvec2 ab = b - a;
    const double length2 = glm::dot(ab, ab);
    const double f = length2 > 0.0 ? std::clamp(-glm::dot(a, ab) / length2, 0.0, 1.0) : 0.0;
    return glm::length(a + f * ab);
}

double cross(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// Distance from the origin to the triangle (a, b, c): 0 inside it or on it; where it is flat
// (a translation's displacements are one point), to its edges.
double distanceToTriangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    const double area = cross(b - a, c - a), ab = cross(a, b), bc = cross(b, c), ca = cross(c, a);
    if (area > 0.0 && ab >= 0.0 && bc >= 0.0 && ca >= 0.0) return 0.0;
    if (area < 0.0 && ab <= 0.0 && bc <= 0.0 && ca <= 0.0) return 0.0;
    return std::min({distanceToSegment(a, b), distanceToSegment(b, c), distanceToSegment(c, a)});
}

}  // namespace

bool EarlyCull::mayCoverAStretch(const TriangleSegment& segment, const raster::Viewport& viewport) {
    if (segment.isStill || !segment.isInFront()) return true;
    std::array<glm::dvec2, 3> p0, p1, travel;
    double size = 0.0;
    for (int i = 0; i < 3; ++i)
        p0[i] = raster::rasterFromClip(segment.clip0[i], viewport), p1[i] = raster::rasterFromClip(segment.clip1[i], viewport), travel[i] = p1[i] - p0[i];
    for (int i = 0; i < 3; ++i) size = std::max({size, glm::length(p0[(i + 1) % 3] - p0[i]), glm::length(p1[(i + 1) % 3] - p1[i])});
    // Each point of the surface moves by a mix of its corners' displacements, so by at least
    // their triangle's distance from no motion.
    const double least = distanceToTriangle(travel[0], travel[1], travel[2]);
    const double share = double(segment.t1) - double(segment.t0);
    return !(least * double(kShortestStretch) > size * share);
}

LargeBuffer<float> EarlyCull::occluderDepths(const SegmentedGeometry& geometry, const raster::Viewport& viewport) {
    const std::span<const TriangleSegment> segments = geometry.segments();
    const Scene& scene = geometry.scene();
    LargeBuffer<float> depths(segments.size());
    tbb::parallel_for(std::size_t(0), segments.size(), [&](std::size_t i) {
        const TriangleSegment& s = segments[i];
        float farthest = std::numeric_limits<float>::infinity();
        if (s.isInFront() && !scene.materials[geometry.flat().triangles()[s.triangle].material].isTranslucent() && mayCoverAStretch(s, viewport)) {
            farthest = 0.0f;
            for (const auto* corners : {&s.clip0, &s.clip1})
                for (const glm::vec4& c : *corners) farthest = std::max(farthest, c.w);
        }
        constructAt(depths, i) = farthest;
    });
    return depths;
}

bool EarlyCull::mayHideAny(std::span<const std::uint32_t> items, std::span<const TriangleSegment> segments, std::span<const float> occluderDepths) {
    float hidesFrom = std::numeric_limits<float>::infinity();
    for (const std::uint32_t i : items) hidesFrom = std::min(hidesFrom, occluderDepths[i]);
    if (hidesFrom == std::numeric_limits<float>::infinity()) return false;
    for (const std::uint32_t i : items)
        if (nearestOf(segments[i].nearness) > hidesFrom) return true;
    return false;
}

}  // namespace streak::exposure
