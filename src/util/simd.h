#pragma once

#include <cstdint>

namespace streak::simd {

// streak's SIMD layer: four double lanes as a GCC/Clang vector extension, and the instruction
// set a batch kernel runs with, chosen at run time. What is installed is built for baseline
// x86-64 (never -march=native): a kernel is written once as an always-inline template on
// these types and instantiated in two entry points, one with the default target (each
// four-lane operation becomes two SSE2 ones) and one with __attribute__((target("avx2"))),
// called only where the CPU has AVX2. Neither enables FMA, so the compiler cannot contract a
// multiply and an add: every lane rounds exactly as the scalar code with the same expression
// does, and a kernel's scalar twin (the plain per-sample code) gives identical results.

// The helpers below are always inlined, so no four-lane value crosses a call: GCC's note that
// passing one changes the ABI without AVX does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

using Double4 = double __attribute__((vector_size(32)));
using Mask4 = std::int64_t __attribute__((vector_size(32)));  ///< lane comparisons: all ones or zero

// |v| lane by lane, by clearing the sign bit (std::abs exactly, signed zeros and NaN included).
[[gnu::always_inline]] inline Double4 abs(Double4 v) {
    return (Double4)((Mask4)v & Mask4{INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX});
}
// Lanes of a where mask is set, else of b.
[[gnu::always_inline]] inline Double4 select(Mask4 mask, Double4 a, Double4 b) {
    return (Double4)(((Mask4)a & mask) | ((Mask4)b & ~mask));
}

#pragma GCC diagnostic pop

// How a batch kernel runs: `scalar` is its twin, the plain code one sample at a time.
enum class Level { scalar, sse2, avx2 };

const char* levelName(Level level);
// The fastest level on this CPU: AVX2 where __builtin_cpu_supports says so, else scalar (the
// SSE2 build of a kernel is kept to check it on every x86-64, not to run it: two-lane halves
// did not pay for their loads and stores).
Level bestLevel();
// bestLevel(), or another where the environment variable STREAK_SIMD says so ("scalar",
// "sse2"; "avx2" only where supported): to measure or check the twins against each other on
// one machine. Read once.
Level activeLevel();
// Whether this CPU can run `level`.
bool isSupported(Level level);

}  // namespace streak::simd
