#include "exposure/closed_surfaces.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

namespace streak::exposure {

namespace {

// The closed surfaces of one mesh: per triangle (of the mesh) its surface counted within the
// mesh, or ClosedSurfaces::kNone; returns how many.
std::uint32_t meshSurfaces(const Mesh& mesh, std::uint32_t vertexOffset, std::span<const VertexArray> poses,
                           std::span<std::uint32_t> surfaceOf) {
    const std::size_t numVertices = mesh.numVertices();
    if (numVertices == 0 || poses.empty()) return 0;
    auto at = [&](int pose, std::uint32_t v) { return poses[std::size_t(pose)][vertexOffset + v]; };
    for (std::size_t k = 0; k < poses.size(); ++k)
        for (std::uint32_t v = 0; v < numVertices; ++v) {
            const glm::vec3 p = at(int(k), v);
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return 0;  // (and no order to sort by)
        }

    // Weld: vertices at one position in the first pose are one corner, if they stay together in
    // every pose (a skin or a morph may pull apart what shares a rest position); a group that
    // parts is left unwelded, which opens the surface around it.
    // (Sorted by a hash of the first pose's position, each run of equal hashes split by position.)
    auto bitsOf = [](float f) { return std::uint64_t(std::bit_cast<std::uint32_t>(f + 0.0f)); };  // (-0 as +0)
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(numVertices);
    for (std::uint32_t v = 0; v < numVertices; ++v) {
        const glm::vec3 p = at(0, v);
        const std::uint64_t h = bitsOf(p.x) * 0x9E3779B97F4A7C15ull ^ std::rotl(bitsOf(p.y) * 0xC2B2AE3D27D4EB4Full, 21) ^
                                std::rotl(bitsOf(p.z) * 0x165667B19E3779F9ull, 42);
        keyed[v] = {h, v};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> corner(numVertices);
    std::vector<std::uint8_t> isParted(numVertices, 0);  ///< per corner: its vertices part in some pose
    for (std::size_t i = 0; i < numVertices;) {
        std::size_t j = i + 1;
        while (j < numVertices && keyed[j].first == keyed[i].first) ++j;
        for (std::size_t g = i; g < j; ++g) {
            const std::uint32_t v = keyed[g].second;
            corner[v] = v;
            for (std::size_t h = i; h < g; ++h)
                if (corner[keyed[h].second] == keyed[h].second && at(0, keyed[h].second) == at(0, v)) {
                    corner[v] = keyed[h].second;
                    break;
                }
            for (std::size_t k = 1; k < poses.size(); ++k)
                if (at(int(k), v) != at(int(k), corner[v])) isParted[corner[v]] = 1;
        }
        i = j;
    }
    for (std::uint32_t v = 0; v < numVertices; ++v)
        if (isParted[corner[v]]) corner[v] = v;

    // Components of the welded corners, over the triangles that are not degenerate.
    std::vector<std::uint32_t> parent(numVertices);
    std::iota(parent.begin(), parent.end(), 0u);
    auto root = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    const std::size_t numTriangles = mesh.triangles.size();
    auto isDegenerate = [&](const glm::uvec3& c) { return c.x == c.y || c.y == c.z || c.x == c.z; };
    auto cornersOf = [&](std::size_t t) {
        const glm::uvec3 v = mesh.triangles[t];
        return glm::uvec3(corner[v.x], corner[v.y], corner[v.z]);
    };
    // Each corner's edges out (to the next corner of each triangle), as lists.
    std::vector<std::uint32_t> firstOut(numVertices + 1, 0);
    for (std::size_t t = 0; t < numTriangles; ++t) {
        const glm::uvec3 c = cornersOf(t);
        if (isDegenerate(c)) continue;
        parent[root(c.x)] = root(c.y), parent[root(c.y)] = root(c.z);
        for (int e = 0; e < 3; ++e) ++firstOut[c[e] + 1];
    }
    std::partial_sum(firstOut.begin(), firstOut.end(), firstOut.begin());
    std::vector<std::uint32_t> out(firstOut.back()), next(firstOut.begin(), firstOut.end() - 1);
    for (std::size_t t = 0; t < numTriangles; ++t) {
        const glm::uvec3 c = cornersOf(t);
        if (isDegenerate(c)) continue;
        for (int e = 0; e < 3; ++e) out[next[c[e]]++] = c[(e + 1) % 3];
    }
    // Closed and oriented: each directed edge once, and its reverse once.
    auto edgesTo = [&](std::uint32_t a, std::uint32_t b) {
        return std::count(out.begin() + firstOut[a], out.begin() + firstOut[a + 1], b);
    };
    std::vector<std::uint8_t> isOpen(numVertices, 0);  ///< per component root
    for (std::uint32_t a = 0; a < numVertices; ++a)
        for (std::uint32_t i = firstOut[a]; i < firstOut[a + 1]; ++i)
            if (edgesTo(a, out[i]) != 1 || edgesTo(out[i], a) != 1) isOpen[root(a)] = 1;

    // Positive volume at every pose, about a corner of the component (for precision).
    std::vector<std::uint32_t> id(numVertices, ClosedSurfaces::kNone);
    std::uint32_t count = 0;
    std::vector<double> volume(numVertices);
    for (std::size_t k = 0; k < poses.size(); ++k) {
        std::fill(volume.begin(), volume.end(), 0.0);
        for (std::size_t t = 0; t < numTriangles; ++t) {
            const glm::uvec3 c = cornersOf(t);
            if (isDegenerate(c)) continue;
            const std::uint32_t r = root(c.x);
            const glm::dvec3 o(at(int(k), r));
            const glm::dvec3 p0 = glm::dvec3(at(int(k), c.x)) - o, p1 = glm::dvec3(at(int(k), c.y)) - o, p2 = glm::dvec3(at(int(k), c.z)) - o;
            volume[r] += glm::dot(p0, glm::cross(p1, p2));
        }
        for (std::uint32_t v = 0; v < numVertices; ++v)
            if (root(v) == v && !(volume[v] > 0.0)) isOpen[v] = 1;
    }
    for (std::size_t t = 0; t < numTriangles; ++t) {
        const glm::uvec3 c = cornersOf(t);
        if (isDegenerate(c)) continue;
        const std::uint32_t r = root(c.x);
        if (isOpen[r]) continue;
        if (id[r] == ClosedSurfaces::kNone) id[r] = count++;
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
