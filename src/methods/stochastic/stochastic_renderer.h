#pragma once

#include "methods/renderer.h"
#include "util/options.h"

#include <memory>

namespace streak {

// Stochastic rasterization (Akenine-Moller et al. 2007; McGuire et al. 2010, as the Hong & Oh
// baseline): every pixel sample has its own shutter time, and each triangle is tested at that
// time at every sample inside its space-time screen bounds. Times are stratified: sample j of
// S at a sub-pixel position takes t in [j/S, (j+1)/S), jittered per pixel from the seed. Noisy
// at low S, converging to the accumulation reference.
// Options: samples (S time samples per sub-pixel position, default 8).
std::unique_ptr<Renderer> createStochasticRenderer(OptionMap& options);

}  // namespace streak
