#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// The post-process motion blur games ship (McGuire et al. 2012, Guertin et al. 2014; Unreal,
// Unity HDRP, Blender EEVEE): the scene drawn once at shutter centre with colour, depth and
// per-pixel screen velocity (the visible point's projections at shutter open and close, with
// the camera of each), then TileMax, NeighborMax and the gather of reconstruction_filter.h. Not
// exact: it knows only what the centre frame shows, so what the motion uncovers and translucent
// surfaces (whose velocity is the opaque surface's behind them) are guessed.
// Options: tile (k, 20), samples (gather taps, 15), max-radius (pixels, default k),
// soft-depth (0.01 of the depth).
std::unique_ptr<Renderer> createPostFilterRenderer(OptionMap& options);

}  // namespace streak
