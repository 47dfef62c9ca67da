#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <span>
#include <vector>

namespace streak {

// Image is a linear-light RGB float raster, row-major with the top row first. Renderers write
// it; image_io.h encodes it (sRGB 8-bit PNG or linear float EXR); metrics.h compares two.
class Image {
public:
    Image() = default;
    Image(int width, int height, glm::vec3 fill = glm::vec3(0.0f));

    int width() const { return m_width; }
    int height() const { return m_height; }
    bool empty() const { return m_pixels.empty(); }

    glm::vec3& at(int x, int y) { return m_pixels[std::size_t(y) * m_width + x]; }
    const glm::vec3& at(int x, int y) const { return m_pixels[std::size_t(y) * m_width + x]; }

    std::span<glm::vec3> pixels() { return m_pixels; }
    std::span<const glm::vec3> pixels() const { return m_pixels; }

private:
    int m_width = 0;                 ///< pixels
    int m_height = 0;                ///< pixels
    std::vector<glm::vec3> m_pixels; ///< linear RGB, width*height
};

}  // namespace streak
