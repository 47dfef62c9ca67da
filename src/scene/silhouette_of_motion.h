#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace streak {

// A mesh edge as one SoM update saw it: its two vertices (mesh indices, for their uvs and
// colours) with their world positions and normals at that update.
struct ShellEdge {
    std::array<std::uint32_t, 2> vertices{};
    std::array<glm::vec3, 2> positions{};
    std::array<glm::vec3, 2> normals{};
};

// One polygon's quad strip of the blur shell (Jones 2004, section 3.2.5): its mesh edge at the
// current pose first, then its history from the newest update to the oldest, each edge with its
// alpha (the strip's fade included). Consecutive edges bound one quad.
struct ShellStrip {
    std::uint32_t triangle = 0;  ///< the polygon, an index into the mesh's triangles
    std::vector<ShellEdge> edges;
    std::vector<float> alphas;   ///< one per edge
};

// SilhouetteOfMotion is the per-polygon state of Jones' method for one mesh (section 3.2.3): a
// circular history of `subdivisions` entries per polygon, the polygon's last SoM edge and the
// updates since it had one, and the global update index.
//
// An update (section 3.2.4) classifies each vertex by the sign of normal . (position - previous
// position): forward when positive, backward when negative (a vertex that did not move is
// neither). A polygon with one forward and two backward vertices records its backward edge (the
// thesis' rule; the opposite rule is as valid, this one is used throughout). Every other polygon
// clears its flag, counts one more update since its last SoM edge, and records that edge's
// vertices at their current pose (hole patching).
class SilhouetteOfMotion {
public:
    static constexpr std::uint32_t kNever = std::numeric_limits<std::uint32_t>::max();

    SilhouetteOfMotion(std::span<const glm::uvec3> triangles, int subdivisions);

    // One SoM update from the previous update's positions to the current positions (mesh vertex
    // order): vertices face by facingNormals, edges are recorded with `normals` (for shading).
    // Returns the number of polygons with an edge on the SoM.
    std::size_t update(std::span<const glm::vec3> previous, std::span<const glm::vec3> positions,
                       std::span<const glm::vec3> facingNormals, std::span<const glm::vec3> normals);
    std::size_t update(std::span<const glm::vec3> previous, std::span<const glm::vec3> positions,
                       std::span<const glm::vec3> normals) {
        return update(previous, positions, normals, normals);
    }

    // Appends the strip of every polygon whose updates since its last SoM edge are fewer than
    // `fade`, built at the current pose (the last update's positions and normals): vertex alpha
    // falls by alpha / subdivisions per edge and the whole strip by updatesSince / fade; a strip
    // stops at an entry never recorded, at `fade` entries in a row off the SoM, or after
    // subdivisions + 1 edges.
    void appendStrips(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, float alpha, int fade,
                      std::vector<ShellStrip>& strips) const;

    int subdivisions() const { return m_subdivisions; }
    std::size_t numUpdates() const { return m_numUpdates; }
    // Updates since the polygon last had an SoM edge (0: it has one now); kNever if it never had.
    std::uint32_t updatesSinceSilhouette(std::uint32_t triangle) const { return m_updatesSince[triangle]; }

private:
    struct Entry {
        ShellEdge edge;
        bool isRecorded = false;      ///< false: cleared (nothing to connect to)
        bool isOnSilhouette = false;  ///< the flag: the edge was on the SoM at this update
    };

    ShellEdge edgeAt(std::array<std::uint32_t, 2> vertices, std::span<const glm::vec3> positions,
                     std::span<const glm::vec3> normals) const;

    int m_subdivisions;
    std::vector<glm::uvec3> m_triangles;
    std::vector<Entry> m_history;                          ///< triangle-major, subdivisions per polygon
    std::vector<std::array<std::uint32_t, 2>> m_lastEdge;  ///< the polygon's last SoM edge
    std::vector<std::uint32_t> m_updatesSince;             ///< kNever: no SoM edge yet
    std::vector<std::int8_t> m_facing;                     ///< per vertex: +1 forward, -1 backward, 0 neither
    int m_updateIndex = -1;                                ///< the newest entry's slot
    std::size_t m_numUpdates = 0;
};

}  // namespace streak
