# The standard and third-party headers that most of the library's files parse before their own
# code (counted with -H over src/: <cmath> in 149 of 97 files' include trees, <vector> 82,
# GLM's vectors, TBB's parallel_for...). Precompiled once per build and reused by every layer's
# library, they take about a second off each file's compile, in each of the three builds a
# CI run makes (optimized, sanitized, fuzz). Only headers from outside streak go here, so a
# file that forgets one of streak's own includes still fails to build. Included by
# src/CMakeLists.txt and tests/fuzz/standalone/CMakeLists.txt.
set(STREAK_LIBRARY_PCH_HEADERS
  <algorithm> <array> <atomic> <cassert> <chrono> <cmath> <cstddef> <cstdint> <functional> <map>
  <memory> <optional> <set> <span> <string> <thread> <utility> <vector>
  <glm/vec2.hpp> <glm/vec3.hpp> <glm/vec4.hpp> <glm/geometric.hpp> <glm/gtc/quaternion.hpp>
  <tbb/blocked_range.h> <tbb/enumerable_thread_specific.h> <tbb/parallel_for.h>)
