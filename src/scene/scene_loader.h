#pragma once

#include "scene/scene.h"

#include <string>

namespace streak {

// Loads a scene from its spec: "builtin:NAME" or "builtin:NAME?key=value&..." for the built-in
// scenes. Throws Error naming the spec when it cannot (unknown scene, bad option, missing or
// unsupported file). The scene is validated (validateScene) by the caller, which counts what
// was skipped.
Scene loadScene(const std::string& spec);

}  // namespace streak
