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

HomogeneousSample MovingTriangle::fromEdges(const std::array<glm::dvec3, 3>& edges, const glm::dvec3& w, const glm::dvec2& ndc,
                                             bool isFront) {
    const glm::dvec3 p(ndc, 1.0);
    const glm::dvec3 e(glm::dot(edges[0], p), glm::dot(edges[1], p), glm::dot(edges[2], p));
    const double sum = e.x + e.y + e.z;
    HomogeneousSample s;
    s.isFrontFacing = isFront;
    if (sum == 0.0 || !std::isfinite(sum)) return s;
    s.bary = e / sum;
    s.viewDepth = glm::dot(s.bary, w);
    s.isValid = true;
    return s;
}

HomogeneousSample MovingTriangle::sample(double u, const glm::dvec2& ndc) const {
    const std::array<glm::dvec3, 3> edges{edgeVector(1, u), edgeVector(2, u), edgeVector(0, u)};
    const glm::dvec3 w(corner(0, u).z, corner(1, u).z, corner(2, u).z);
    return fromEdges(edges, w, ndc, glm::dot(corner(0, u), edges[0]) > 0.0);
}

}  // namespace streak::raster
