#pragma once

#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "util/stats.h"

#include <string>

namespace streak {

// An OBJ or PLY mesh, or a numbered sequence of them (`fluid_%04d.ply`: frame N is file N), as a
// scene. A sequence is an animation: between two frames' files each vertex moves on the line
// between its positions there, so the shutter [frame, frame + shutter] takes the files it spans,
// floor(frame) to ceil(frame + shutter), and the keys are chosen over it as for a glTF animation
// (the same options: key tolerance, Bezier pieces, cameras, point caches, trails). Past the
// sequence's first or last file the mesh holds it, as an animation holds its end values; a file
// missing between two that exist is an Error. Where the files' topology differs (fluids,
// remeshers), the mesh is the file of GltfOptions::velocityFrame (--frame), moved along its
// velocities from there where it has them (PLY vx vy vz, an OBJ's sidecar), else held still;
// --stats counts it (sequence_topology_changes, sequence_held_still). With
// isSequenceInterpolated the files are interpolated whenever their vertex counts agree (the
// first file's triangles), and an Error where they do not. The mesh becomes
// one glTF mesh whose files are morph targets, loaded by the glTF loader, so every glTF option
// applies as it does to a glTF file. Throws Error naming the file for a missing frame or a bad
// file.
Scene loadMeshSequence(const std::string& spec, const GltfOptions& options, RenderStats* stats = nullptr);

}  // namespace streak
