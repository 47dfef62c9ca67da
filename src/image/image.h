#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace streak {

class DeepImage;

// Where an image lies in a larger frame: a region of it (a border render), its top-left pixel at
// (x, y) of a frame frameWidth x frameHeight. EXR keeps it as the data window inside the display
// window, which is how compositors and `streak stitch` put regions back in place.
struct FramePlacement {
    int x = 0, y = 0;
    int frameWidth = 0, frameHeight = 0;
};

// A named float channel of an image beside its colour: a pass (depth "Z", Cryptomatte's
// "CryptoObject00.r", ...), one value per pixel. EXR writes it under its name.
struct ImageChannel {
    std::string name;
    std::vector<float> values;
};

// Image is a linear-light RGB float raster, row-major with the top row first. Renderers write
// it; image_io.h encodes it (sRGB 8-bit PNG or linear float EXR); metrics.h compares two. An
// image is a whole frame unless it is placed in one (a region).
//
// Alpha, when the image has it, is each pixel's coverage: the share of its samples' exposure in
// which a surface, not the background, shows (a translucent surface covers by its opacity).
// Renderers give it with the colour they render over the scene's background; withTransparent-
// Background() then takes the background out. An image with alpha in a file holds colour
// premultiplied by it: what shows over a black background (EXR's convention).
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

    // Coverage per pixel (see above), width*height; empty without alpha.
    bool hasAlpha() const { return !m_alpha.empty(); }
    std::span<float> alpha() { return m_alpha; }
    std::span<const float> alpha() const { return m_alpha; }
    float alphaAt(int x, int y) const { return m_alpha.empty() ? 1.0f : m_alpha[std::size_t(y) * m_width + x]; }
    // Throws Error unless there is one value per pixel; an empty vector removes the alpha.
    void setAlpha(std::vector<float> alpha);
    // Alpha 0 everywhere: nothing covered yet (a renderer's start).
    void setUncovered() { m_alpha.assign(m_pixels.size(), 0.0f); }

    // Passes: named channels (one value per pixel) and the string attributes that describe them
    // (Cryptomatte's manifests), written to EXR beside R G B (A); PNG leaves them out.
    const std::vector<ImageChannel>& channels() const { return m_channels; }
    const std::map<std::string, std::string>& metadata() const { return m_metadata; }
    // Throws Error unless `values` has one value per pixel and the name is new and not R, G, B or A.
    void addChannel(std::string name, std::vector<float> values);
    void setMetadata(const std::string& key, std::string value) { m_metadata[key] = std::move(value); }

    // The deep image of the same render (PassRequest::deep), or null: each pixel's surfaces as
    // deep samples, compositing to this image's RGBA. region() crops it too.
    const DeepImage* deep() const { return m_deep.get(); }
    void setDeep(std::shared_ptr<const DeepImage> deep) { m_deep = std::move(deep); }
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
    std::vector<float> m_alpha;      ///< coverage, width*height, or empty
    std::vector<ImageChannel> m_channels;
    std::map<std::string, std::string> m_metadata;
    std::optional<FramePlacement> m_placement;
    std::shared_ptr<const DeepImage> m_deep;
};

// A render over `background` with its coverage (alpha) as what shows over a transparent one:
// colour premultiplied by alpha, the background's share (1 - alpha) taken out. Exact, because
// every method's colour is its surfaces' plus the background times its share. Throws Error when
// the image has no alpha.
Image withTransparentBackground(Image image, const glm::vec3& background);

}  // namespace streak
