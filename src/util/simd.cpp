#include "util/simd.h"

#include <cstdlib>
#include <string_view>

namespace streak::simd {

const char* levelName(Level level) {
    switch (level) {
    case Level::scalar: return "scalar";
    case Level::sse2: return "sse2";
    case Level::avx2: return "avx2";
    }
    return "scalar";
}

bool isSupported(Level level) {
    if (level != Level::avx2) return true;  // SSE2 is baseline x86-64
#if defined(__x86_64__) || defined(__i386__)
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

// Without AVX2 the scalar twin: four lanes as two SSE2 halves, with the lanes' loads and stores,
// measured slower than it (docs/BENCHMARKS.md, "SIMD edge batches").
Level bestLevel() { return isSupported(Level::avx2) ? Level::avx2 : Level::scalar; }

Level activeLevel() {
    static const Level level = [] {
        const Level best = bestLevel();
        const char* env = std::getenv("STREAK_SIMD");
        if (!env) return best;
        const std::string_view name(env);
        if (name == "scalar") return Level::scalar;
        if (name == "sse2") return Level::sse2;
        if (name == "avx2" && isSupported(Level::avx2)) return Level::avx2;
        return best;
    }();
    return level;
}

}  // namespace streak::simd
