#pragma once

#include <glm/vec2.hpp>

#include <array>
#include <cstddef>

namespace streak::raster {

// The convex hull of a few points (N of them) as indices into them, counter-clockwise
// from the lowest x (then lowest y); points on a hull edge are left out. Andrew's monotone chain:
// the motion path's side hulls and the swept hull both take it.
struct ConvexHull {
    std::array<int, 16> index{};  ///< the chains' work space: twice the most points taken
    int count = 0;
};
template <std::size_t N>  // 4 and 6 are built
ConvexHull convexHull(const std::array<glm::dvec2, N>& points);

}  // namespace streak::raster
