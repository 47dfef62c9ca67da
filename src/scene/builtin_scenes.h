#pragma once

#include "scene/scene.h"
#include "util/options.h"

#include <span>
#include <string_view>

namespace streak {

struct BuiltinSceneInfo {
    std::string_view name;
    std::string_view description;  ///< one line, with the options the scene takes
};

// The procedural scenes streak ships: deterministic, no files. `streak scenes` lists them.
std::span<const BuiltinSceneInfo> builtinScenes();

// Builds builtin scene `name` with its options (e.g. n=2000 for cubes). Throws Error for an
// unknown name (listing the known ones) or an option the scene does not take.
Scene makeBuiltinScene(std::string_view name, OptionMap options);

}  // namespace streak
