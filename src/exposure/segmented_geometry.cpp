#include "exposure/segmented_geometry.h"

#include "raster/moving_triangle.h"

#include <glm/common.hpp>
#include <glm/mat4x4.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>

namespace streak::exposure {

namespace {

// Vertices probed for the deviation of linear pieces: evenly strided over the scene, at most this
// many, so that the choice costs no more on a dense mesh than on a small one.
constexpr std::size_t kMaxProbeVertices = 4096;
constexpr double kSeenNdc = 1.5;

// The largest screen distance, in pixels of a viewport.height tall image, between a probed
// vertex's true position at the middle of each of numSegments even pieces of the shutter (its
// motion at that time, seen through the camera at that time) and where the piece puts it (its
// clip-space position interpolated linearly between the piece's ends, as the exact methods do).
// Only points seen at that time are counted: in front of the near plane, and within a quarter of
// the image beyond its borders (|NDC| <= 1.5). Off screen, and most of all near the eye plane,
// NDC distances grow without bound and say nothing of the image.
double pieceDeviation(const Scene& scene, const raster::Viewport& viewport, int numSegments) {
    const float aspect = float(viewport.width) / float(viewport.height);
    std::size_t numVertices = 0;
    for (const Mesh& mesh : scene.meshes) numVertices += mesh.numVertices();
    const std::size_t stride = std::max<std::size_t>(1, numVertices / kMaxProbeVertices);
    double worst = 0.0;
    for (int k = 0; k < numSegments; ++k) {
        const std::array<float, 3> times{float(k) / float(numSegments), (float(k) + 0.5f) / float(numSegments),
                                         float(k + 1) / float(numSegments)};
        std::array<glm::dmat4, 3> clipFromWorld;
        for (int i = 0; i < 3; ++i) clipFromWorld[std::size_t(i)] = glm::dmat4(scene.camera.clipFromWorld(times[std::size_t(i)], aspect));
        std::size_t next = 0;  // the next probed vertex, counted over all meshes
        std::size_t first = 0;
        for (const Mesh& mesh : scene.meshes) {
            const std::array<MotionWeights, 3> weights{mesh.weightsAt(times[0]), mesh.weightsAt(times[1]), mesh.weightsAt(times[2])};
            const std::size_t n = mesh.numVertices();
            for (; next < first + n; next += stride) {
                const std::uint32_t v = std::uint32_t(next - first);
                std::array<glm::dvec4, 3> clip;
                for (int i = 0; i < 3; ++i)
                    clip[std::size_t(i)] = clipFromWorld[std::size_t(i)] * glm::dvec4(glm::dvec3(mesh.positionAt(v, weights[std::size_t(i)])), 1.0);
                const glm::dvec4 linear = 0.5 * (clip[0] + clip[2]);
                const glm::dvec4& truth = clip[1];
                if (!(linear.w > scene.camera.zNear) || !(truth.w > scene.camera.zNear)) continue;
                const glm::dvec2 seen = glm::dvec2(truth) / truth.w;
                if (!(std::abs(seen.x) <= kSeenNdc && std::abs(seen.y) <= kSeenNdc)) continue;
                const double pixels = Camera::pixelsOfNdc(glm::dvec2(linear) / linear.w - seen, aspect, double(viewport.height));
                if (std::isfinite(pixels)) worst = std::max(worst, pixels);
            }
            first += n;
        }
    }
    return worst;
}

}  // namespace

SegmentedGeometry::SegmentPlan SegmentedGeometry::plan(const Scene& scene, int curveSegments, const raster::Viewport& viewport) {
    int maxKeys = 2;
    // A moving camera that does not turn keeps linear motion linear (Camera::isTurning).
    bool isCurved = scene.camera.isTurning();
    for (const Mesh& mesh : scene.meshes) {
        maxKeys = std::max(maxKeys, mesh.numKeys);
        isCurved = isCurved || mesh.isCurved();
    }
    const int keySegments = maxKeys - 1;
    SegmentPlan plan;
    if (!isCurved) plan.piecesPerKey = 1;
    else if (curveSegments != kAutoCurveSegments) plan.piecesPerKey = std::clamp(curveSegments, 1, kMaxCurveSegments);
    else
        for (int pieces = 1;; pieces *= 2) {
            plan.piecesPerKey = pieces;
            plan.deviationPixels = pieceDeviation(scene, viewport, keySegments * pieces);
            if (plan.deviationPixels <= kCurveTolerancePixels || pieces >= kMaxCurveSegments) break;
        }
    plan.numSegments = keySegments * plan.piecesPerKey;
    return plan;
}

SegmentedGeometry::SegmentedGeometry(const Scene& scene, const raster::Viewport& viewport, int curveSegments) : m_flat(scene) {
    m_plan = plan(scene, curveSegments, viewport);
    m_numSegments = m_plan.numSegments;
    const float aspect = float(viewport.width) / float(viewport.height);

    const int n = m_numSegments;
    m_positions.resize(std::size_t(n) + 1), m_normals.resize(std::size_t(n) + 1);
    std::vector<glm::mat4> clipFromWorld(std::size_t(n) + 1);
    tbb::parallel_for(0, n + 1, [&](int k) {
        const float t = float(k) / float(n);
        m_flat.positionsAt(t, m_positions[std::size_t(k)]);
        m_flat.normalsAt(t, m_normals[std::size_t(k)]);
        clipFromWorld[std::size_t(k)] = scene.camera.clipFromWorld(t, aspect);
    });
    const auto& triangles = m_flat.triangles();
    m_segments.resize(triangles.size() * std::size_t(n));
    std::atomic<std::int64_t> backFacing{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_segments.size(), 1024), [&](const tbb::blocked_range<std::size_t>& range) {
        std::int64_t localBackFacing = 0;
        for (std::size_t p = range.begin(); p != range.end(); ++p) {
            const std::uint32_t tri = std::uint32_t(p / std::size_t(n));
            const std::size_t k = p % std::size_t(n);
            TriangleSegment& s = m_segments[p];
            s.triangle = tri;
            s.t0 = float(k) / float(n);
            s.t1 = float(k + 1) / float(n);
            const glm::uvec3 v = triangles[tri].vertices;
            float minW = std::numeric_limits<float>::max();
            for (int i = 0; i < 3; ++i) {
                s.clip0[i] = clipFromWorld[k] * glm::vec4(m_positions[k][v[i]], 1.0f);
                s.clip1[i] = clipFromWorld[k + 1] * glm::vec4(m_positions[k + 1][v[i]], 1.0f);
                minW = std::min({minW, s.clip0[i].w, s.clip1[i].w});
            }
            s.nearness = minW > 0.0f ? 1.0f / minW : 0.0f;
            if (s.isInFront()) {
                if (raster::isBackFacingThroughout(s.clip0, s.clip1)) s.orientation = -1;
                // Swapping two corners flips the orientation: back facing that way is front facing.
                else if (raster::isBackFacingThroughout({s.clip0[0], s.clip0[2], s.clip0[1]}, {s.clip1[0], s.clip1[2], s.clip1[1]})) s.orientation = 1;
            }
            s.isBackFacingThroughout = !triangles[tri].isDoubleSided && s.orientation < 0;
            localBackFacing += s.isBackFacingThroughout;
        }
        backFacing += localBackFacing;
    });
    m_numBackFacing = backFacing.load();
}

const TriangleSegment& SegmentedGeometry::segmentAt(std::uint32_t triangle, float t) const {
    return segment(triangle, std::clamp(int(t * float(m_numSegments)), 0, m_numSegments - 1));
}

SegmentedGeometry::WorldCorners SegmentedGeometry::cornersOf(const TriangleSegment& segment) const {
    // Only this geometry's own segments carry their index in their address.
    assert(&segment >= m_segments.data() && &segment < m_segments.data() + m_segments.size());
    const std::size_t k = std::size_t(&segment - m_segments.data()) % std::size_t(m_numSegments);
    const glm::uvec3 v = m_flat.triangles()[segment.triangle].vertices;
    WorldCorners c;
    for (int i = 0; i < 3; ++i) {
        c.world0[i] = m_positions[k][v[i]], c.world1[i] = m_positions[k + 1][v[i]];
        c.normal0[i] = m_normals[k][v[i]], c.normal1[i] = m_normals[k + 1][v[i]];
    }
    return c;
}

std::vector<raster::PixelBounds> SegmentedGeometry::screenBounds(const raster::Viewport& viewport) const {
    std::vector<raster::PixelBounds> bounds(m_segments.size());
    tbb::parallel_for(std::size_t(0), m_segments.size(), [&](std::size_t i) {
        const TriangleSegment& s = m_segments[i];
        raster::PixelBounds& b = bounds[i];
        if (s.isBackFacingThroughout) return;  // empty
        if (!s.isInFront()) {
            b = {0, 0, viewport.width - 1, viewport.height - 1};
            return;
        }
        glm::dvec2 lo(1e300), hi(-1e300);
        for (const auto* corners : {&s.clip0, &s.clip1})
            for (const glm::vec4& c : *corners) {
                const glm::dvec2 p((double(c.x) / c.w + 1.0) * 0.5 * viewport.width, (1.0 - double(c.y) / c.w) * 0.5 * viewport.height);
                lo = glm::min(lo, p), hi = glm::max(hi, p);
            }
        b = raster::pixelBoundsOfRaster(lo, hi, viewport);
    });
    return bounds;
}

void recordSegmentPlan(RenderStats& stats, const SegmentedGeometry::SegmentPlan& plan) {
    stats.setCounter("curve_segments", plan.piecesPerKey);
    if (plan.deviationPixels >= 0.0) stats.setCounter("curve_deviation_px", plan.deviationPixels);
}

}  // namespace streak::exposure
