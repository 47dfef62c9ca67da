#include "scene/motion.h"

#include "raster/bernstein.h"

#include <algorithm>
#include <cassert>
#include <vector>

namespace streak {

MotionWeights motionWeights(int numKeys, MotionInterpolation interpolation, float t, int pieces) {
    assert(numKeys >= 2);
    t = std::clamp(t, 0.0f, 1.0f);
    MotionWeights w;
    if (interpolation == MotionInterpolation::PiecewiseLinear || numKeys == 2) {
        const float x = t * float(numKeys - 1);
        const int segment = std::min(int(x), numKeys - 2);
        const float u = x - float(segment);
        w.first = segment;
        w.count = 2;
        w.weights[0] = 1.0f - u;
        w.weights[1] = u;
        return w;
    }
    assert(pieces >= 1 && (numKeys - 1) % pieces == 0 && (numKeys - 1) / pieces < MotionWeights::kMaxKeys);
    // The piece holding t, and t within it (one piece: t itself, to the bit).
    const int n = (numKeys - 1) / pieces;
    const float x = t * float(pieces);
    const int piece = std::min(int(x), pieces - 1);
    const float u = x - float(piece);
    // Bernstein basis of degree n, built by the de Casteljau recurrence on the weights
    // themselves: stable for all u in [0,1], unlike powers of u and (1-u).
    w.first = piece * n;
    w.count = n + 1;
    w.weights[0] = 1.0f;
    for (int degree = 1; degree <= n; ++degree) {
        for (int i = degree; i >= 0; --i) {
            const float fromLeft = i > 0 ? w.weights[i - 1] * u : 0.0f;
            const float stay = i < degree ? w.weights[i] * (1.0f - u) : 0.0f;
            w.weights[i] = fromLeft + stay;
        }
    }
    return w;
}

void bezierControlPointsThroughSamples(std::span<glm::vec3> keys, int numKeys) {
    assert(numKeys >= 2 && numKeys <= 4 && keys.size() % std::size_t(numKeys) == 0);
    const std::size_t n = keys.size() / std::size_t(numKeys);
    const auto weights = raster::bezierThroughSamples(numKeys - 1);
    const std::vector<glm::vec3> samples(keys.begin(), keys.end());
    for (int j = 0; j < numKeys; ++j)
        for (std::size_t v = 0; v < n; ++v) {
            glm::vec3 p(0.0f);
            for (int i = 0; i < numKeys; ++i) p += float(weights[std::size_t(j)][std::size_t(i)]) * samples[std::size_t(i) * n + v];
            keys[std::size_t(j) * n + v] = p;
        }
}

std::vector<glm::vec3> bezierControlPointsFittingSamples(std::span<const glm::vec3> samples, int numSamples, int order) {
    assert(numSamples > order && samples.size() % std::size_t(numSamples) == 0);
    const std::size_t n = samples.size() / std::size_t(numSamples);
    const std::vector<double> weights = raster::bezierFittingSamples(order, numSamples);
    std::vector<glm::vec3> control(std::size_t(order + 1) * n, glm::vec3(0.0f));
    for (int j = 0; j <= order; ++j)
        for (int i = 0; i < numSamples; ++i) {
            const float w = float(weights[std::size_t(j * numSamples + i)]);
            for (std::size_t v = 0; v < n; ++v) control[std::size_t(j) * n + v] += w * samples[std::size_t(i) * n + v];
        }
    return control;
}

}  // namespace streak
