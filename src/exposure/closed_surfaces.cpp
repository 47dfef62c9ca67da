#include "exposure/closed_surfaces.h"

#include "util/memory.h"

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

namespace streak::exposure {

namespace {

// The closed surfaces of one mesh: per triangle (of the mesh) its surface counted within the
// mesh, or ClosedSurfaces::kNone; returns how many. About linear in the mesh's size: a hash
// table welds, each directed edge is looked for in its end's list of edges out (searched
// sorted where it is long), and surfaces are flooded across the edges' twins.
std::uint32_t meshSurfaces(const Mesh& mesh, std::uint32_t vertexOffset, std::span<const VertexArray> poses,
                           std::span<std::uint32_t> surfaceOf) {
    const std::size_t numVertices = mesh.numVertices(), numTriangles = mesh.triangles.size();
    constexpr std::uint32_t kNone = ClosedSurfaces::kNone;
    if (numVertices == 0 || numVertices >= kNone || numTriangles >= kNone / 3 || poses.empty()) return 0;
    auto at = [&](std::size_t pose, std::uint32_t v) { return poses[pose][vertexOffset + v]; };
    for (std::size_t k = 0; k < poses.size(); ++k)
        for (std::uint32_t v = 0; v < numVertices; ++v) {
            const glm::vec3 p = at(k, v);
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return 0;
        }

    // Weld: vertices at one position in the first pose are one corner, if they stay together in
    // every pose (a skin or a morph may pull apart what shares a rest position); a group that
    // parts is left unwelded, which opens the surface around it.
    auto bitsOf = [](float f) { return std::uint64_t(std::bit_cast<std::uint32_t>(f + 0.0f)); };  // (-0 as +0)
    const std::size_t tableSize = std::bit_ceil(2 * numVertices);
    LargeVector<std::uint32_t> table(tableSize, kNone), corner(numVertices);
    for (std::uint32_t v = 0; v < numVertices; ++v) {
        const glm::vec3 p = at(0, v);
        const std::uint64_t h = bitsOf(p.x) * 0x9E3779B97F4A7C15ull ^ std::rotl(bitsOf(p.y) * 0xC2B2AE3D27D4EB4Full, 21) ^
                                std::rotl(bitsOf(p.z) * 0x165667B19E3779F9ull, 42);
        for (std::size_t slot = (h ^ (h >> 29)) & (tableSize - 1);; slot = (slot + 1) & (tableSize - 1)) {
            if (table[slot] == kNone) {
                table[slot] = corner[v] = v;
                break;
            }
            if (at(0, table[slot]) == p) {
                corner[v] = table[slot];
                break;
            }
        }
    }
    // Poses that repeat the one before (a still mesh under a turning camera's many segment
    // ends) are not measured again.
    std::vector<std::size_t> distinctPoses{0};
    for (std::size_t k = 1; k < poses.size(); ++k)
        for (std::uint32_t v = 0; v < numVertices; ++v)
            if (at(k, v) != at(distinctPoses.back(), v)) {
                distinctPoses.push_back(k);
                break;
            }
    LargeVector<std::uint8_t> isParted(numVertices, 0);  ///< per corner: its vertices part in some pose
    for (const std::size_t k : distinctPoses)
        for (std::uint32_t v = 0; v < numVertices; ++v)
            if (corner[v] != v && at(k, v) != at(k, corner[v])) isParted[corner[v]] = 1;
    for (std::uint32_t v = 0; v < numVertices; ++v)
        if (isParted[corner[v]]) corner[v] = v;

    // Each triangle's welded corners (kNone where two are one: degenerate, left out), and each
    // corner's edges out (to the next corner of each triangle, with the edge's slot 3 t + e) as
    // lists.
    LargeVector<glm::uvec3> corners(numTriangles);
    LargeVector<std::uint32_t> firstOut(numVertices + 1, 0);
    for (std::size_t t = 0; t < numTriangles; ++t) {
        const glm::uvec3 v = mesh.triangles[t];
        const glm::uvec3 c(corner[v.x], corner[v.y], corner[v.z]);
        corners[t] = c.x == c.y || c.y == c.z || c.x == c.z ? glm::uvec3(kNone) : c;
        if (corners[t].x != kNone)
            for (int e = 0; e < 3; ++e) ++firstOut[c[e] + 1];
    }
    std::partial_sum(firstOut.begin(), firstOut.end(), firstOut.begin());
    struct Edge {
        std::uint32_t to, slot;
    };
    LargeVector<Edge> out(firstOut.back());
    {
        LargeVector<std::uint32_t> next(firstOut.begin(), firstOut.end() - 1);
        for (std::uint32_t t = 0; t < numTriangles; ++t)
            if (corners[t].x != kNone)
                for (std::uint32_t e = 0; e < 3; ++e) out[next[corners[t][int(e)]]++] = {corners[t][int((e + 1) % 3)], 3 * t + e};
    }
    // The edges from -> to: how many (0, 1, or 2 for more), and the slot of the last found. A
    // corner's list is short, a few edges, and scanned whole; a hub's is sorted first and
    // searched, so that a fan of many triangles costs no more than its size times its log.
    constexpr std::uint32_t kShortList = 16;
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(numVertices), 4096), [&](const tbb::blocked_range<std::uint32_t>& r) {
        for (std::uint32_t v = r.begin(); v != r.end(); ++v)
            if (firstOut[v + 1] - firstOut[v] > kShortList)
                std::sort(out.begin() + firstOut[v], out.begin() + firstOut[v + 1], [](const Edge& x, const Edge& y) { return x.to < y.to; });
    });
    auto edgesTo = [&](std::uint32_t from, std::uint32_t to, std::uint32_t& slot) {
        const Edge* first = out.data() + firstOut[from];
        const Edge* const last = out.data() + firstOut[from + 1];
        const bool isSorted = last - first > std::ptrdiff_t(kShortList);
        if (isSorted) first = std::lower_bound(first, last, to, [](const Edge& x, std::uint32_t target) { return x.to < target; });
        int count = 0;
        for (; first != last && count < 2 && (!isSorted || first->to == to); ++first)
            if (first->to == to) slot = first->slot, ++count;
        return count;
    };
    // Closed and oriented: each directed edge once and its reverse once, its twin (per edge
    // slot; kNone where it has none, which opens the surface).
    // (Each slot is written by the corner it leaves from alone, so corners go in parallel.)
    LargeVector<std::uint32_t> twin(3 * std::size_t(numTriangles), kNone);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(numVertices), 4096), [&](const tbb::blocked_range<std::uint32_t>& r) {
        for (std::uint32_t a = r.begin(); a != r.end(); ++a)
            for (std::uint32_t i = firstOut[a]; i < firstOut[a + 1]; ++i) {
                std::uint32_t reverse = kNone, same = kNone;
                if (edgesTo(a, out[i].to, same) == 1 && edgesTo(out[i].to, a, reverse) == 1) twin[out[i].slot] = reverse;
            }
    });
    // Surfaces: triangles joined across their edges by twins, never at a corner alone (two
    // shells touching at a point, one of them inward say, are two surfaces, each measured).
    LargeVector<std::uint32_t> surface(numTriangles, kNone);  ///< per triangle: its surface's first triangle
    LargeVector<std::uint8_t> isOpen(numTriangles, 0);        ///< per surface's first triangle
    std::vector<std::uint32_t> stack;
    for (std::uint32_t seed = 0; seed < numTriangles; ++seed) {
        if (corners[seed].x == kNone || surface[seed] != kNone) continue;
        surface[seed] = seed;
        stack.assign(1, seed);
        while (!stack.empty()) {
            const std::uint32_t t = stack.back();
            stack.pop_back();
            for (std::uint32_t e = 0; e < 3; ++e) {
                const std::uint32_t other = twin[3 * t + e];
                if (other == kNone) {
                    isOpen[seed] = 1;
                    continue;
                }
                const std::uint32_t u = other / 3;
                if (surface[u] == kNone) surface[u] = seed, stack.push_back(u);
            }
        }
    }

    // Positive volume at every (distinct) pose, about a corner of the surface (for precision).
    LargeVector<double> volume(numTriangles);
    for (const std::size_t k : distinctPoses) {
        std::fill(volume.begin(), volume.end(), 0.0);
        for (std::uint32_t t = 0; t < numTriangles; ++t) {
            const std::uint32_t r = surface[t];
            if (r == kNone || isOpen[r]) continue;
            const glm::uvec3 c = corners[t];
            const glm::dvec3 o(at(k, corners[r].x));
            const glm::dvec3 p0 = glm::dvec3(at(k, c.x)) - o, p1 = glm::dvec3(at(k, c.y)) - o, p2 = glm::dvec3(at(k, c.z)) - o;
            volume[r] += glm::dot(p0, glm::cross(p1, p2));
        }
        for (std::uint32_t t = 0; t < numTriangles; ++t)
            if (surface[t] == t && !(volume[t] > 0.0)) isOpen[t] = 1;
    }
    LargeVector<std::uint32_t> id(numTriangles, kNone);
    std::uint32_t count = 0;
    for (std::uint32_t t = 0; t < numTriangles; ++t) {
        const std::uint32_t r = surface[t];
        if (r == kNone || isOpen[r]) continue;
        if (id[r] == kNone) id[r] = count++;
        surfaceOf[t] = id[r];
    }
    return count;
}

}  // namespace

ClosedSurfaces::ClosedSurfaces(const FlatGeometry& flat, std::span<const VertexArray> poses) {
    const Scene& scene = flat.scene();
    m_surfaceOf.assign(flat.triangles().size(), kNone);
    // A mesh's triangles follow the mesh before it's in the flat geometry.
    std::vector<std::size_t> firstTriangle(scene.meshes.size() + 1, 0);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) firstTriangle[m + 1] = firstTriangle[m] + scene.meshes[m].triangles.size();
    std::vector<std::uint32_t> counts(scene.meshes.size(), 0);
    tbb::parallel_for(std::size_t(0), scene.meshes.size(), [&](std::size_t m) {
        const Mesh& mesh = scene.meshes[m];
        const Material& material = scene.materials[mesh.material];
        // Single-sided triangles drop their back faces already; a blend or a cut-out is not
        // closed to the eye.
        if (!material.doubleSided || material.isTranslucent()) return;
        const std::span<std::uint32_t> local(m_surfaceOf.data() + firstTriangle[m], mesh.triangles.size());
        counts[m] = meshSurfaces(mesh, flat.meshVertexOffset(std::uint32_t(m)), poses, local);
    });
    // Number the meshes' surfaces one after another, and list each surface's triangles.
    std::vector<std::uint32_t> base(scene.meshes.size() + 1, 0);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) base[m + 1] = base[m] + counts[m];
    m_first.assign(std::size_t(base.back()) + 1, 0);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (std::size_t t = firstTriangle[m]; t < firstTriangle[m + 1]; ++t)
            if (m_surfaceOf[t] != kNone) m_surfaceOf[t] += base[m], ++m_first[m_surfaceOf[t] + 1];
    std::partial_sum(m_first.begin(), m_first.end(), m_first.begin());
    m_triangles.resize(m_first.back());
    std::vector<std::uint32_t> next(m_first.begin(), m_first.end() - 1);
    for (std::uint32_t t = 0; t < m_surfaceOf.size(); ++t)
        if (m_surfaceOf[t] != kNone) m_triangles[next[m_surfaceOf[t]]++] = t;
}

}  // namespace streak::exposure
