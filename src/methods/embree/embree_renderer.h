#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// Ray-traced motion blur with Embree 3, as CPU path tracers (Cycles) do it: each mesh is an
// Embree triangle geometry with one vertex buffer per time step (piecewise-linear keys map one
// to one; Bezier keys are cut into curve-segments linear steps per key segment), and each
// pixel sample (the --aa positions) traces `samples` primary rays at stratified times, the very
// times stochastic gives its samples (stratifiedSampleTime), from the camera posed at that time.
// Hits are shaded with shadeSurface at the ray's time, with the texture footprint of one sample
// spacing (the barycentrics of the rays one spacing right and down, on the hit triangle's
// plane). Translucent and back-facing single-sided hits are passed through front to back (an
// intersection filter skips the triangles already met); at most max-layers translucent layers
// blend over the opaque hit, the rest counted.
// Options: samples (S per sub-pixel position, 8), curve-segments (4), max-layers (64).
std::unique_ptr<Renderer> createEmbreeRenderer(OptionMap& options);

}  // namespace streak
