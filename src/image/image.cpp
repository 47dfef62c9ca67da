#include "image/image.h"

#include "util/error.h"

#include <algorithm>
#include <cstdint>
#include <string>

namespace streak {

Image::Image(int width, int height, glm::vec3 fill) : m_width(width), m_height(height) {
    if (width < 0 || height < 0)
        throw Error("invalid image size " + std::to_string(width) + "x" + std::to_string(height));
    m_pixels.assign(std::size_t(width) * std::size_t(height), fill);
}

void Image::place(const FramePlacement& p) {
    if (p.x < 0 || p.y < 0 || p.frameWidth <= 0 || p.frameHeight <= 0 || std::int64_t(p.x) + m_width > p.frameWidth ||
        std::int64_t(p.y) + m_height > p.frameHeight)
        throw Error("a " + std::to_string(m_width) + "x" + std::to_string(m_height) + " image at " + std::to_string(p.x) + "," + std::to_string(p.y) +
                    " does not lie inside a " + std::to_string(p.frameWidth) + "x" + std::to_string(p.frameHeight) + " frame");
    m_placement = p;
}

Image Image::region(int x0, int y0, int x1, int y1) const {
    if (x0 < 0 || y0 < 0 || x1 > m_width || y1 > m_height || x0 >= x1 || y0 >= y1)
        throw Error("region " + std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(x1) + "," + std::to_string(y1) +
                    " is not inside the " + std::to_string(m_width) + "x" + std::to_string(m_height) + " image");
    Image out(x1 - x0, y1 - y0);
    for (int y = y0; y < y1; ++y) std::copy(&at(x0, y), &at(x0, y) + (x1 - x0), &out.at(0, y - y0));
    out.place({x0, y0, m_width, m_height});
    return out;
}

}  // namespace streak
