#include "image/image.h"

#include "util/error.h"

#include <string>

namespace streak {

Image::Image(int width, int height, glm::vec3 fill) : m_width(width), m_height(height) {
    if (width < 0 || height < 0)
        throw Error("invalid image size " + std::to_string(width) + "x" + std::to_string(height));
    m_pixels.assign(std::size_t(width) * std::size_t(height), fill);
}

}  // namespace streak
