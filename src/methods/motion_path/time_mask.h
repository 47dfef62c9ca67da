#pragma once

#include "scene/shutter.h"

#include <array>
#include <bit>
#include <cstdint>

namespace streak::motion_path {

// TimeMask is a set of n time slices of the shutter (Hong & Oh 2017, section 3.4): bit i stands
// for [i/n, (i+1)/n), n = 32, 64, 128 or 256 (at most kMaxBits). Visibility over time becomes
// bitwise logic: visible = current & ~accumulated.
class TimeMask {
public:
    static constexpr int kMaxBits = 256;

    // The slices whose centres (i + 1/2)/n lie in [t0, t1): |count/n - (t1 - t0)| <= 1/n.
    static TimeMask span(float t0, float t1, int numBits);
    static TimeMask full(int numBits) { return span(0.0f, 1.0f, numBits); }
    // The slices of a row's exposure (not of time) that [t0, t1] covers: under a shutter curve
    // or a rolling window every slice still weighs 1/n (span() itself for the identity window).
    static TimeMask exposed(float t0, float t1, const ShutterWindow& window, int numBits) {
        return window.isIdentity() ? span(t0, t1, numBits) : span(window.exposureAt(t0), window.exposureAt(t1), numBits);
    }

    TimeMask operator|(const TimeMask& o) const { return combine(o, [](std::uint64_t a, std::uint64_t b) { return a | b; }); }
    TimeMask operator&(const TimeMask& o) const { return combine(o, [](std::uint64_t a, std::uint64_t b) { return a & b; }); }
    // this & ~o: the slices of this that o does not cover.
    TimeMask minus(const TimeMask& o) const { return combine(o, [](std::uint64_t a, std::uint64_t b) { return a & ~b; }); }
    TimeMask& operator|=(const TimeMask& o) { return *this = *this | o; }
    bool operator==(const TimeMask&) const = default;

    int count() const {
        int n = 0;
        for (std::uint64_t w : m_words) n += std::popcount(w);
        return n;
    }
    bool isEmpty() const { return (m_words[0] | m_words[1] | m_words[2] | m_words[3]) == 0; }
    bool test(int bit) const { return (m_words[bit >> 6] >> (bit & 63)) & 1u; }
    void set(int bit) { m_words[bit >> 6] |= std::uint64_t(1) << (bit & 63); }

private:
    template <class Op>
    TimeMask combine(const TimeMask& o, Op op) const {
        TimeMask r;
        for (int i = 0; i < 4; ++i) r.m_words[i] = op(m_words[i], o.m_words[i]);
        return r;
    }

    std::array<std::uint64_t, 4> m_words{};  ///< bit i in word i/64; bits >= n stay zero
};

}  // namespace streak::motion_path
