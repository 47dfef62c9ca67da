#include "image/deep_image.h"

#include "util/error.h"

#include <string>

namespace streak {

DeepImage::DeepImage(int width, int height)
    : m_width(width), m_height(height), m_offsets(std::size_t(width) * std::size_t(height) + 1, 0) {}

void DeepImage::assign(const std::vector<std::vector<DeepSample>>& perPixel) {
    if (perPixel.size() + 1 != m_offsets.size()) throw Error("deep image: one sample list per pixel expected");
    m_samples.clear();
    for (std::size_t i = 0; i < perPixel.size(); ++i) {
        m_samples.insert(m_samples.end(), perPixel[i].begin(), perPixel[i].end());
        m_offsets[i + 1] = m_samples.size();
    }
}

DeepImage DeepImage::region(int x0, int y0, int x1, int y1) const {
    if (!(x0 >= 0 && y0 >= 0 && x0 < x1 && y0 < y1 && x1 <= m_width && y1 <= m_height))
        throw Error("region " + std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(x1) + "," + std::to_string(y1) +
                    " is not inside the " + std::to_string(m_width) + "x" + std::to_string(m_height) + " deep image");
    DeepImage out(x1 - x0, y1 - y0);
    std::size_t i = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++i) {
            const std::span<const DeepSample> s = samples(x, y);
            out.m_samples.insert(out.m_samples.end(), s.begin(), s.end());
            out.m_offsets[i + 1] = out.m_samples.size();
        }
    out.place({x0, y0, m_width, m_height});
    return out;
}

}  // namespace streak
