#pragma once

#include "image/image.h"
#include "image/passes.h"
#include "scene/scene.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace streak::exposure {

// The passes of one frame (PassRequest) as a method fills them, pixel by pixel: each sample
// reports what shows in it, each surface with its share of the sample (the exposure it takes
// from the background, as its weight in the colour) and its view depth there. A pixel's
// coverage of an object or material is then the sum of its surfaces' shares over the pixel's
// samples, weighted as the colour's box filter weighs them; so an object's coverages sum to
// the alpha, and with the exact methods they are exact, as the colour is.
class PassFrame {
public:
    PassFrame(const Scene& scene, const PassRequest& request, int width, int height);

    const PassRequest& request() const { return m_request; }
    bool isEmpty() const { return !m_request.any(); }

    // Adds the passes' channels and Cryptomatte metadata to `image` (of the frame's size).
    void writeTo(Image& image) const;

private:
    friend class PixelPasses;
    PassRequest m_request;
    int m_width = 0, m_height = 0;
    std::vector<float> m_objectIds, m_materialIds;    ///< per scene mesh and material: its Cryptomatte ID
    std::vector<std::string> m_objectNames, m_materialNames;
    std::vector<float> m_depth, m_nearest;            ///< per pixel
    std::vector<float> m_objectRanks, m_materialRanks;  ///< per pixel, ranks x (ID, coverage)
};

// One thread's running passes of one pixel: begin(), then add() each surface of each sample,
// then finish() writes the pixel.
class PixelPasses {
public:
    void begin();
    // A surface of mesh `object` and material `material` showing in a sample of the pixel: its
    // share of that sample, its mean view depth over the time it shows and the nearest it gets.
    void add(std::uint32_t object, std::uint32_t material, float share, float depth, float nearest);
    // Writes the pixel: each sample weighs sampleWeight (1 / samples for the box filter).
    void finish(PassFrame& frame, int x, int y, float sampleWeight);

private:
    std::vector<std::pair<std::uint32_t, float>> m_objects, m_materials;  ///< index, summed share
    double m_depthSum = 0.0, m_shareSum = 0.0;
    float m_nearest = kEmptyDepth;
};

}  // namespace streak::exposure
