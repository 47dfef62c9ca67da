#include "exposure/segmented_geometry.h"

#include "exposure/closed_surfaces.h"
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
// How far a merged segment may turn a corner's normal from its key's (radians): a thousandth of
// a radian changes a diffuse term by a thousandth, under what an 8-bit image can hold.
constexpr double kMergeNormalRadians = 1e-3;
// The longest run of segments whose joints are measured one by one where the bound on their
// straightness is too coarse (SegmentedGeometry::mergeLinearRuns).
constexpr std::size_t kMeasuredRun = 8;

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

// What a segment's ends' clip corners say of it: its nearness (1 / its nearest corner's view
// depth; clip space is linear over the segment, so the nearest is at an end) and its facing.
void finishSegment(TriangleSegment& s, bool isDoubleSided) {
    float minW = std::numeric_limits<float>::max();
    for (int i = 0; i < 3; ++i) minW = std::min({minW, s.clip0[i].w, s.clip1[i].w});
    s.nearness = minW > 0.0f ? 1.0f / minW : 0.0f;
    s.orientation = 0;
    if (s.isInFront()) {
        if (raster::isBackFacingThroughout(s.clip0, s.clip1)) s.orientation = -1;
        // Swapping two corners flips the orientation: back facing that way is front facing.
        else if (raster::isBackFacingThroughout({s.clip0[0], s.clip0[2], s.clip0[1]}, {s.clip1[0], s.clip1[2], s.clip1[1]})) s.orientation = 1;
    }
    s.isBackFacingThroughout = !isDoubleSided && s.orientation < 0;
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

SegmentedGeometry::SegmentedGeometry(const Scene& scene, const raster::Viewport& viewport, int curveSegments, double mergeTolerancePixels,
                                     bool cullClosed)
    : m_flat(scene) {
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
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_segments.size(), 1024), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t p = range.begin(); p != range.end(); ++p) {
            const std::uint32_t tri = std::uint32_t(p / std::size_t(n));
            const std::size_t k = p % std::size_t(n);
            TriangleSegment& s = constructAt(m_segments, p);
            s.triangle = tri;
            s.t0 = float(k) / float(n);
            s.t1 = float(k + 1) / float(n);
            s.key0 = std::uint32_t(k), s.key1 = std::uint32_t(k + 1);
            const glm::uvec3 v = triangles[tri].vertices;
            for (int i = 0; i < 3; ++i) {
                s.clip0[i] = clipFromWorld[k] * glm::vec4(m_positions[k][v[i]], 1.0f);
                s.clip1[i] = clipFromWorld[k + 1] * glm::vec4(m_positions[k + 1][v[i]], 1.0f);
            }
            finishSegment(s, triangles[tri].isDoubleSided);
            s.isStill = isStill(s);
        }
    });
    // A camera that does not turn maps straight clip paths to straight world paths (clip space is
    // a fixed linear map of the view, plus the camera's own linear travel), so the world corners
    // shading takes at a merged segment's ends hold between them too; a turning one does not.
    if (n > 1 && mergeTolerancePixels > 0.0 && !scene.camera.isTurning()) mergeLinearRuns(viewport, mergeTolerancePixels);
    if (cullClosed) cullClosedBackFaces(scene.camera);
    std::atomic<std::int64_t> backFacing{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_segments.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
        std::int64_t localBackFacing = 0;
        for (std::size_t p = range.begin(); p != range.end(); ++p) localBackFacing += m_segments[p].isBackFacingThroughout && !isMergedAway(p);
        backFacing += localBackFacing;
    });
    m_numBackFacing = backFacing.load();
    m_isCameraStatic = scene.camera.isStatic();
    m_hasWholeShutterSegments = n == 1 || std::any_of(m_segments.begin(), m_segments.end(), [](const TriangleSegment& s) { return s.t0 == 0.0f && s.t1 == 1.0f; });
}

void SegmentedGeometry::cullClosedBackFaces(const Camera& camera) {
    const ClosedSurfaces closed(m_flat, m_positions);
    if (closed.count() == 0) return;
    const std::size_t n = std::size_t(m_numSegments);
    // A surface's back faces are hidden where the near plane stays clear of it all the shutter:
    // every corner of every segment beyond it, so every point (clip space is linear over a
    // segment). That also keeps the eye outside it: a closed surface around the eye would
    // reach behind it, where view depth is negative.
    std::atomic<std::int64_t> surfaces{0}, triangles{0};
    tbb::parallel_for(std::uint32_t(0), closed.count(), [&](std::uint32_t s) {
        for (const std::uint32_t t : closed.trianglesOf(s))
            for (std::size_t k = 0; k < n; ++k)
                for (const auto* corners : {&m_segments[t * n + k].clip0, &m_segments[t * n + k].clip1})
                    for (const glm::vec4& c : *corners)
                        if (!(c.w > camera.zNear)) return;
        ++surfaces, triangles += std::int64_t(closed.trianglesOf(s).size());
        for (const std::uint32_t t : closed.trianglesOf(s))
            for (std::size_t k = 0; k < n; ++k) {
                TriangleSegment& segment = m_segments[t * n + k];
                segment.isBackFacingThroughout = segment.isBackFacingThroughout || segment.orientation < 0;
            }
    });
    m_numClosedSurfaces = surfaces.load(), m_numClosedTriangles = triangles.load();
}

void SegmentedGeometry::mergeLinearRuns(const raster::Viewport& viewport, double tolerancePixels) {
    const std::size_t n = std::size_t(m_numSegments);
    const auto& triangles = m_flat.triangles();
    const double pixelsPerNdc = 0.5 * double(std::max(viewport.width, viewport.height));
    const glm::dvec2 halfSize(0.5 * viewport.width, 0.5 * viewport.height);
    // Whether key pose `middle` of corner `vertex` lies on the straight path from key a to key b
    // at its time: on screen within the tolerance, in view depth to 1e-5 of its size, its
    // normal's direction within kMergeNormalRadians (shading normalizes the mix). Measured, where
    // the bound below is too coarse for float rounding that does not add up.
    auto isOnPath = [&](const glm::vec4& clipA, const glm::vec4& clipMiddle, const glm::vec4& clipB, std::uint32_t vertex, std::size_t a,
                        std::size_t middle, std::size_t b) {
        const double u = double(middle - a) / double(b - a);
        const glm::dvec4 mixed = glm::mix(glm::dvec4(clipA), glm::dvec4(clipB), u), truth(clipMiddle);
        if (!(mixed.w > 0.0 && truth.w > 0.0)) return false;
        const glm::dvec2 off = (glm::dvec2(mixed) / mixed.w - glm::dvec2(truth) / truth.w) * halfSize;
        if (!(std::abs(off.x) <= tolerancePixels && std::abs(off.y) <= tolerancePixels && std::abs(mixed.w - truth.w) <= 1e-5 * truth.w)) return false;
        const glm::dvec3 normal = glm::mix(glm::dvec3(m_normals[a][vertex]), glm::dvec3(m_normals[b][vertex]), u);
        const glm::dvec3 normalTruth(m_normals[middle][vertex]);
        const double lengths = glm::length(normal) * glm::length(normalTruth);
        if (!(lengths > 0.0)) return normal == normalTruth;
        return glm::length(glm::cross(normal, normalTruth)) <= kMergeNormalRadians * lengths && glm::dot(normal, normalTruth) > 0.0;
    };
    std::atomic<std::int64_t> mergedAway{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 256), [&](const tbb::blocked_range<std::size_t>& range) {
        std::int64_t localMerged = 0;
        for (std::size_t tri = range.begin(); tri != range.end(); ++tri) {
            TriangleSegment* slots = &m_segments[tri * n];
            const glm::uvec3 v = triangles[tri].vertices;
            for (std::size_t a = 0; a < n;) {
                // The run of slots a..b grows while a bound on how far its joints stray from
                // the straight path between its ends stays within the tolerance. With every
                // slot's velocity (clip space, per key segment) within M of the first slot's,
                // key j of a run of L slots lies within 2 L M of the mix of the run's ends (the
                // sum of the velocities' departures before it, less its share of all of them),
                // in each clip coordinate. That is within 2 L M (1 + |ndc|) / (w - 2 L M) in NDC,
                // and 2 L M of view depth; normals the same way. One step per slot: a still
                // triangle (M = 0) merges whole, at any number of keys.
                double clipSpread = 0.0, normalSpread = 0.0;
                double minW = std::numeric_limits<double>::max(), maxNdc = 0.0, minNormal = std::numeric_limits<double>::max();
                auto take = [&](std::size_t key, const std::array<glm::vec4, 3>& clip) {
                    for (int i = 0; i < 3; ++i) {
                        minW = std::min(minW, double(clip[i].w));
                        if (clip[i].w > 0.0f)
                            maxNdc = std::max({maxNdc, std::abs(double(clip[i].x) / clip[i].w), std::abs(double(clip[i].y) / clip[i].w)});
                        minNormal = std::min(minNormal, double(glm::length(m_normals[key][v[i]])));
                    }
                };
                take(a, slots[a].clip0);
                take(a + 1, slots[a].clip1);
                std::size_t b = a;
                while (b + 1 < n) {
                    const std::size_t next = b + 1;
                    double clip = clipSpread, normal = normalSpread;
                    for (int i = 0; i < 3; ++i) {
                        const glm::dvec4 d = (glm::dvec4(slots[next].clip1[i]) - glm::dvec4(slots[next].clip0[i])) -
                                             (glm::dvec4(slots[a].clip1[i]) - glm::dvec4(slots[a].clip0[i]));
                        clip = std::max({clip, std::abs(d.x), std::abs(d.y), std::abs(d.z), std::abs(d.w)});
                        const glm::dvec3 dn = (glm::dvec3(m_normals[next + 1][v[i]]) - glm::dvec3(m_normals[next][v[i]])) -
                                              (glm::dvec3(m_normals[a + 1][v[i]]) - glm::dvec3(m_normals[a][v[i]]));
                        normal = std::max({normal, std::abs(dn.x), std::abs(dn.y), std::abs(dn.z)});
                    }
                    const double saveW = minW, saveNdc = maxNdc, saveNormal = minNormal;
                    take(next + 1, slots[next].clip1);
                    const double reach = 2.0 * double(next - a + 1);  // 2 L
                    const double clipOff = reach * clip, normalOff = reach * normal * std::sqrt(3.0);
                    const bool isStraight = clipOff == 0.0 ||
                                            (minW - clipOff > 0.0 && clipOff * (1.0 + maxNdc) / (minW - clipOff) * pixelsPerNdc <= tolerancePixels &&
                                             clipOff <= 1e-5 * minW);
                    // Normals: zero (a mesh without them) stays zero; else the mix turns the
                    // key's own by at most about its offset over its length.
                    const bool isNormalKept = normalOff == 0.0 || normalOff <= kMergeNormalRadians * 0.5 * minNormal;
                    // Where the bound is too coarse, a short run is measured joint by joint
                    // instead (at most kMeasuredRun slots, so the work stays linear in keys).
                    auto isMeasuredStraight = [&] {
                        if (next - a + 1 > kMeasuredRun) return false;
                        for (std::size_t middle = a + 1; middle <= next; ++middle)
                            for (int i = 0; i < 3; ++i)
                                if (!isOnPath(slots[a].clip0[i], slots[middle].clip0[i], slots[next].clip1[i], v[i], a, middle, next + 1)) return false;
                        return true;
                    };
                    if ((!isStraight || !isNormalKept) && !isMeasuredStraight()) {
                        minW = saveW, maxNdc = saveNdc, minNormal = saveNormal;
                        break;
                    }
                    clipSpread = clip, normalSpread = normal, b = next;
                }
                if (b > a) {
                    TriangleSegment merged = slots[a];
                    merged.t1 = slots[b].t1, merged.clip1 = slots[b].clip1, merged.key1 = slots[b].key1;
                    finishSegment(merged, triangles[tri].isDoubleSided);
                    merged.isStill = isStill(merged);
                    for (std::size_t k = a; k <= b; ++k) slots[k] = merged;
                    localMerged += std::int64_t(b - a);
                }
                a = b + 1;
            }
        }
        mergedAway += localMerged;
    });
    m_numMergedAway = mergedAway.load();
}

const TriangleSegment& SegmentedGeometry::segmentAt(std::uint32_t triangle, float t) const {
    return segment(triangle, segment(triangle, std::clamp(int(t * float(m_numSegments)), 0, m_numSegments - 1)).key0);
}

bool SegmentedGeometry::isStill(const TriangleSegment& segment) const {
    // (The clip corners are at hand: most moving segments stop there.)
    if (segment.clip0 != segment.clip1) return false;
    const glm::uvec3 v = m_flat.triangles()[segment.triangle].vertices;
    for (int i = 0; i < 3; ++i)
        if (m_positions[segment.key0][v[i]] != m_positions[segment.key1][v[i]] || m_normals[segment.key0][v[i]] != m_normals[segment.key1][v[i]])
            return false;
    return true;
}

SegmentedGeometry::WorldCorners SegmentedGeometry::cornersOf(const TriangleSegment& segment) const {
    const std::size_t k0 = segment.key0, k1 = segment.key1;
    assert(k1 <= std::size_t(m_numSegments) && k0 < k1);
    const glm::uvec3 v = m_flat.triangles()[segment.triangle].vertices;
    WorldCorners c;
    for (int i = 0; i < 3; ++i) {
        c.world0[i] = m_positions[k0][v[i]], c.world1[i] = m_positions[k1][v[i]];
        c.normal0[i] = m_normals[k0][v[i]], c.normal1[i] = m_normals[k1][v[i]];
    }
    return c;
}

LargeBuffer<raster::PixelBounds> SegmentedGeometry::screenBounds(const raster::Viewport& viewport) const {
    LargeBuffer<raster::PixelBounds> bounds(m_segments.size());
    tbb::parallel_for(std::size_t(0), m_segments.size(), [&](std::size_t i) {
        const TriangleSegment& s = m_segments[i];
        raster::PixelBounds& b = constructAt(bounds, i);
        if (s.isBackFacingThroughout || isMergedAway(i)) return;  // empty
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

void recordSegments(RenderStats& stats, const SegmentedGeometry& segmented) {
    stats.setCounter("segments_per_triangle", segmented.numSegments());
    stats.setCounter("segments_merged", double(segmented.numMergedAway()));
    stats.setCounter("closed_surfaces", double(segmented.numClosedSurfaces()));
    stats.setCounter("closed_surface_triangles", double(segmented.numClosedTriangles()));
    recordSegmentPlan(stats, segmented.segmentPlan());
}

void recordSegmentPlan(RenderStats& stats, const SegmentedGeometry::SegmentPlan& plan) {
    stats.setCounter("curve_segments", plan.piecesPerKey);
    if (plan.deviationPixels >= 0.0) stats.setCounter("curve_deviation_px", plan.deviationPixels);
}

}  // namespace streak::exposure
