#pragma once

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

}  // namespace streak::test
