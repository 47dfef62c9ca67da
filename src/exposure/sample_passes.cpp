#include "exposure/sample_passes.h"

#include "image/cryptomatte.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace streak::exposure {

namespace {

constexpr const char* kObjectType = "CryptoObject";
constexpr const char* kMaterialType = "CryptoMaterial";

void addShare(std::vector<std::pair<std::uint32_t, float>>& shares, std::uint32_t index, float share) {
    for (auto& s : shares)
        if (s.first == index) {
            s.second += share;
            return;
        }
    shares.emplace_back(index, share);
}

// Ranks the pixel's IDs by coverage (ties by ID, so the order never depends on the samples'
// order) into `ranks` pairs of out, zeros past the last.
void writeRanks(std::vector<std::pair<std::uint32_t, float>>& shares, const std::vector<float>& ids, float weight, int ranks, float* out) {
    std::sort(shares.begin(), shares.end(), [&](const auto& a, const auto& b) {
        return a.second != b.second ? a.second > b.second : ids[a.first] < ids[b.first];
    });
    for (int r = 0; r < ranks; ++r) {
        const bool has = std::size_t(r) < shares.size();
        out[2 * r] = has ? ids[shares[std::size_t(r)].first] : 0.0f;
        out[2 * r + 1] = has ? shares[std::size_t(r)].second * weight : 0.0f;
    }
}

void writeCryptomatte(Image& image, const char* type, const std::vector<float>& ranks, int numRanks, const std::vector<std::string>& names) {
    const std::size_t pixels = std::size_t(image.width()) * std::size_t(image.height());
    for (int r = 0; r < 2 * cryptomatteLayers(numRanks); ++r) {
        for (const bool isCoverage : {false, true}) {
            std::vector<float> values(pixels, 0.0f);
            if (r < numRanks)
                for (std::size_t i = 0; i < pixels; ++i) values[i] = ranks[i * std::size_t(2 * numRanks) + std::size_t(2 * r) + (isCoverage ? 1u : 0u)];
            image.addChannel(cryptomatteChannel(type, r, isCoverage), std::move(values));
        }
    }
    const std::string prefix = "cryptomatte/" + cryptomatteKey(type) + "/";
    image.setMetadata(prefix + "name", type);
    image.setMetadata(prefix + "hash", "MurmurHash3_32");
    image.setMetadata(prefix + "conversion", "uint32_to_float32");
    image.setMetadata(prefix + "manifest", cryptomatteManifest(names));
}

}  // namespace

PassFrame::PassFrame(const Scene& scene, const PassRequest& request, int width, int height)
    : m_request(request), m_width(width), m_height(height), m_background(scene.background) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    if (request.deep) m_deep.resize(pixels);
    if (request.depth) m_depth.assign(pixels, kEmptyDepth), m_nearest.assign(pixels, kEmptyDepth);
    const std::size_t ranks = std::size_t(request.cryptoRanks) * 2;
    if (request.objectId) m_objectRanks.assign(pixels * ranks, 0.0f);
    if (request.materialId) m_materialRanks.assign(pixels * ranks, 0.0f);
    for (const Mesh& mesh : scene.meshes) m_objectNames.push_back(mesh.name), m_objectIds.push_back(cryptomatteId(mesh.name));
    for (const Material& material : scene.materials) m_materialNames.push_back(material.name), m_materialIds.push_back(cryptomatteId(material.name));
}

void PassFrame::writeTo(Image& image, RenderStats& stats) const {
    if (m_request.deep) {
        auto deep = std::make_shared<DeepImage>(m_width, m_height);
        deep->assign(m_deep);
        stats.setCounter("deep_samples", double(deep->numSamples()));
        stats.setCounter("deep_samples_max", double(m_request.deepSamples));
        stats.setCounter("deep_pixels_merged", double(m_deepMergedPixels.load()));
        stats.setCounter("deep_layers_merged", double(m_deepMergedLayers.load()));
        image.setDeep(std::move(deep));
    }
    if (m_request.depth) {
        image.addChannel("Z", m_depth);
        image.addChannel("Z.min", m_nearest);
    }
    if (m_request.objectId) writeCryptomatte(image, kObjectType, m_objectRanks, m_request.cryptoRanks, m_objectNames);
    if (m_request.materialId) writeCryptomatte(image, kMaterialType, m_materialRanks, m_request.cryptoRanks, m_materialNames);
}

void PixelPasses::begin(const PassFrame& frame) {
    m_objects.clear(), m_materials.clear();
    m_depthSum = 0.0, m_shareSum = 0.0;
    m_nearest = kEmptyDepth;
    m_wantsColor = frame.m_request.deep;
    m_deep.clear();
}

void PixelPasses::add(const ShownSurface& s) {
    if (!(s.share > 0.0f)) return;
    addShare(m_objects, s.object, s.share);
    addShare(m_materials, s.material, s.share);
    m_depthSum += double(s.share) * double(s.depth), m_shareSum += double(s.share);
    m_nearest = std::min(m_nearest, s.nearest);
    if (m_wantsColor) m_deep.push_back({s.triangle, s.object, s.share, s.nearest, s.farthest, glm::vec3(0.0f)});
}

void PixelPasses::addColor(std::uint32_t triangle, const glm::vec3& color) {
    if (m_wantsColor) m_deep.push_back({triangle, ~0u, 0.0f, kEmptyDepth, -kEmptyDepth, color});
}

void PixelPasses::compact() {
    std::sort(m_deep.begin(), m_deep.end(), [](const DeepRecord& a, const DeepRecord& b) { return a.triangle < b.triangle; });
    std::size_t n = 0;
    for (const DeepRecord& r : m_deep) {
        if (n > 0 && m_deep[n - 1].triangle == r.triangle) {
            DeepRecord& into = m_deep[n - 1];
            if (r.object != ~0u) into.object = r.object;
            into.share += r.share, into.color += r.color;
            into.nearest = std::min(into.nearest, r.nearest), into.farthest = std::max(into.farthest, r.farthest);
        } else {
            m_deep[n++] = r;
        }
    }
    m_deep.resize(n);
}

SampledPasses::SampledPasses(const Scene& scene, const FlatTriangles& triangles, const PassRequest& request, int width, int height,
                             const raster::PixelBounds& pixels, float sampleWeight)
    : m_frame(scene, request, width, height), m_triangles(triangles), m_bounds(pixels), m_sampleWeight(sampleWeight),
      m_pixels(std::size_t(pixels.x1 - pixels.x0 + 1) * std::size_t(pixels.y1 - pixels.y0 + 1)) {
    for (PixelPasses& pixel : m_pixels) pixel.begin(m_frame);
}

void SampledPasses::add(PixelPasses& pixel, std::uint32_t triangle, float share, float depth, const glm::vec3& color) {
    if (!(share > 0.0f)) return;
    const FlatTriangle& t = m_triangles[triangle];
    pixel.add({triangle, t.mesh, t.material, share, depth, depth, depth});
    pixel.addColor(triangle, color);
}

void SampledPasses::writeTo(Image& image, RenderStats& stats) {
    std::size_t i = 0;
    for (int y = m_bounds.y0; y <= m_bounds.y1; ++y)
        for (int x = m_bounds.x0; x <= m_bounds.x1; ++x) m_pixels[i++].finish(m_frame, x, y, 1.0f);  // shares came weighed
    m_frame.writeTo(image, stats);
}

int layerDeepSurfaces(std::vector<DeepLayer>& layers, int maxLayers) {
    std::sort(layers.begin(), layers.end(), [](const DeepLayer& a, const DeepLayer& b) {
        return a.nearest != b.nearest ? a.nearest < b.nearest : a.farthest < b.farthest;
    });
    auto join = [](DeepLayer& into, const DeepLayer& from) {
        into.share += from.share, into.color += from.color;
        into.farthest = std::max(into.farthest, from.farthest);
    };
    std::size_t n = 0;
    for (const DeepLayer& layer : layers) {
        if (n > 0 && (layer.nearest == layers[n - 1].nearest || (layer.object == layers[n - 1].object && layer.nearest <= layers[n - 1].farthest)))
            join(layers[n - 1], layer);
        else
            layers[n++] = layer;
    }
    layers.resize(n);
    int joins = 0;
    if (maxLayers > 0 && n > std::size_t(maxLayers)) {
        // Join across the n - maxLayers smallest gaps (ties: the nearer first).
        std::vector<std::uint32_t> gaps(n - 1);
        std::iota(gaps.begin(), gaps.end(), 0u);
        auto gap = [&](std::uint32_t i) { return double(layers[i + 1].nearest) - double(layers[i].farthest); };
        const std::size_t cuts = n - std::size_t(maxLayers);
        std::nth_element(gaps.begin(), gaps.begin() + std::ptrdiff_t(cuts - 1), gaps.end(), [&](std::uint32_t a, std::uint32_t b) {
            return gap(a) != gap(b) ? gap(a) < gap(b) : a < b;
        });
        std::vector<char> joinsNext(n, 0);
        for (std::size_t k = 0; k < cuts; ++k) joinsNext[gaps[k]] = 1;
        std::size_t m = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (i > 0 && joinsNext[i - 1]) join(layers[m - 1], layers[i]);
            else layers[m++] = layers[i];
        }
        layers.resize(m);
        joins = int(cuts);
    }
    for (std::size_t i = 0; i + 1 < layers.size(); ++i) layers[i].farthest = std::min(layers[i].farthest, layers[i + 1].nearest);
    return joins;
}

void deepSamplesOf(const std::vector<DeepLayer>& layers, const glm::vec3* background, std::vector<DeepSample>& out) {
    out.clear();
    // What the layers in front leave: 1 - their summed shares.
    double transmittance = 1.0;
    for (const DeepLayer& layer : layers) {
        if (!(layer.share > 0.0) || !(transmittance > 1e-9)) continue;
        const double alpha = std::min(layer.share / transmittance, 1.0);
        out.push_back({layer.nearest, layer.farthest, glm::vec3(layer.color / transmittance), float(alpha)});
        transmittance -= layer.share;
    }
    // The background takes all that is left, behind everything.
    if (background && transmittance > 1e-7) out.push_back({kEmptyDepth, kEmptyDepth, *background, 1.0f});
}

void PixelPasses::finish(PassFrame& frame, int x, int y, float sampleWeight) {
    const std::size_t pixel = std::size_t(y) * std::size_t(frame.m_width) + std::size_t(x);
    const PassRequest& request = frame.m_request;
    if (request.depth) {
        frame.m_depth[pixel] = m_shareSum > 0.0 ? float(m_depthSum / m_shareSum) : kEmptyDepth;
        frame.m_nearest[pixel] = m_nearest;
    }
    if (request.deep) {
        // Each triangle's records (its shares, then its colours) into one surface, then layers.
        std::sort(m_deep.begin(), m_deep.end(), [](const DeepRecord& a, const DeepRecord& b) { return a.triangle < b.triangle; });
        std::vector<DeepLayer> layers;
        for (std::size_t i = 0; i < m_deep.size();) {
            DeepLayer layer{~0u, 0.0, glm::dvec3(0.0), kEmptyDepth, -kEmptyDepth};
            std::size_t j = i;
            for (; j < m_deep.size() && m_deep[j].triangle == m_deep[i].triangle; ++j) {
                const DeepRecord& r = m_deep[j];
                if (r.object != ~0u) layer.object = r.object;
                layer.share += double(r.share) * sampleWeight;
                layer.color += glm::dvec3(r.color) * double(sampleWeight);
                layer.nearest = std::min(layer.nearest, r.nearest), layer.farthest = std::max(layer.farthest, r.farthest);
            }
            // A depth past the background's, or none at all (NaN), is held in front of the
            // background's sample, so the samples stay sorted and apart.
            static const float kFarthest = std::nextafter(kEmptyDepth, 0.0f);
            auto held = [](float d) { return d == d ? std::min(d, kFarthest) : kFarthest; };
            layer.nearest = held(layer.nearest), layer.farthest = std::max(held(layer.farthest), layer.nearest);
            if (layer.share > 0.0) layers.push_back(layer);
            i = j;
        }
        if (const int joins = layerDeepSurfaces(layers, request.deepSamples); joins > 0) {
            frame.m_deepMergedPixels.fetch_add(1, std::memory_order_relaxed);
            frame.m_deepMergedLayers.fetch_add(joins, std::memory_order_relaxed);
        }
        deepSamplesOf(layers, request.deepBackground ? &frame.m_background : nullptr, frame.m_deep[pixel]);
    }
    const std::size_t stride = std::size_t(request.cryptoRanks) * 2;
    if (request.objectId) writeRanks(m_objects, frame.m_objectIds, sampleWeight, request.cryptoRanks, &frame.m_objectRanks[pixel * stride]);
    if (request.materialId) writeRanks(m_materials, frame.m_materialIds, sampleWeight, request.cryptoRanks, &frame.m_materialRanks[pixel * stride]);
}

}  // namespace streak::exposure
