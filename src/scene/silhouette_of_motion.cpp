#include "scene/silhouette_of_motion.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

namespace streak {

SilhouetteOfMotion::SilhouetteOfMotion(std::span<const glm::uvec3> triangles, int subdivisions)
    : m_subdivisions(subdivisions),
      m_triangles(triangles.begin(), triangles.end()),
      m_history(triangles.size() * std::size_t(subdivisions)),
      m_lastEdge(triangles.size()),
      m_updatesSince(triangles.size(), kNever) {}

ShellEdge SilhouetteOfMotion::edgeAt(std::array<std::uint32_t, 2> vertices, std::span<const glm::vec3> positions,
                                     std::span<const glm::vec3> normals) const {
    return {vertices, {positions[vertices[0]], positions[vertices[1]]}, {normals[vertices[0]], normals[vertices[1]]}};
}

std::size_t SilhouetteOfMotion::update(std::span<const glm::vec3> previous, std::span<const glm::vec3> positions,
                                       std::span<const glm::vec3> facingNormals, std::span<const glm::vec3> normals) {
    m_updateIndex = (m_updateIndex + 1) % m_subdivisions;
    ++m_numUpdates;
    m_facing.resize(positions.size());
    tbb::parallel_for(std::size_t(0), positions.size(), [&](std::size_t v) {
        const float d = glm::dot(facingNormals[v], positions[v] - previous[v]);
        m_facing[v] = d > 0.0f ? 1 : d < 0.0f ? -1 : 0;
    });
    std::atomic<std::size_t> numOnSilhouette{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_triangles.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        std::size_t found = 0;
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            const glm::uvec3& tri = m_triangles[t];
            int forward = 0, backward = 0, forwardCorner = 0;
            for (int c = 0; c < 3; ++c) {
                const int f = m_facing[tri[c]];
                if (f > 0) ++forward, forwardCorner = c;
                if (f < 0) ++backward;
            }
            Entry& entry = m_history[t * std::size_t(m_subdivisions) + std::size_t(m_updateIndex)];
            if (forward == 1 && backward == 2) {
                // The backward edge, in the polygon's winding after the forward corner.
                m_lastEdge[t] = {tri[(forwardCorner + 1) % 3], tri[(forwardCorner + 2) % 3]};
                m_updatesSince[t] = 0;
                entry = {edgeAt(m_lastEdge[t], positions, normals), true, true};
                ++found;
            } else {
                if (m_updatesSince[t] != kNever) ++m_updatesSince[t];
                entry.isOnSilhouette = false;
                entry.isRecorded = m_updatesSince[t] != kNever;
                if (entry.isRecorded) entry.edge = edgeAt(m_lastEdge[t], positions, normals);
            }
        }
        numOnSilhouette += found;
    });
    return numOnSilhouette.load();
}

void SilhouetteOfMotion::appendStrips(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, float alpha,
                                      int fade, std::vector<ShellStrip>& strips) const {
    if (m_updateIndex < 0) return;
    const int s = m_subdivisions;
    for (std::size_t t = 0; t < m_triangles.size(); ++t) {
        const std::uint32_t since = m_updatesSince[t];
        if (since == kNever || since >= std::uint32_t(fade)) continue;
        const float stripFade = 1.0f - float(since) / float(fade);
        ShellStrip strip;
        strip.triangle = std::uint32_t(t);
        strip.edges.push_back(edgeAt(m_lastEdge[t], positions, normals));
        strip.alphas.push_back(alpha * stripFade);
        int offInARow = 0;
        for (int j = 1; j <= s; ++j) {
            const Entry& entry = m_history[t * std::size_t(s) + std::size_t((m_updateIndex - (j - 1) + s) % s)];
            if (!entry.isRecorded) break;
            offInARow = entry.isOnSilhouette ? 0 : offInARow + 1;
            if (offInARow >= fade) break;
            strip.edges.push_back(entry.edge);
            strip.alphas.push_back(std::max(0.0f, alpha - float(j) * alpha / float(s)) * stripFade);
        }
        if (strip.edges.size() >= 2) strips.push_back(std::move(strip));
    }
}

}  // namespace streak
