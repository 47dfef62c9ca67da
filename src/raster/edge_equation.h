#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cstdint>

namespace streak::raster {

// Exact per-sample geometry in homogeneous 2D (Olano & Greer 1997): a triangle's corners as
// clip-space (x, y, w) need no division, so a sample can be evaluated at any time without
// snapping or clipping. The edge function of corners j, k at normalized device point p is
// E(p) = (c_j x c_k) . (p.x, p.y, 1); the three E, normalized to sum 1, are the
// perspective-correct barycentrics of p (the corner opposite the edge gets its E).

// Barycentrics, view depth and orientation of a triangle at one NDC point.
struct HomogeneousSample {
    glm::dvec3 bary{0.0};    ///< perspective-correct; sum 1
    double viewDepth = 0.0;  ///< interpolated clip w (> 0 in front of the camera)
    bool isValid = false;    ///< false for a triangle seen edge-on (all E sum to 0)
    bool isFrontFacing = true;  ///< counter-clockwise in NDC (with all w > 0)
};

HomogeneousSample evaluateHomogeneous(const std::array<glm::vec4, 3>& clip, const glm::dvec2& ndc);
// The same from the corners' clip-space (x, y, w).
HomogeneousSample evaluateHomogeneousXyw(const std::array<glm::dvec3, 3>& xyw, const glm::dvec2& ndc);

// Whether the sample at ndc is inside a triangle whose edge vectors are edges[e] (edge e of
// corners e, e + 1: c_e x c_(e+1)) and whose edge functions there are values[e] = edges[e] . p:
// all edges of one sign (either orientation), and an edge within float precision of zero goes
// by the rasterizer's top-left rule. Moving triangles of every order share it.
// "Within float precision": |value| <= kOnEdgeTolerance (|e.x x| + |e.y y| + |e.z|).
inline constexpr double kOnEdgeTolerance = 1e-6;
bool isInsideByEdges(const std::array<glm::dvec3, 3>& edges, const glm::dvec2& ndc, const std::array<double, 3>& values);

// A quadratic q(u) = a u^2 + b u + c.
struct Quadratic {
    double a = 0.0, b = 0.0, c = 0.0;
    double operator()(double u) const { return (a * u + b) * u + c; }
    // The largest value on [0, 1]: at an end, or at the vertex of a downward parabola.
    double maxOnUnitInterval() const {
        double m = std::max((*this)(0.0), (*this)(1.0));
        if (a < 0.0) {
            const double u = -b / (2.0 * a);
            if (u > 0.0 && u < 1.0) m = std::max(m, (*this)(u));
        }
        return m;
    }
};

// The edge function of a moving edge as a vector quadratic: (a u^2 + b u + c) . p for
// p = (x, y, 1), from its corners' (x, y, w) at u = 0 and their change to u = 1.
struct MovingEdge {
    glm::dvec3 a{0.0}, b{0.0}, c{0.0};
};
MovingEdge movingEdge(const glm::dvec3& p0, const glm::dvec3& dp, const glm::dvec3& q0, const glm::dvec3& dq);

// Gribel et al. 2010: with corners moving linearly in clip space, c(u) = c0 + u (c1 - c0), the
// edge function of a moving edge at a fixed sample is quadratic in u:
// E(u) = ((a0 + u da) x (b0 + u db)) . p.
Quadratic movingEdgeFunction(const glm::vec4& a0, const glm::vec4& a1, const glm::vec4& b0, const glm::vec4& b1,
                             const glm::dvec2& ndc);

// How many quadratics were solved, by case (for --stats).
struct RootCaseCounts {
    std::int64_t constant = 0;    ///< a = b = 0: no root (or identically zero)
    std::int64_t linear = 0;      ///< a negligible next to b and c: one root, -c / b
    std::int64_t noRealRoot = 0;  ///< negative discriminant
    std::int64_t doubleRoot = 0;  ///< zero discriminant: the sample touches the edge at one instant
    std::int64_t twoRoots = 0;
    void add(const RootCaseCounts& o) {
        constant += o.constant, linear += o.linear, noRealRoot += o.noRealRoot, doubleRoot += o.doubleRoot, twoRoots += o.twoRoots;
    }
};

// Real roots of q in ascending order (0, 1 or 2 of them; a double root counts once). Uses the
// cancellation-free form (Numerical Recipes 5.6) and handles a = 0 (linear) and a = b = 0.
// Counts the case in *counts when given.
int solveQuadratic(const Quadratic& q, double roots[2], RootCaseCounts* counts = nullptr);

// NDC position of a fixed-point raster sample (x right, y up).
glm::dvec2 ndcFromRaster(double rasterX, double rasterY, int width, int height);

}  // namespace streak::raster
