#pragma once

#include <glm/vec3.hpp>

#include <cstdint>

namespace streak {

// sRGB transfer functions (IEC 61966-2-1). streak works in linear light; sRGB appears only
// where 8-bit data enters (textures, PNG input) or leaves (PNG output, display-space metrics).
float srgbToLinear(float encoded);
float linearToSrgb(float linear);           ///< clamps to [0,1] first
glm::vec3 linearToSrgb(const glm::vec3& linear);
std::uint8_t linearToSrgb8(float linear);   ///< rounds to nearest
float srgb8ToLinear(std::uint8_t encoded);  ///< table lookup, exact for all 256 codes

}  // namespace streak
