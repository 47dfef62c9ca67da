#include "raster/moving_triangle.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace streak::raster {

MovingTriangle::MovingTriangle(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close) {
    for (int i = 0; i < 3; ++i) {
        m_corner[i] = {double(open[i].x), double(open[i].y), double(open[i].w)};
        m_delta[i] = glm::dvec3(double(close[i].x), double(close[i].y), double(close[i].w)) - m_corner[i];
    }
    for (int e = 0; e < 3; ++e) {
        const int f = (e + 1) % 3;
        const MovingEdge edge = movingEdge(m_corner[e], m_delta[e], m_corner[f], m_delta[f]);
        m_a[e] = edge.a, m_b[e] = edge.b, m_c[e] = edge.c;
    }
}

HomogeneousSample MovingTriangle::sample(double u, const glm::dvec2& ndc) const {
    const glm::dvec3 p(ndc, 1.0);
    const glm::dvec3 e(glm::dot(edgeVector(1, u), p), glm::dot(edgeVector(2, u), p), glm::dot(edgeVector(0, u), p));
    const double sum = e.x + e.y + e.z;
    HomogeneousSample s;
    s.isFrontFacing = isFrontFacing(u);
    if (sum == 0.0 || !std::isfinite(sum)) return s;
    s.bary = e / sum;
    s.viewDepth = s.bary.x * corner(0, u).z + s.bary.y * corner(1, u).z + s.bary.z * corner(2, u).z;
    s.isValid = true;
    return s;
}

}  // namespace streak::raster
