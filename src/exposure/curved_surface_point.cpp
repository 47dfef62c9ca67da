#include "exposure/curved_surface_point.h"

namespace streak::exposure {

namespace {

// De Casteljau over order + 1 control points.
glm::vec3 curveAt(const std::array<glm::vec3, raster::CurvedTriangle::kMaxOrder + 1>& control, int order, float u) {
    auto c = control;
    for (int level = order; level > 0; --level)
        for (int j = 0; j < level; ++j) c[std::size_t(j)] += u * (c[std::size_t(j + 1)] - c[std::size_t(j)]);
    return c[0];
}

}  // namespace

const raster::CurvedTriangle& curvedTriangleOf(const CurvedGeometry& geometry, std::uint32_t segment, CurvedTriangleCache& cache) {
    return cache.get(geometry.segments().size(), segment, [&] {
        const CurvedSegment& s = geometry.segments()[segment];
        return raster::CurvedTriangle(s.order, s.clip);
    });
}

CurvedSurfacePoint::CurvedSurfacePoint(const CurvedGeometry& geometry, const raster::Viewport& viewport, int samplesPerAxis,
                                       std::uint32_t triangle, const glm::dvec2& ndc, CurvedTriangleCache& cache)
    : m_geometry(geometry),
      m_step(2.0 / (double(viewport.width) * samplesPerAxis), 2.0 / (double(viewport.height) * samplesPerAxis)),
      m_triangle(triangle),
      m_ndc(ndc),
      m_cache(cache) {}

bool CurvedSurfacePoint::at(float t, bool withFootprint, SurfacePoint& out) const {
    const CurvedSegment& segment = m_geometry.segmentAt(m_triangle, t);
    const auto index = std::uint32_t(&segment - m_geometry.segments().data());
    const raster::CurvedTriangle& curved = curvedTriangleOf(m_geometry, index, m_cache);
    const double u = segment.localTime(t);
    const std::array<glm::dvec3, 3> corners = curved.cornersAt(u);
    const raster::HomogeneousSample s = raster::evaluateHomogeneousXyw(corners, m_ndc);
    if (!s.isValid) return false;
    glm::dvec3 right = s.bary, down = s.bary;
    if (withFootprint) {
        const raster::HomogeneousSample r = raster::evaluateHomogeneousXyw(corners, m_ndc + glm::dvec2(m_step.x, 0.0));
        const raster::HomogeneousSample d = raster::evaluateHomogeneousXyw(corners, m_ndc + glm::dvec2(0.0, -m_step.y));
        // Past the horizon the neighbours say nothing about the footprint.
        if (r.isValid && d.isValid && r.viewDepth > 0.0 && d.viewDepth > 0.0) right = r.bary, down = d.bary;
    }
    std::array<glm::vec3, 3> world, normal;
    for (std::size_t i = 0; i < 3; ++i) {
        world[i] = curveAt(segment.world[i], segment.order, float(u));
        normal[i] = curveAt(segment.normal[i], segment.order, float(u));
    }
    const FlatGeometry& flat = m_geometry.flat();
    out = flat.surfacePoint(flat.triangles()[m_triangle], world, normal, glm::vec3(s.bary), glm::vec3(right), glm::vec3(down), s.isFrontFacing);
    return true;
}

ShadedColor shadeCurvedSpan(const CurvedGeometry& geometry, const raster::Viewport& viewport, ShadingMode mode, const SpanShadingSettings& settings,
                            std::uint32_t triangle, float t0, float t1, const glm::dvec2& ndc, CurvedTriangleCache& cache) {
    return shadeTimeSpan(geometry.flat().scene(), mode, t0, t1, CurvedSurfacePoint(geometry, viewport, settings.samplesPerAxis, triangle, ndc, cache),
                         settings);
}

}  // namespace streak::exposure
