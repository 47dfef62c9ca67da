#pragma once

#include "util/random.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <array>

namespace streak::test {

// The NDC corners of a moving triangle's segment at time u (clip space is linear in u).
inline std::array<glm::dvec2, 3> poseAt(const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, double u) {
    std::array<glm::dvec2, 3> p;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec4 c = glm::mix(glm::dvec4(open[i]), glm::dvec4(close[i]), u);
        p[i] = glm::dvec2(c.x, c.y) / c.w;
    }
    return p;
}

// Point k of a swept bound's test (SweptHull, SweptPieces): even k anywhere in [-1, 1]^2; odd k
// on an edge of the pose at a random time (isOnEdge set), every other one of those nudged by
// about the on-edge tolerance, and every tenth beyond a corner along its edge, where the
// tolerance reaches furthest.
inline glm::dvec2 sweptTestPoint(Rng& rng, const std::array<glm::vec4, 3>& open, const std::array<glm::vec4, 3>& close, int k, bool& isOnEdge) {
    glm::dvec2 p(rng.uniform(-1, 1), rng.uniform(-1, 1));
    isOnEdge = k % 2 == 1;
    if (!isOnEdge) return p;
    const std::array<glm::dvec2, 3> pose = poseAt(open, close, rng.uniform(0, 1));
    const int e = k % 3;
    p = pose[e] + double(rng.uniform(0, 1)) * (pose[(e + 1) % 3] - pose[e]);
    if (k % 4 == 3) p += glm::dvec2(rng.uniform(-1, 1), rng.uniform(-1, 1)) * 1e-6;
    if (k % 10 == 5) {
        const glm::dvec2 out = pose[e] - pose[(e + 1) % 3];
        p = pose[e] + out * (1e-6 * double(rng.uniform(0, 4)) / glm::length(out));
    }
    return p;
}

}  // namespace streak::test
