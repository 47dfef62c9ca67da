#pragma once

#include <glm/vec3.hpp>

#include <algorithm>

namespace streak {

// Barycentrics held to their triangle: negative weights dropped, the rest renormalised. A point
// outside the triangle then names the nearest part of it along the dropped corners, which is what
// a shading or a texture tap held to one triangle reads (never the texels of a neighbour in an
// atlas that the extrapolated barycentrics would reach).
inline glm::dvec3 clampedBarycentrics(const glm::dvec3& b) {
    if (b.x >= 0.0 && b.y >= 0.0 && b.z >= 0.0) return b;
    const glm::dvec3 c(std::max(b.x, 0.0), std::max(b.y, 0.0), std::max(b.z, 0.0));
    const double sum = c.x + c.y + c.z;
    return sum > 0.0 ? c / sum : glm::dvec3(1.0 / 3.0);
}

}  // namespace streak
