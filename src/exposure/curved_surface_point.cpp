#include "exposure/curved_surface_point.h"

#include <cmath>

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

CurvedSurfacePoint::CurvedSurfacePoint(const CurvedGeometry& geometry, const raster::Viewport& viewport, const ShadingSite& site,
                                       std::uint32_t triangle, CurvedTriangleCache& cache)
    : m_geometry(geometry),
      m_step(2.0 * site.footprintPixels.x / double(viewport.width), 2.0 * site.footprintPixels.y / double(viewport.height)),
      m_clamp(site.clampToTriangle),
      m_isBox(site.boxFootprint),
      m_boxTaps(site.boxTaps),
      m_boxBudget(site.boxBudget),
      m_triangle(triangle),
      m_ndc(site.ndc),
      m_uv(geometry.flat().cornerUvs(geometry.flat().triangles()[triangle])),
      m_cache(cache) {}

const CurvedSegment& CurvedSurfacePoint::select(float t) const {
    const CurvedSegment& segment = m_geometry.segmentAt(m_triangle, t);
    if (&segment != m_segment) {
        m_segment = &segment;
        m_curved = &curvedTriangleOf(m_geometry, std::uint32_t(&segment - m_geometry.segments().data()), m_cache);
        // Corner i's weight is the edge function of the edge opposite it, edge (i + 1) % 3.
        m_uNumerator = m_vNumerator = m_denominator = raster::Bernstein{};
        for (int i = 0; i < 3; ++i) {
            const raster::Bernstein e = m_curved->edgeFunction((i + 1) % 3, m_ndc);
            m_weights[std::size_t(i)] = e;
            m_uNumerator = m_uNumerator + double(m_uv[std::size_t(i)].x) * e;
            m_vNumerator = m_vNumerator + double(m_uv[std::size_t(i)].y) * e;
            m_denominator = m_denominator + e;
        }
    }
    return segment;
}

bool CurvedSurfacePoint::uvAt(float t, glm::vec2& uv) const {
    const double u = select(t).localTime(t);
    const double denominator = m_denominator(u);
    if (denominator == 0.0 || !std::isfinite(denominator)) return false;
    // A box's taps are clipped to the triangle instead (TextureFootprint::clipTo).
    if (m_clamp && !m_isBox && heldUvOutside(glm::dvec3(m_weights[0](u), m_weights[1](u), m_weights[2](u)) / denominator, m_uv, uv)) return true;
    uv = glm::vec2(float(m_uNumerator(u) / denominator), float(m_vNumerator(u) / denominator));
    return true;
}

bool CurvedSurfacePoint::at(float t, bool withFootprint, SurfacePoint& out) const {
    const CurvedSegment& segment = select(t);
    const raster::CurvedTriangle& curved = *m_curved;
    const double u = segment.localTime(t);
    const std::array<glm::dvec3, 3> corners = curved.cornersAt(u);
    raster::HomogeneousSample s = raster::evaluateHomogeneousXyw(corners, m_ndc);
    if (!s.isValid) return false;
    glm::dvec3 right = s.bary, down = s.bary;
    if (withFootprint) {
        const raster::HomogeneousSample r = raster::evaluateHomogeneousXyw(corners, m_ndc + glm::dvec2(m_step.x, 0.0));
        const raster::HomogeneousSample d = raster::evaluateHomogeneousXyw(corners, m_ndc + glm::dvec2(0.0, -m_step.y));
        // Past the horizon the neighbours say nothing about the footprint.
        if (r.isValid && d.isValid && r.viewDepth > 0.0 && d.viewDepth > 0.0) right = r.bary, down = d.bary;
    }
    if (m_clamp) {
        // The footprint keeps its shape; it moves with the point.
        const glm::dvec3 held = clampedBarycentrics(s.bary);
        right += held - s.bary, down += held - s.bary, s.bary = held;
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

int CurvedSurfacePoint::materialIndex() const { return int(m_geometry.flat().triangles()[m_triangle].material); }

ShadedColor shadeCurvedSpan(const CurvedGeometry& geometry, const raster::Viewport& viewport, ShadingMode mode, const SpanShadingSettings& settings,
                            std::uint32_t triangle, float t0, float t1, const ShadingSite& site, CurvedTriangleCache& cache) {
    return shadeTimeSpan(geometry.flat().scene(), mode, t0, t1, CurvedSurfacePoint(geometry, viewport, site, triangle, cache), settings);
}

}  // namespace streak::exposure
