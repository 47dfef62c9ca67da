#pragma once

#include "exposure/segmented_geometry.h"
#include "exposure/shading_site.h"
#include "exposure/triangle_cache.h"
#include "raster/moving_triangle.h"
#include "raster/screen_triangle.h"
#include "exposure/span_shading.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace streak::exposure {

// Each segment's MovingTriangle (TriangleCache).
class MovingTriangleCache {
public:
    const raster::MovingTriangle& get(const SegmentedGeometry& geometry, std::uint32_t segment) {
        return m_cache.get(geometry.segments().size(), segment, [&] {
            const TriangleSegment& s = geometry.segments()[segment];
            return raster::MovingTriangle(s.clip0, s.clip1);
        });
    }
    // The segment's key poses (SegmentedGeometry::cornersOf), kept for the next call: a pixel's
    // samples shade the same triangle one after another (PixelShading sorts by triangle).
    const SegmentedGeometry::WorldCorners& cornersOf(const SegmentedGeometry& geometry, std::uint32_t segment) {
        if (segment != m_cornersSegment || &geometry != m_cornersGeometry)
            m_corners = geometry.cornersOf(geometry.segments()[segment]), m_cornersSegment = segment, m_cornersGeometry = &geometry;
        return m_corners;
    }
    void clear() { m_cache.clear(), m_cornersGeometry = nullptr; }

private:
    TriangleCache<raster::MovingTriangle> m_cache;
    const SegmentedGeometry* m_cornersGeometry = nullptr;
    std::uint32_t m_cornersSegment = 0;
    SegmentedGeometry::WorldCorners m_corners;
};

// A triangle under one pixel sample at any time of the shutter, for span shading: exact
// barycentrics from the moving edge equations of the segment holding that time, world position
// and normal from the key poses, and the uv a texture tap needs as a ratio of quadratics. The
// segment last used is kept, since taps come in time order.
class TriangleSurfacePoint final : public MovingSurfacePoint {
public:
    // The point under site.ndc, its texture footprint site.footprintPixels.
    TriangleSurfacePoint(const SegmentedGeometry& geometry, const raster::Viewport& viewport, const ShadingSite& site, std::uint32_t triangle,
                         MovingTriangleCache& cache);

    bool at(float t, bool withFootprint, SurfacePoint& out) const override;
    bool uvAt(float t, glm::vec2& uv) const override;
    bool vertexColorAt(float t, glm::vec4& color) const override;
    const std::array<glm::vec2, 3>* uvTriangle() const override { return m_clamp ? &cornerUvs() : nullptr; }
    bool hasBoxFootprint() const override { return m_isBox; }
    glm::ivec2 boxTaps() const override { return m_boxTaps; }
    int boxBudget() const override { return m_boxBudget; }
    int materialIndex() const override;
    // Still: one segment holds [t0, t1], its corners and normals do not move, nor does the camera.
    bool isStill(float t0, float t1) const override;
    std::span<const SiteSample> sharedSamples() const override { return m_samples; }
    // (As a sample shading alone finds its point: its own barycentrics, not held to the triangle.)
    bool atSample(const glm::dvec2& ndc, const SurfacePoint& middle, SurfacePoint& out) const override;

private:
    const TriangleSegment& select(float t) const;
    void makeUvRatio() const;
    // The sample at local time u of the selected segment, without neighbours, its barycentrics
    // held to the triangle where the site asks; false where it cannot be evaluated.
    bool plainSample(double u, raster::HomogeneousSample& s) const;
    // The surface point of `segment` (the selected one) at local time u whose barycentrics are
    // s's, right's and down's those of its footprint's neighbours.
    SurfacePoint pointOf(const TriangleSegment& segment, double u, const raster::HomogeneousSample& s, const glm::dvec3& right,
                         const glm::dvec3& down) const;

    const SegmentedGeometry& m_geometry;
    glm::dvec2 m_step;  ///< the footprint in NDC
    bool m_clamp;       ///< barycentrics held to the triangle
    bool m_isBox;       ///< a shared shading's box footprint (ShadingSite::boxFootprint): its taps clipped, its uv not held
    glm::ivec2 m_boxTaps;  ///< ShadingSite::boxTaps
    int m_boxBudget;       ///< ShadingSite::boxBudget
    std::uint32_t m_triangle;
    glm::dvec2 m_ndc;
    std::span<const SiteSample> m_samples;  ///< ShadingSite::samples
    // The triangle's corner uvs, read on first use (a still point's shading never asks).
    const std::array<glm::vec2, 3>& cornerUvs() const;
    mutable bool m_hasUv = false;
    mutable std::array<glm::vec2, 3> m_uv;
    mutable const TriangleSegment* m_segment = nullptr;  ///< the segment the members below belong to
    MovingTriangleCache& m_cache;
    mutable const raster::MovingTriangle* m_moving = nullptr;
    // The uv's ratio of quadratics, made for the segment on the first uvAt() there (an
    // untextured surface never asks).
    mutable bool m_hasUvRatio = false;
    mutable std::array<glm::dvec2, 3> m_uvNumerator{};  ///< u^2, u, 1 coefficients
    mutable raster::Quadratic m_uvDenominator;
    mutable std::array<raster::Quadratic, 3> m_weights;  ///< corner i's unnormalised barycentric
};

// The mean shaded colour and opacity of a triangle over [t0, t1] at a site (shadeTimeSpan).
ShadedColor shadeTriangleSpan(const SegmentedGeometry& geometry, const raster::Viewport& viewport, ShadingMode mode,
                              const SpanShadingSettings& settings, std::uint32_t triangle, float t0, float t1, const ShadingSite& site,
                              MovingTriangleCache& cache);

}  // namespace streak::exposure
