#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// The accumulation buffer (the papers' reference): the scene is rasterized with a depth buffer
// at S stratified shutter times t_s = (s + 1/2) / S and the S images are averaged. Translucent
// surfaces are sorted and blended per sample at each time. Converges to the exact motion blur
// as S grows; Hong & Oh use S = 3000 for their reference images.
// Options: samples (S, default 256).
std::unique_ptr<Renderer> createAccumulationRenderer(OptionMap& options);

}  // namespace streak
