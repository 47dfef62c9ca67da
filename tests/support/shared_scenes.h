#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace streak::test {

// The third-party glTF sample models in ../shared/scenes (relative to the repository root):
// STREAK_SHARED_SCENES_DIR is its absolute path, set by CMake. They are not part of the
// repository, so tests that need them skip (with this message) where the folder is absent.
// (As a path joined, not strings added: GCC 12 at -O1 warns of a false -Warray-bounds in the
// inlined string concatenation.)
inline std::string sharedScene(const std::string& relative) { return (std::filesystem::path(STREAK_SHARED_SCENES_DIR) / relative).string(); }

inline bool hasSharedScenes() { return std::filesystem::is_directory(STREAK_SHARED_SCENES_DIR); }

#define STREAK_REQUIRE_SHARED_SCENES()                                                                               \
    do {                                                                                                            \
        if (!::streak::test::hasSharedScenes())                                                                     \
            GTEST_SKIP() << "the glTF sample models are not at " STREAK_SHARED_SCENES_DIR " (../shared/scenes)"; \
    } while (0)

}  // namespace streak::test
