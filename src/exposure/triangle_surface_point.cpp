#include "exposure/triangle_surface_point.h"

#include <glm/common.hpp>

#include <cmath>

namespace streak::exposure {

TriangleSurfacePoint::TriangleSurfacePoint(const SegmentedGeometry& geometry, const raster::Viewport& viewport, const ShadingSite& site,
                                           std::uint32_t triangle, MovingTriangleCache& cache)
    : m_geometry(geometry),
      m_step(2.0 * site.footprintPixels.x / double(viewport.width), 2.0 * site.footprintPixels.y / double(viewport.height)),
      m_clamp(site.clampToTriangle),
      m_isBox(site.boxFootprint),
      m_boxTaps(site.boxTaps),
      m_boxBudget(site.boxBudget),
      m_triangle(triangle),
      m_ndc(site.ndc),
      m_samples(site.samples),
      m_cache(cache) {}

const std::array<glm::vec2, 3>& TriangleSurfacePoint::cornerUvs() const {
    if (!m_hasUv) m_uv = m_geometry.flat().cornerUvs(m_geometry.flat().triangles()[m_triangle]), m_hasUv = true;
    return m_uv;
}

const TriangleSegment& TriangleSurfacePoint::select(float t) const {
    const TriangleSegment& segment = m_geometry.segmentAt(m_triangle, t);
    if (&segment != m_segment) {
        m_segment = &segment;
        m_moving = &m_cache.get(m_geometry, std::uint32_t(&segment - m_geometry.segments().data()));
        m_hasUvRatio = false;
    }
    return segment;
}

void TriangleSurfacePoint::makeUvRatio() const {
    // Corner i's weight is the edge function of the edge opposite it, edge (i + 1) % 3.
    m_uvNumerator = {glm::dvec2(0.0), glm::dvec2(0.0), glm::dvec2(0.0)};
    m_uvDenominator = {};
    for (int i = 0; i < 3; ++i) {
        const raster::Quadratic e = m_moving->edgeFunction((i + 1) % 3, m_ndc);
        m_weights[std::size_t(i)] = e;
        const glm::dvec2 uv(cornerUvs()[i]);
        m_uvNumerator[0] += e.a * uv, m_uvNumerator[1] += e.b * uv, m_uvNumerator[2] += e.c * uv;
        m_uvDenominator.a += e.a, m_uvDenominator.b += e.b, m_uvDenominator.c += e.c;
    }
    m_hasUvRatio = true;
}

bool TriangleSurfacePoint::at(float t, bool withFootprint, SurfacePoint& out) const {
    const TriangleSegment& segment = select(t);
    // (A still segment is the same at every u.)
    const double u = segment.isStill ? 0.0 : segment.localTime(t);
    raster::HomogeneousSample s;
    glm::dvec3 right, down;
    if (withFootprint) {
        std::array<raster::HomogeneousSample, 2> n;
        m_moving->sampleWithNeighbours<2>(u, m_ndc, {glm::dvec2(m_step.x, 0.0), glm::dvec2(0.0, -m_step.y)}, s, n);
        if (!s.isValid) return false;
        // Past the horizon the neighbours say nothing about the footprint.
        const bool isUseful = n[0].isValid && n[1].isValid && n[0].viewDepth > 0.0 && n[1].viewDepth > 0.0;
        right = isUseful ? n[0].bary : s.bary, down = isUseful ? n[1].bary : s.bary;
        if (m_clamp) {
            // The footprint keeps its shape; it moves with the point.
            const glm::dvec3 held = clampedBarycentrics(s.bary);
            right += held - s.bary, down += held - s.bary, s.bary = held;
        }
    } else {
        if (!plainSample(u, s)) return false;
        right = down = s.bary;
    }
    out = pointOf(segment, u, s, right, down);
    return true;
}

SurfacePoint TriangleSurfacePoint::pointOf(const TriangleSegment& segment, double u, const raster::HomogeneousSample& s, const glm::dvec3& right,
                                           const glm::dvec3& down) const {
    std::array<glm::vec3, 3> world, normal;
    const float uf = float(u);
    const SegmentedGeometry::WorldCorners& corners = m_cache.cornersOf(m_geometry, std::uint32_t(&segment - m_geometry.segments().data()));
    if (segment.isStill) {
        world = corners.world0, normal = corners.normal0;
    } else {
        for (int i = 0; i < 3; ++i) {
            world[i] = glm::mix(corners.world0[i], corners.world1[i], uf);
            normal[i] = glm::mix(corners.normal0[i], corners.normal1[i], uf);
        }
    }
    const FlatGeometry& flat = m_geometry.flat();
    return flat.surfacePoint(flat.triangles()[m_triangle], world, normal, glm::vec3(s.bary), glm::vec3(right), glm::vec3(down), s.isFrontFacing);
}

bool TriangleSurfacePoint::plainSample(double u, raster::HomogeneousSample& s) const {
    s = m_moving->sample(u, m_ndc);
    if (!s.isValid) return false;
    if (m_clamp) s.bary = clampedBarycentrics(s.bary);
    return true;
}

bool TriangleSurfacePoint::atSample(const glm::dvec2& ndc, const SurfacePoint& middle, SurfacePoint& out) const {
    const TriangleSegment& segment = select(0.5f);
    if (!segment.isStill) return false;
    const raster::HomogeneousSample s = m_moving->sample(0.0, ndc);
    if (!s.isValid) return false;
    out = pointOf(segment, 0.0, s, s.bary, s.bary);
    out.duvdx = middle.duvdx, out.duvdy = middle.duvdy;
    return true;
}

bool TriangleSurfacePoint::vertexColorAt(float t, glm::vec4& color) const {
    raster::HomogeneousSample s;
    if (!plainSample(select(t).localTime(t), s)) return false;
    const FlatGeometry& flat = m_geometry.flat();
    color = flat.vertexColorAt(flat.triangles()[m_triangle], glm::vec3(s.bary));
    return true;
}

bool TriangleSurfacePoint::isStill(float t0, float t1) const {
    const TriangleSegment& segment = select(t0);
    return segment.isStill && &segment == &m_geometry.segmentAt(m_triangle, t1) && m_geometry.scene().camera.isStatic();
}

int TriangleSurfacePoint::materialIndex() const { return int(m_geometry.flat().triangles()[m_triangle].material); }

// uv is a ratio of quadratics in u: sum(uv_i E_opposite(u)) / sum(E(u)).
bool TriangleSurfacePoint::uvAt(float t, glm::vec2& uv) const {
    const double u = select(t).localTime(t);
    if (!m_hasUvRatio) makeUvRatio();
    const double denominator = m_uvDenominator(u);
    if (denominator == 0.0 || !std::isfinite(denominator)) return false;
    // A box's taps are clipped to the triangle instead (TextureFootprint::clipTo).
    if (m_clamp && !m_isBox && heldUvOutside(glm::dvec3(m_weights[0](u), m_weights[1](u), m_weights[2](u)) / denominator, cornerUvs(), uv)) return true;
    uv = glm::vec2(((m_uvNumerator[0] * u + m_uvNumerator[1]) * u + m_uvNumerator[2]) / denominator);
    return true;
}

ShadedColor shadeTriangleSpan(const SegmentedGeometry& geometry, const raster::Viewport& viewport, ShadingMode mode,
                              const SpanShadingSettings& settings, std::uint32_t triangle, float t0, float t1, const ShadingSite& site,
                              MovingTriangleCache& cache) {
    return shadeTimeSpan(geometry.scene(), mode, t0, t1, TriangleSurfacePoint(geometry, viewport, site, triangle, cache), settings);
}

}  // namespace streak::exposure
