#pragma once

#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "util/stats.h"

#include <string>

namespace streak {

// Loads a scene from its spec: "builtin:NAME" or "builtin:NAME?key=value&..." for the built-in
// scenes, the path of a .gltf or .glb file, or of an OBJ or PLY mesh or sequence, loaded with `gltf` (which the built-in scenes
// ignore). Throws Error naming the spec when it cannot (unknown scene, bad option, missing,
// broken or unsupported file). The scene is validated (validateScene) by the caller, which
// counts what was skipped; loaders may add their own counters to `stats`.
Scene loadScene(const std::string& spec, const GltfOptions& gltf = {}, RenderStats* stats = nullptr);

// True when the spec names a scene file with a clock and a camera of its own to frame: glTF, or
// an OBJ or PLY mesh or numbered sequence (scene/mesh_sequence.h), which take the glTF options.
bool isSceneFileSpec(const std::string& spec);
// True when the spec names a glTF file (by its extension, .gltf or .glb, in any case).
bool isGltfSpec(const std::string& spec);

}  // namespace streak
