#pragma once

#include "raster/edge_equation.h"
#include "raster/moving_triangle.h"
#include "util/simd.h"

#include <glm/vec2.hpp>

#include <array>
#include <cstddef>
#include <cstdint>

namespace streak::raster {

// EdgeBatch holds one moving triangle's three edge quadratics and its staysOutside answer at
// each of a run of samples, found together, and for a still triangle its inside test too. Each coefficient of an edge quadratic is affine in
// the sample (x, y) (MovingTriangle), so a run of samples is vector arithmetic: four lanes at
// a time through util/simd.h, with the per-sample code as its scalar twin. Every level gives
// bit-identical quadratics and answers (tested), so a box loop that asks the batch finds the
// same spans, through MovingTriangle::insideSpans given the quadratics, as one asking sample by
// sample, and does not evaluate the edges twice.
struct EdgeBatch {
    static constexpr int kCapacity = 32;  ///< samples per batch: a box loop asks in runs of this many
    int count = 0;
    std::array<std::array<Quadratic, 3>, kCapacity> edges;  ///< MovingTriangle::edgeFunctions at each sample
    std::array<std::uint8_t, kCapacity> staysOutside;        ///< MovingTriangle::staysOutside at each sample (0 or 1)
    std::array<std::uint8_t, kCapacity> isInsideStill;       ///< a still triangle: isInsideByEdges at each sample not staying outside
};

// Fills `batch` for the `count` (at most kCapacity) samples ndc[0], ndc[stride], ... of the
// triangle in orientation `orientation` (as staysOutside takes it), at `level`.
void evaluateEdgeBatch(const MovingTriangle& moving, int orientation, const glm::dvec2* ndc, std::ptrdiff_t stride, int count,
                       EdgeBatch& batch, simd::Level level);

// MovingTriangle::insideSpans at sample i of the batch (at ndc), from what the batch found: a
// still triangle's inside test, a moving one's quadratics.
inline int insideSpansOf(const MovingTriangle& moving, const EdgeBatch& batch, int i, const glm::dvec2& ndc, double zNear, bool checkNearPlane,
                         std::array<double, 8>& bounds, RootCaseCounts* rootCases = nullptr) {
    if (moving.isStill()) return moving.stillSpansOf(batch.isInsideStill[std::size_t(i)] != 0, ndc, zNear, checkNearPlane, bounds, rootCases);
    return moving.insideSpans(batch.edges[std::size_t(i)], ndc, zNear, checkNearPlane, bounds, rootCases);
}

}  // namespace streak::raster
