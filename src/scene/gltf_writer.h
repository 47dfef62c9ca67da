#pragma once

#include "scene/scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace streak {

// A scene as a glTF 2.0 binary (.glb), so another renderer can play it as streak renders it
// (bench/cycles_reference.py renders built-in scenes with Cycles this way):
//  - each mesh is a node whose POSITION (and NORMAL) is its first key pose and whose morph
//    targets are the other keys' offsets from it; a LINEAR weights animation is one-hot on
//    target k-1 at key k's time, k / (K-1) seconds, and zero at 0 s, so glTF's linear
//    interpolation is streak's piecewise-linear motion, with the shutter t in [0, 1] as the
//    animation's first second (load it back with --frame 0 --shutter 24 --fps 24). Meshes that
//    do not move have no targets. Uvs are TEXCOORD_0, vertex colours COLOR_0;
//  - materials keep base colour, opacity (alpha of baseColorFactor), alpha mode and cutoff
//    (an Opaque material with opacity below 1, which streak blends, becomes BLEND) and
//    double-sidedness; textures are 8-bit sRGB PNGs of level 0 (exact for streak's textures,
//    which come from 8-bit sRGB) with their wrap modes;
//  - the camera is a perspective camera (yfov, znear, no zfar) on a node posed at shutter open,
//    with a LINEAR translation and rotation animation to its close pose when it moves (glTF's
//    slerp is streak's), placed first so a glTF loader picks it.
// The light and the background have no glTF equivalent and are left out. Meshes with Bezier
// keys cannot be written this way: Error.
std::vector<std::uint8_t> writeGltfBinary(const Scene& scene);

// The same document as glTF text (.gltf), its buffer inlined as a base64 data: uri.
std::string writeGltfText(const Scene& scene);

}  // namespace streak
