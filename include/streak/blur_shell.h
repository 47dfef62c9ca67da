#pragma once

// The blur shell (Jones 2004) as geometry: the trail a mesh leaves over [T - length, T] as
// alpha-faded quad strips, to write out and look at from any angle (`streak shell`).

#include "streak/scene.h"

#include <cstddef>
#include <map>
#include <string>

namespace streak::api {

// The trail the shell options (blur-shell's: length, subdivisions, alpha, fade, facing) need:
// load the scene with it (LoadOptions::trail). Throws Error for an option the shell does not take.
Trail blurShellTrail(const std::map<std::string, std::string>& options);

// The mesh at the trail's end and its shell, with the figures of the build.
struct BlurShell {
    Scene scene;
    std::size_t strips = 0;
    std::size_t triangles = 0;          ///< of the shell alone
    std::size_t silhouetteEdges = 0;    ///< polygons on the silhouette of motion at the last update
};
BlurShell blurShell(const Scene& trail, const std::map<std::string, std::string>& options);

}  // namespace streak::api
