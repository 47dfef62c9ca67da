#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace streak {

// Where an image lies in a larger frame: a region of it (a border render), its top-left pixel at
// (x, y) of a frame frameWidth x frameHeight. EXR keeps it as the data window inside the display
// window, which is how compositors and `streak stitch` put regions back in place.
struct FramePlacement {
    int x = 0, y = 0;
    int frameWidth = 0, frameHeight = 0;
};

// Image is a linear-light RGB float raster, row-major with the top row first. Renderers write
// it; image_io.h encodes it (sRGB 8-bit PNG or linear float EXR); metrics.h compares two. An
// image is a whole frame unless it is placed in one (a region).
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

    // Where the image lies in its frame; none for a whole frame.
    const std::optional<FramePlacement>& placement() const { return m_placement; }
    // Throws Error unless the image lies inside the frame.
    void place(const FramePlacement& placement);

    // The pixels [x0, x1) x [y0, y1) of this whole frame, placed in it.
    Image region(int x0, int y0, int x1, int y1) const;

private:
    int m_width = 0;                 ///< pixels
    int m_height = 0;                ///< pixels
    std::vector<glm::vec3> m_pixels; ///< linear RGB, width*height
    std::optional<FramePlacement> m_placement;
};

}  // namespace streak
