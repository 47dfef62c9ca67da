#include "exposure/curved_geometry.h"

#include "util/error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace streak::exposure {

namespace {

constexpr int kMaxPieces = 64;

// Control points of the curves through samples[i] at t = i / order (raster::bezierThroughSamples).
template <class T, std::size_t N>
std::array<T, N> throughSamples(const std::array<T, N>& samples, int order) {
    const auto w = raster::bezierThroughSamples(order);
    std::array<T, N> control{};
    for (int j = 0; j <= order; ++j) {
        T sum = samples[0] * float(w[std::size_t(j)][0]);
        for (int i = 1; i <= order; ++i) sum += samples[std::size_t(i)] * float(w[std::size_t(j)][std::size_t(i)]);
        control[std::size_t(j)] = sum;
    }
    return control;
}

}  // namespace

CurvedGeometry::CurvedGeometry(const Scene& scene, float aspect, int cameraOrder) : m_flat(scene) {
    // Pieces: every mesh's key segments (linear keys) or Bezier pieces end on a piece boundary
    // (the least common multiple of their counts, capped); a Bezier piece is cut exactly
    // anywhere, so the order is the highest of them.
    int pieces = 1, bezierOrder = 1;
    bool isCapped = false;
    const auto piecesOf = [](const Mesh& mesh) { return (mesh.numKeys - 1) / mesh.bezierOrder(); };
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.bezierOrder() > raster::CurvedTriangle::kMaxOrder)
            throw Error("method 'higher-order': mesh '" + mesh.name + "' has Bezier keys of order " + std::to_string(mesh.bezierOrder()) +
                        "; the most is " + std::to_string(raster::CurvedTriangle::kMaxOrder));
        bezierOrder = std::max(bezierOrder, mesh.bezierOrder());
        if (!isCapped) {
            const int next = std::lcm(pieces, piecesOf(mesh));
            if (next > kMaxPieces) isCapped = true;
            else pieces = next;
        }
    }
    if (isCapped)
        for (const Mesh& mesh : scene.meshes) pieces = std::max(pieces, piecesOf(mesh));
    // Past the cap some key times fall inside pieces: their paths are then fitted too.
    m_isFitted = !scene.camera.isStatic() || isCapped;
    m_order = m_isFitted ? std::clamp(cameraOrder, 1, raster::CurvedTriangle::kMaxOrder) : bezierOrder;
    m_numPieces = pieces;

    // Positions, normals and the camera at order + 1 evenly spaced times of every piece.
    const int n = m_order, numTimes = pieces * n + 1;
    std::vector<VertexArray> positions(static_cast<std::size_t>(numTimes)), normals(static_cast<std::size_t>(numTimes));
    std::vector<glm::mat4> clipFromWorld(static_cast<std::size_t>(numTimes));
    tbb::parallel_for(0, numTimes, [&](int k) {
        const float t = float(k) / float(numTimes - 1);
        m_flat.positionsAt(t, positions[std::size_t(k)]);
        m_flat.normalsAt(t, normals[std::size_t(k)]);
        clipFromWorld[std::size_t(k)] = scene.camera.clipFromWorld(t, aspect);
    });
    const auto& triangles = m_flat.triangles();
    m_segments.resize(triangles.size() * std::size_t(pieces));
    tbb::parallel_for(std::size_t(0), m_segments.size(), [&](std::size_t p) {
        const auto tri = std::uint32_t(p / std::size_t(pieces));
        const int piece = int(p % std::size_t(pieces));
        CurvedSegment& s = constructAt(m_segments, p);
        s.triangle = tri;
        s.t0 = float(piece) / float(pieces);
        s.t1 = float(piece + 1) / float(pieces);
        s.order = n;
        const glm::uvec3 v = triangles[tri].vertices;
        float minW = std::numeric_limits<float>::max();
        for (std::size_t i = 0; i < 3; ++i) {
            raster::CurvedTriangle::Corner clip{};
            std::array<glm::vec3, raster::CurvedTriangle::kMaxOrder + 1> world{}, normal{};
            for (int j = 0; j <= n; ++j) {
                const std::size_t k = std::size_t(piece * n + j);
                world[std::size_t(j)] = positions[k][v[i]];
                normal[std::size_t(j)] = normals[k].empty() ? glm::vec3(0.0f) : normals[k][v[i]];
                clip[std::size_t(j)] = clipFromWorld[k] * glm::vec4(world[std::size_t(j)], 1.0f);
            }
            s.clip[i] = throughSamples(clip, n);
            s.world[i] = throughSamples(world, n);
            s.normal[i] = throughSamples(normal, n);
            for (int j = 0; j <= n; ++j) minW = std::min(minW, s.clip[i][std::size_t(j)].w);
        }
        s.nearness = minW > 0.0f ? 1.0f / minW : 0.0f;
    });
}

const CurvedSegment& CurvedGeometry::segmentAt(std::uint32_t triangle, float t) const {
    const int piece = std::clamp(int(t * float(m_numPieces)), 0, m_numPieces - 1);
    return m_segments[std::size_t(triangle) * std::size_t(m_numPieces) + std::size_t(piece)];
}

std::vector<raster::PixelBounds> CurvedGeometry::screenBounds(const raster::Viewport& viewport, int intervals) const {
    std::vector<raster::PixelBounds> bounds(m_segments.size() * std::size_t(intervals));
    tbb::parallel_for(std::size_t(0), m_segments.size(), [&](std::size_t i) {
        const CurvedSegment& s = m_segments[i];
        // Each coordinate's curve over each sub-piece, by subdivision.
        std::array<std::array<raster::Bernstein, 3>, 3> curves;  // corner, coordinate (x, y, w)
        for (std::size_t c = 0; c < 3; ++c)
            for (int axis = 0; axis < 3; ++axis) {
                raster::Bernstein& b = curves[c][std::size_t(axis)];
                b.degree = s.order;
                for (int j = 0; j <= s.order; ++j) {
                    const glm::vec4& p = s.clip[c][std::size_t(j)];
                    b.coefficients[std::size_t(j)] = axis == 0 ? p.x : axis == 1 ? p.y : p.w;
                }
            }
        for (int k = 0; k < intervals; ++k) {
            raster::PixelBounds& b = bounds[i * std::size_t(intervals) + std::size_t(k)];
            const double u0 = double(k) / intervals, u1 = double(k + 1) / intervals;
            glm::dvec2 lo(1e300), hi(-1e300);
            bool isBehind = false;
            for (std::size_t c = 0; c < 3 && !isBehind; ++c) {
                const raster::Bernstein x = curves[c][0].restricted(u0, u1), y = curves[c][1].restricted(u0, u1),
                                        w = curves[c][2].restricted(u0, u1);
                for (int j = 0; j <= s.order; ++j) {
                    const double cw = w.coefficients[std::size_t(j)];
                    if (!(cw > 0.0)) {
                        isBehind = true;
                        break;
                    }
                    const glm::dvec2 p((x.coefficients[std::size_t(j)] / cw + 1.0) * 0.5 * viewport.width,
                                       (1.0 - y.coefficients[std::size_t(j)] / cw) * 0.5 * viewport.height);
                    lo = glm::min(lo, p), hi = glm::max(hi, p);
                }
            }
            b = isBehind ? raster::PixelBounds{0, 0, viewport.width - 1, viewport.height - 1} : raster::pixelBoundsOfRaster(lo, hi, viewport);
        }
    });
    return bounds;
}

}  // namespace streak::exposure
