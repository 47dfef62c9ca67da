#pragma once

#include "raster/swept_hull.h"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <array>

namespace streak::raster {

// SweptPieces bounds where a moving triangle can cover a sample when SweptHull finds no hull
// for its whole segment: the triangle turns over somewhere in it (or is too sharp). The segment
// is cut into kPieces equal pieces of u. A piece whose triangle keeps its orientation gets its
// own SweptHull; one where it turns over gets the convex hull of its six projected end corners
// (the triangle lies in it over the piece, see SweptHull), widened by kBoxMargin
// (SweptHull::buildAround), or where those six lie on a line their NDC box, widened as much. A
// row's range is the x range of every piece it crosses. A long segment (a whole shutter of
// camera travel) then visits the band the triangle sweeps while it turns over, not its motion
// box. (Until stop 64 such a piece took its box: a dense sphere's silhouette triangles, tiny
// and turning over while a camera pan carries them 47 pixels, sent 45% of the dense move's
// solved samples through their boxes, 10% of them covered.)
//
// What a piece's bound leaves out, like the motion box itself, is the reach along the line a
// triangle collapses onto while it turns over: insideSpans's on-edge tolerance accepts samples
// on that line for about a millionth of the segment (an on-edge artefact, not coverage).
class SweptPieces {
public:
    static constexpr int kPieces = 4;
    static constexpr double kBoxMargin = 1e-4;  ///< NDC: 25 times the on-edge tolerance's reach

    // Returns false, leaving no bound, when a corner is not in front of the eye at an end.
    bool build(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close);
    // The union of the pieces' x ranges on the sample row at height y (as SweptHull::rowRange).
    bool rowRange(double y, double& xLo, double& xHi) const;
    double area() const { return m_area; }  ///< NDC: the pieces' hulls and boxes together
    int numHulls() const;                   ///< pieces whose triangle keeps its orientation (SweptHull::build)
    int numTurning() const;                 ///< pieces where it turns over (or is too sharp), bounded by buildAround's hull or a box

private:
    std::array<SweptHull, kPieces> m_hull;                ///< a piece's hull, where it has one
    std::array<glm::dvec2, kPieces> m_boxLo{}, m_boxHi{};  ///< else its widened box
    std::array<bool, kPieces> m_hasHull{};                ///< bounded by m_hull (either build)
    std::array<bool, kPieces> m_turns{};                  ///< SweptHull::build found no hull
    double m_area = 0.0;
    bool m_isBuilt = false;
};

}  // namespace streak::raster
