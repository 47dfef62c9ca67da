#pragma once

#include <algorithm>
#include <cstdint>

namespace streak {

// Deterministic randomness with no dependence on the standard library's distributions (whose
// output differs between implementations): a scene or sample pattern is the same everywhere.

// A 64-bit mix (SplitMix64 finalizer) of a value: for hashing pixel/sample indices with a seed.
inline std::uint64_t mixBits(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

inline std::uint64_t hashValues(std::uint64_t a, std::uint64_t b, std::uint64_t c = 0, std::uint64_t d = 0) {
    return mixBits(a ^ mixBits(b ^ mixBits(c ^ mixBits(d + 0x9e3779b97f4a7c15ull))));
}

// A float in [0, 1) from the top 24 bits of a hash.
inline float unitFloat(std::uint64_t bits) { return float(bits >> 40) * (1.0f / 16777216.0f); }

// The shutter time of one pixel sample in time stratum j of S: [j/S, (j+1)/S) jittered by a hash
// of the seed, the pixel (y * width + x), the sample's index in the pixel and j. Stochastic
// rasterization's per-sample time: one definition, so its CPU and GPU methods agree.
inline float stratifiedSampleTime(std::uint64_t seed, std::uint64_t pixel, int sample, int stratum, int numStrata) {
    const float jitter = unitFloat(hashValues(seed, pixel, std::uint64_t(sample), std::uint64_t(stratum)));
    return std::min((float(stratum) + jitter) / float(numStrata), 1.0f);
}

// Rng is a small sequential generator (SplitMix64) for building scenes.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : m_state(seed) {}
    std::uint64_t next() { return mixBits(m_state += 0x9e3779b97f4a7c15ull); }
    float uniform() { return unitFloat(next()); }
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

private:
    std::uint64_t m_state;
};

}  // namespace streak
