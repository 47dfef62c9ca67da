#pragma once

#include "scene/flat_geometry.h"

#include <cstdint>
#include <span>
#include <vector>

namespace streak::exposure {

// Closed surfaces: where a double-sided triangle's back face can never be seen.
//
// Along a ray from an eye outside a closed, consistently oriented surface, the surface's winding
// number starts at 0, rises by one at each crossing through a face turned towards the eye (in)
// and falls by one at each through a face turned away (out). So a ray reaches a face turned
// away only after it has passed one turned towards it, nearer, unless the ray is then in a
// region of negative winding, which only a surface turned inside out through itself has (not
// looked for; `--option closed-cull=0` keeps every back face). An opaque surface therefore
// hides its own back faces from an eye outside it, double-sided material or not: an exact
// method may drop a segment that faces away all its time, as it drops a single-sided one, and
// on a closed mesh that is about half of them (a dense mesh of spheres, a morphing wave).
// Cycles, which renders both sides, shows the same image.
//
// ClosedSurfaces finds them in a frame's double-sided meshes (single-sided ones drop their back
// faces already), per mesh: triangles joined across their edges whose corners, welded where
// they share a position at every pose, give each directed edge once and its reverse once (a
// closed, oriented surface; degenerate triangles left out; shells touching at a corner are
// separate), whose material is opaque (not blended, not masked: a cut-out would open it) and
// whose signed volume is positive at every pose (its front faces point outwards; between two
// poses, where the volume is a cubic in time, it is not measured: only a surface passing
// through itself inside out could turn it negative there). Which of them a frame may cull also needs the near plane clear
// of the surface all the shutter (SegmentedGeometry): a surface the near plane cuts shows its
// inside through the cut, and a surface around the eye reaches behind it, so where the near
// plane is clear the eye is outside.
class ClosedSurfaces {
public:
    static constexpr std::uint32_t kNone = ~0u;

    // `poses`: the flat geometry's vertices at one or more times (the segment ends), every one
    // of which must keep a surface's welded corners together and its volume positive.
    ClosedSurfaces(const FlatGeometry& flat, std::span<const VertexArray> poses);

    std::uint32_t count() const { return std::uint32_t(m_first.size()) - 1; }
    // The closed surface a triangle is on, or kNone.
    std::uint32_t surfaceOf(std::uint32_t triangle) const { return m_surfaceOf[triangle]; }
    // The triangles of surface s.
    std::span<const std::uint32_t> trianglesOf(std::uint32_t s) const {
        return std::span<const std::uint32_t>(m_triangles).subspan(m_first[s], m_first[s + 1] - m_first[s]);
    }

private:
    std::vector<std::uint32_t> m_surfaceOf;  ///< per triangle
    std::vector<std::uint32_t> m_triangles;  ///< surface by surface
    std::vector<std::uint32_t> m_first;      ///< per surface, into m_triangles; one more at the end
};

}  // namespace streak::exposure
