#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace streak {

// How a vertex moves between its K key poses over the shutter t in [0,1]. Keys are uniformly
// spaced in t. K = 2 is linear motion in either mode.
enum class MotionInterpolation : std::uint8_t {
    PiecewiseLinear,  ///< K-1 linear segments through the keys
    // P Bezier curves of degree n = (K-1)/P, one per P-th of the shutter, with the keys as
    // control points; piece p takes keys p n ... p n + n, so neighbours share their joint key and
    // the path is continuous. P = 1 (the default) is one curve of degree K-1.
    Bezier,
};

// MotionWeights is the linear combination of key poses that gives a vertex at one time:
// position(t) = sum_i weights[i] * key[first + i]. Both interpolations are linear in the keys,
// so the same weights move positions, normals and (since projection is linear in homogeneous
// coordinates) clip-space positions alike.
struct MotionWeights {
    static constexpr int kMaxKeys = 16;  ///< highest Bezier degree + 1 streak evaluates

    int first = 0;  ///< first key used
    int count = 0;  ///< number of keys used
    std::array<float, kMaxKeys> weights{};

    template <class T>
    T apply(const T* keys) const {
        T sum = keys[first] * weights[0];
        for (int i = 1; i < count; ++i) sum += keys[first + i] * weights[i];
        return sum;
    }
    // Keys of one vertex stored key-major with a stride (Mesh::positions layout).
    template <class T>
    T apply(const T* keys, std::size_t stride) const {
        T sum = keys[std::size_t(first) * stride] * weights[0];
        for (int i = 1; i < count; ++i) sum += keys[std::size_t(first + i) * stride] * weights[i];
        return sum;
    }
};

// The weights for numKeys keys at shutter time t (clamped to [0,1]), Bezier keys in `pieces`
// pieces. Precondition: numKeys >= 2; for Bezier, pieces divides numKeys - 1 and the degree
// (numKeys - 1) / pieces is below MotionWeights::kMaxKeys.
MotionWeights motionWeights(int numKeys, MotionInterpolation interpolation, float t, int pieces = 1);

// Replaces samples of curves at the key times (key-major: numKeys blocks of equal size, as
// Mesh::positions) by the control points of the Bezier curves of order numKeys - 1 through
// them (raster::bezierThroughSamples). Linear in the samples, so it converts positions and
// normals alike. numKeys <= 4.
void bezierControlPointsThroughSamples(std::span<glm::vec3> keys, int numKeys);

// The control points (order + 1 blocks) of the Bezier curves of that order fitted by least
// squares to numSamples blocks of samples at evenly spaced times (raster::bezierFittingSamples).
std::vector<glm::vec3> bezierControlPointsFittingSamples(std::span<const glm::vec3> samples, int numSamples, int order);

// Shutter time of key k of numKeys (uniform spacing).
inline float keyTime(int k, int numKeys) { return float(k) / float(numKeys - 1); }

}  // namespace streak
