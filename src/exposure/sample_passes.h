#pragma once

#include "image/deep_image.h"
#include "image/image.h"
#include "image/passes.h"
#include "raster/tile_grid.h"
#include "raster/translucency.h"
#include "scene/flat_geometry.h"
#include "scene/scene.h"
#include "util/stats.h"

#include <glm/vec3.hpp>

#include <atomic>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace streak::exposure {

// The passes of one frame (PassRequest) as a method fills them, pixel by pixel: each sample
// reports what shows in it, each surface with its share of the sample (the exposure it takes
// from the background, as its weight in the colour) and its view depth there. A pixel's
// coverage of an object or material is then the sum of its surfaces' shares over the pixel's
// samples, weighted as the colour's box filter weighs them; so an object's coverages sum to
// the alpha, and with the exact methods they are exact, as the colour is.
//
// The deep image takes each surface's colour too (its share of the sample's colour, as the
// beauty sums it): a pixel's surfaces are kept by triangle, then joined into layers along the
// view depth (DeepLayering), which become its deep samples. Their alphas are chosen so that
// compositing them front to back gives the pixel's colour and alpha exactly: under motion
// blur the surfaces of a sample show at different times, side by side in its exposure rather
// than one over another, and a share s after shares W in front is the alpha s / (1 - W).
class PassFrame {
public:
    PassFrame(const Scene& scene, const PassRequest& request, int width, int height);

    const PassRequest& request() const { return m_request; }
    bool isEmpty() const { return !m_request.any(); }

    // Adds the passes' channels and Cryptomatte metadata to `image` (of the frame's size), and
    // the deep image; records what the deep samples' bound merged (deep_* in the stats).
    void writeTo(Image& image, RenderStats& stats) const;

private:
    friend class PixelPasses;
    PassRequest m_request;
    int m_width = 0, m_height = 0;
    glm::vec3 m_background{0.0f};
    std::vector<std::vector<DeepSample>> m_deep;  ///< per pixel, when deep
    std::atomic<std::int64_t> m_deepMergedPixels{0}, m_deepMergedLayers{0};
    std::vector<float> m_objectIds, m_materialIds;    ///< per scene mesh and material: its Cryptomatte ID
    std::vector<std::string> m_objectNames, m_materialNames;
    std::vector<float> m_depth, m_nearest;            ///< per pixel
    std::vector<float> m_objectRanks, m_materialRanks;  ///< per pixel, ranks x (ID, coverage)
};

// A surface showing in a sample: triangle `triangle` of mesh `object` and material
// `material`, its share of the sample, its mean view depth over the time it shows, and the
// nearest and farthest it gets then.
struct ShownSurface {
    std::uint32_t triangle = 0, object = 0, material = 0;
    float share = 0.0f, depth = 0.0f, nearest = 0.0f, farthest = 0.0f;
};

// One thread's running passes of one pixel: begin(), then add() each surface of each sample
// (and, for the deep image, addColor() each colour they add to it), then finish() writes the
// pixel.
class PixelPasses {
public:
    void begin(const PassFrame& frame);
    void add(const ShownSurface& surface);
    // What triangle `triangle` adds to a sample's colour (its colour times its share), summed
    // over its pieces; kept only for the deep image.
    void addColor(std::uint32_t triangle, const glm::vec3& color);
    bool wantsColor() const { return m_wantsColor; }
    // Joins each triangle's records for the deep image into one, so a pixel added to at many
    // times (SampledPasses) keeps one a surface.
    void compact();
    // Writes the pixel: each sample weighs sampleWeight (1 / samples for the box filter).
    void finish(PassFrame& frame, int x, int y, float sampleWeight);

private:
    struct DeepRecord {
        std::uint32_t triangle = 0, object = 0;
        float share = 0.0f, nearest = 0.0f, farthest = 0.0f;
        glm::vec3 color{0.0f};
    };
    std::vector<std::pair<std::uint32_t, float>> m_objects, m_materials;  ///< index, summed share
    double m_depthSum = 0.0, m_shareSum = 0.0;
    float m_nearest = kEmptyDepth;
    bool m_wantsColor = false;  ///< the frame is deep
    std::vector<DeepRecord> m_deep;
};

// The passes of a method that samples the shutter at instants or strata (accumulation,
// stochastic): each pixel's PixelPasses kept across them (one thread at a time per pixel: the
// tiles of one time are disjoint), each tile's samples added at each time, and the pixels
// written at the end. Their estimate converges to the exact methods' as the times grow.
class SampledPasses {
public:
    // The pixels of `pixels` (the render's region, in the width x height frame) are kept; each
    // sample at each time weighs sampleWeight in its pixel's passes (1 / (samples x times) for the
    // box filter), applied as it is added so that many times sum without losing precision.
    SampledPasses(const Scene& scene, const FlatTriangles& triangles, const PassRequest& request, int width, int height,
                  const raster::PixelBounds& pixels, float sampleWeight);

    // One tile's samples (pixel-major in rect, spp a pixel) at one time, each weighed
    // weightOfRow(row) (times sampleWeight): the opaque surface opaqueTriangle[i] (a FlatTriangle; ~0u: none) at
    // 1 / opaqueInvW[i], shaded opaqueColor[i], behind the translucent fragments that
    // compositeTranslucent sorted (their `triangle` a FlatTriangle too). `transmittance` is
    // the caller's scratch.
    template <class WeightOfRow>
    void addTile(const raster::PixelBounds& rect, int spp, std::span<const std::uint32_t> opaqueTriangle, std::span<const float> opaqueInvW,
                 std::span<const glm::vec3> opaqueColor, const std::vector<raster::TranslucentFragment>& sorted,
                 std::vector<float>& transmittance, WeightOfRow&& weightOfRow) {
        const int tileWidth = rect.x1 - rect.x0 + 1;
        // A tile may reach past the region: its pixels there are not kept.
        auto pixelOf = [&](std::size_t sample, int& x, int& y) -> PixelPasses* {
            const int p = int(sample / std::size_t(spp));
            x = rect.x0 + p % tileWidth, y = rect.y0 + p / tileWidth;
            if (x < m_bounds.x0 || x > m_bounds.x1 || y < m_bounds.y0 || y > m_bounds.y1) return nullptr;
            return &m_pixels[std::size_t(y - m_bounds.y0) * std::size_t(m_bounds.x1 - m_bounds.x0 + 1) + std::size_t(x - m_bounds.x0)];
        };
        transmittance.assign(opaqueTriangle.size(), 1.0f);
        raster::forEachCompositedFragment(sorted, opaqueInvW, std::span<float>(transmittance), [&](const raster::TranslucentFragment& f, float share) {
            int x = 0, y = 0;
            PixelPasses* pixel = pixelOf(f.sample, x, y);
            const float weight = share * weightOfRow(y) * m_sampleWeight;
            if (pixel) add(*pixel, f.triangle, weight, 1.0f / f.invW, f.color * weight);
        });
        for (std::size_t i = 0; i < opaqueTriangle.size(); ++i) {
            int x = 0, y = 0;
            PixelPasses* pixel = pixelOf(i, x, y);
            if (!pixel) continue;
            if (opaqueTriangle[i] != ~0u && opaqueInvW[i] > 0.0f) {
                const float share = transmittance[i] * weightOfRow(y) * m_sampleWeight;
                add(*pixel, opaqueTriangle[i], share, 1.0f / opaqueInvW[i], opaqueColor[i] * share);
            }
            if ((i + 1) % std::size_t(spp) == 0 && m_frame.request().deep) pixel->compact();
        }
    }

    // Writes the pixels into the frame, and the frame into `image`.
    void writeTo(Image& image, RenderStats& stats);

private:
    void add(PixelPasses& pixel, std::uint32_t triangle, float share, float depth, const glm::vec3& color);

    PassFrame m_frame;
    const FlatTriangles& m_triangles;
    raster::PixelBounds m_bounds;
    float m_sampleWeight = 1.0f;
    std::vector<PixelPasses> m_pixels;  ///< the bounds' pixels, row by row
};

// A pixel's surfaces joined into deep layers. Each `Layer` is its surfaces' summed share of the
// pixel and colour, from the nearest depth to the farthest they show at.
//  - Surfaces of one object whose depth ranges overlap are one layer (a smooth surface seen over
//    several triangles), as are surfaces whose nearest depths are equal (no order between them);
//  - past `maxLayers`, the layers with the smallest depth gaps between them are joined (the
//    count of joins is returned) until maxLayers remain;
//  - then each layer's far end is held to the next one's near (tidy: none overlap).
struct DeepLayer {
    std::uint32_t object = 0;
    double share = 0.0;
    glm::dvec3 color{0.0};
    float nearest = 0.0f, farthest = 0.0f;
};
int layerDeepSurfaces(std::vector<DeepLayer>& layers, int maxLayers);

// The deep samples of a pixel's layers (layerDeepSurfaces' output, front to back), and of the
// background behind them (its colour, at depth kEmptyDepth) when `background` is given: alphas
// and premultiplied colours such that compositing them front to back, each over what is behind,
// gives the summed colour and the summed share as alpha.
void deepSamplesOf(const std::vector<DeepLayer>& layers, const glm::vec3* background, std::vector<DeepSample>& out);

}  // namespace streak::exposure
