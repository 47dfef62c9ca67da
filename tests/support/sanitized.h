#pragma once

#include <string_view>

// The Sanitized. suite (STREAK_SANITIZE) runs every CPU test under AddressSanitizer and
// UndefinedBehaviorSanitizer, about ten times slower than the optimized build. The heaviest
// tests run the same code paths on a smaller workload there (fewer cases, fewer shutter times),
// which is all the sanitizers need; their thresholds hold at either size.
namespace streak::test {

#ifdef STREAK_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// Whether a test that loops over every method runs `method` here: the sanitized copy runs the CPU
// methods only. The GL twins run in the optimized suite; under AddressSanitizer llvmpipe builds
// their programs 2.1x slower (its LLVM code generation allocates through ASan's allocator:
// motion-path-gl's cold first render 40 -> 84 s), which took two tests 106 and 129 s in a cold run here.
inline bool runsHere(std::string_view method) { return !(kSanitized && method.ends_with("-gl")); }

}  // namespace streak::test
