#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// The blur shell (Jones 2004): not a shutter average but a trail of geometry. Over the trail
// (the shutter; a glTF scene is loaded over [T - length, T], T = --frame / --fps) it runs
// `subdivisions` silhouette-of-motion updates from a cleared state and builds each polygon's
// alpha-faded quad strip (scene/blur_shell); then draws the scene at T, opaque as every method
// draws it, and the shell over it through the shared CPU rasterizer. Camera motion alone makes
// no shell: the SoM is found in world space.
//
// Options: length (seconds, 0.2), subdivisions (10), alpha (0.5), fade (3): BlurShellOptions;
// blend: ordered (default, the thesis: the shell blended in submission order over the mesh,
// depth tested against it without depth writes) or sorted (order independent: the shell joins
// the translucent surfaces, sorted per sample front to back).
// Stats: silhouette_edges (at T), silhouette_edges_per_update, shell_strips, shell_triangles;
// phases "silhouette" (the SoM updates), "shell build" and "draw".
std::unique_ptr<Renderer> createBlurShellRenderer(OptionMap& options);

}  // namespace streak
