#include "image/color.h"

#include <array>
#include <cmath>

namespace streak {

float srgbToLinear(float encoded) {
    if (encoded <= 0.04045f) return encoded / 12.92f;
    return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
    // Written so NaN lands on 0: a stray NaN sample must not poison a PNG or a metric.
    if (!(linear > 0.0f)) return 0.0f;
    if (linear >= 1.0f) return 1.0f;
    if (linear <= 0.0031308f) return linear * 12.92f;
    return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

glm::vec3 linearToSrgb(const glm::vec3& linear) {
    return {linearToSrgb(linear.x), linearToSrgb(linear.y), linearToSrgb(linear.z)};
}

std::uint8_t linearToSrgb8(float linear) {
    return std::uint8_t(std::lround(linearToSrgb(linear) * 255.0f));
}

float srgb8ToLinear(std::uint8_t encoded) {
    // Built in double so each entry is the correctly rounded float of the exact value.
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double e = i / 255.0;
            t[i] = float(e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table[encoded];
}

}  // namespace streak
