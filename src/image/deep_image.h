#pragma once

#include "image/image.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace streak {

// One deep sample of a pixel (OpenEXR's deep data): a surface layer lying from depth z to
// zBack (view depth; equal for a point sample), its alpha and its colour premultiplied by it.
// Composited front to back with "over" (OpenEXR's "Interpreting Deep Pixels": sorted, not
// overlapping, so no sample needs splitting), a pixel's samples give its flat RGBA.
struct DeepSample {
    float z = 0.0f, zBack = 0.0f;
    glm::vec3 color{0.0f};
    float alpha = 0.0f;
};

// A deep image: each pixel's samples, front to back and tidy (sorted by z, none overlapping
// another's [z, zBack]), row-major with the top row first; placed in a frame as Image is.
class DeepImage {
public:
    DeepImage() = default;
    // Pixels with no samples, until assign() fills them.
    DeepImage(int width, int height);
    int width() const { return m_width; }
    int height() const { return m_height; }
    std::size_t numSamples() const { return m_samples.size(); }
    std::span<const DeepSample> samples(int x, int y) const {
        const std::size_t i = std::size_t(y) * std::size_t(m_width) + std::size_t(x);
        return std::span<const DeepSample>(m_samples).subspan(m_offsets[i], m_offsets[i + 1] - m_offsets[i]);
    }
    std::span<const std::uint64_t> offsets() const { return m_offsets; }  ///< per pixel, and one past the last
    std::span<const DeepSample> allSamples() const { return m_samples; }
    // Every pixel's samples at once: `perPixel` holds width x height lists.
    void assign(const std::vector<std::vector<DeepSample>>& perPixel);

    const std::optional<FramePlacement>& placement() const { return m_placement; }
    void place(const FramePlacement& placement) { m_placement = placement; }
    // The pixels [x0, x1) x [y0, y1) of this whole frame, placed in it.
    DeepImage region(int x0, int y0, int x1, int y1) const;

private:
    int m_width = 0, m_height = 0;
    std::vector<std::uint64_t> m_offsets{0};
    std::vector<DeepSample> m_samples;
    std::optional<FramePlacement> m_placement;
};

}  // namespace streak
