#pragma once

#include "methods/motion_path/interval.h"

#include <glm/vec3.hpp>

#include <span>

namespace streak::motion_path {

// The colour of a pixel sample over the shutter from its intervals sorted front to back (Hong &
// Oh 2017, section 3.4), with numBits time slices. Opaque intervals: visible = current &
// ~accumulated; colour += interval colour * |visible| / n; accumulated |= current; stop when
// full; the background fills the slices nothing covers. When some interval is translucent,
// each slice keeps a transmittance instead of a bit (beyond the paper): colour += alpha T c / n
// per slice, T *= 1 - alpha.
glm::vec3 resolveIntervals(std::span<const Interval> sorted, int numBits, const glm::vec3& background);

}  // namespace streak::motion_path
