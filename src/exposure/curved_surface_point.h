#pragma once

#include "exposure/curved_geometry.h"
#include "exposure/shading_site.h"
#include "exposure/triangle_cache.h"
#include "raster/curved_triangle.h"
#include "raster/screen_triangle.h"
#include "exposure/span_shading.h"

#include <glm/vec2.hpp>

#include <cstdint>

namespace streak::exposure {

using CurvedTriangleCache = TriangleCache<raster::CurvedTriangle>;

// Each curved segment's edge equations, from the cache.
const raster::CurvedTriangle& curvedTriangleOf(const CurvedGeometry& geometry, std::uint32_t segment, CurvedTriangleCache& cache);

// A triangle on curved paths under one pixel sample at any time of the shutter, for span
// shading along the curved uv path: exact barycentrics from the curved edge equations of the
// piece holding that time, world position and normal from the world-space control points.
class CurvedSurfacePoint final : public MovingSurfacePoint {
public:
    // The point under site.ndc, its texture footprint site.footprintPixels.
    CurvedSurfacePoint(const CurvedGeometry& geometry, const raster::Viewport& viewport, const ShadingSite& site, std::uint32_t triangle,
                       CurvedTriangleCache& cache);

    bool at(float t, bool withFootprint, SurfacePoint& out) const override;
    // uv as a ratio of Bernstein polynomials: sum(uv_i E_opposite(u)) / sum(E(u)).
    bool uvAt(float t, glm::vec2& uv) const override;
    const std::array<glm::vec2, 3>* uvTriangle() const override { return m_clamp ? &m_uv : nullptr; }
    bool hasBoxFootprint() const override { return m_isBox; }
    glm::ivec2 boxTaps() const override { return m_boxTaps; }
    int boxBudget() const override { return m_boxBudget; }
    int materialIndex() const override;

private:
    const CurvedSegment& select(float t) const;

    const CurvedGeometry& m_geometry;
    glm::dvec2 m_step;  ///< the footprint in NDC
    bool m_clamp;       ///< barycentrics held to the triangle
    bool m_isBox;       ///< a shared shading's box footprint (ShadingSite::boxFootprint): its taps clipped, its uv not held
    glm::ivec2 m_boxTaps;  ///< ShadingSite::boxTaps
    int m_boxBudget;       ///< ShadingSite::boxBudget
    std::uint32_t m_triangle;
    glm::dvec2 m_ndc;
    std::array<glm::vec2, 3> m_uv;
    CurvedTriangleCache& m_cache;
    mutable const CurvedSegment* m_segment = nullptr;  ///< the piece the members below belong to
    mutable const raster::CurvedTriangle* m_curved = nullptr;
    mutable raster::Bernstein m_uNumerator, m_vNumerator, m_denominator;
    mutable std::array<raster::Bernstein, 3> m_weights;  ///< corner i's unnormalised barycentric
};

// The mean shaded colour and opacity of a curved triangle over [t0, t1] at a site.
ShadedColor shadeCurvedSpan(const CurvedGeometry& geometry, const raster::Viewport& viewport, ShadingMode mode, const SpanShadingSettings& settings,
                            std::uint32_t triangle, float t0, float t1, const ShadingSite& site, CurvedTriangleCache& cache);

}  // namespace streak::exposure
