#include "image/image.h"

#include "image/deep_image.h"

#include "util/error.h"

#include <glm/common.hpp>

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

void Image::setAlpha(std::vector<float> alpha) {
    if (!alpha.empty() && alpha.size() != m_pixels.size())
        throw Error("alpha of " + std::to_string(alpha.size()) + " values for a " + std::to_string(m_width) + "x" + std::to_string(m_height) + " image");
    m_alpha = std::move(alpha);
}

void Image::addChannel(std::string name, std::vector<float> values) {
    if (values.size() != m_pixels.size())
        throw Error("channel " + name + " of " + std::to_string(values.size()) + " values for a " + std::to_string(m_width) + "x" + std::to_string(m_height) + " image");
    if (name.empty() || name == "R" || name == "G" || name == "B" || name == "A") throw Error("channel name '" + name + "' is taken by the colour");
    for (const ImageChannel& c : m_channels)
        if (c.name == name) throw Error("the image has a channel " + name + " already");
    m_channels.push_back({std::move(name), std::move(values)});
}

Image Image::region(int x0, int y0, int x1, int y1) const {
    if (x0 < 0 || y0 < 0 || x1 > m_width || y1 > m_height || x0 >= x1 || y0 >= y1)
        throw Error("region " + std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(x1) + "," + std::to_string(y1) +
                    " is not inside the " + std::to_string(m_width) + "x" + std::to_string(m_height) + " image");
    Image out(x1 - x0, y1 - y0);
    for (int y = y0; y < y1; ++y) std::copy(&at(x0, y), &at(x0, y) + (x1 - x0), &out.at(0, y - y0));
    if (hasAlpha()) {
        std::vector<float> alpha;
        alpha.reserve(std::size_t(x1 - x0) * std::size_t(y1 - y0));
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) alpha.push_back(alphaAt(x, y));
        out.setAlpha(std::move(alpha));
    }
    for (const ImageChannel& c : m_channels) {
        std::vector<float> values;
        values.reserve(std::size_t(x1 - x0) * std::size_t(y1 - y0));
        for (int y = y0; y < y1; ++y)
            values.insert(values.end(), c.values.begin() + std::ptrdiff_t(std::size_t(y) * m_width + std::size_t(x0)),
                          c.values.begin() + std::ptrdiff_t(std::size_t(y) * m_width + std::size_t(x1)));
        out.addChannel(c.name, std::move(values));
    }
    out.m_metadata = m_metadata;
    out.place({x0, y0, m_width, m_height});
    if (m_deep) out.m_deep = std::make_shared<const DeepImage>(m_deep->region(x0, y0, x1, y1));
    return out;
}

Image withTransparentBackground(Image image, const glm::vec3& background) {
    if (!image.hasAlpha()) throw Error("a transparent background needs the render's coverage (alpha)");
    std::span<glm::vec3> pixels = image.pixels();
    std::span<const float> alpha = image.alpha();
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = glm::max(pixels[i] - background * (1.0f - alpha[i]), glm::vec3(0.0f));
    return image;
}

}  // namespace streak
