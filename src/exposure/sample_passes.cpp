#include "exposure/sample_passes.h"

#include "image/cryptomatte.h"

#include <algorithm>
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
    : m_request(request), m_width(width), m_height(height) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    if (request.depth) m_depth.assign(pixels, kEmptyDepth), m_nearest.assign(pixels, kEmptyDepth);
    const std::size_t ranks = std::size_t(request.cryptoRanks) * 2;
    if (request.objectId) m_objectRanks.assign(pixels * ranks, 0.0f);
    if (request.materialId) m_materialRanks.assign(pixels * ranks, 0.0f);
    for (const Mesh& mesh : scene.meshes) m_objectNames.push_back(mesh.name), m_objectIds.push_back(cryptomatteId(mesh.name));
    for (const Material& material : scene.materials) m_materialNames.push_back(material.name), m_materialIds.push_back(cryptomatteId(material.name));
}

void PassFrame::writeTo(Image& image) const {
    if (m_request.depth) {
        image.addChannel("Z", m_depth);
        image.addChannel("Z.min", m_nearest);
    }
    if (m_request.objectId) writeCryptomatte(image, kObjectType, m_objectRanks, m_request.cryptoRanks, m_objectNames);
    if (m_request.materialId) writeCryptomatte(image, kMaterialType, m_materialRanks, m_request.cryptoRanks, m_materialNames);
}

void PixelPasses::begin() {
    m_objects.clear(), m_materials.clear();
    m_depthSum = 0.0, m_shareSum = 0.0;
    m_nearest = kEmptyDepth;
}

void PixelPasses::add(std::uint32_t object, std::uint32_t material, float share, float depth, float nearest) {
    if (!(share > 0.0f)) return;
    addShare(m_objects, object, share);
    addShare(m_materials, material, share);
    m_depthSum += double(share) * double(depth), m_shareSum += double(share);
    m_nearest = std::min(m_nearest, nearest);
}

void PixelPasses::finish(PassFrame& frame, int x, int y, float sampleWeight) {
    const std::size_t pixel = std::size_t(y) * std::size_t(frame.m_width) + std::size_t(x);
    const PassRequest& request = frame.m_request;
    if (request.depth) {
        frame.m_depth[pixel] = m_shareSum > 0.0 ? float(m_depthSum / m_shareSum) : kEmptyDepth;
        frame.m_nearest[pixel] = m_nearest;
    }
    const std::size_t stride = std::size_t(request.cryptoRanks) * 2;
    if (request.objectId) writeRanks(m_objects, frame.m_objectIds, sampleWeight, request.cryptoRanks, &frame.m_objectRanks[pixel * stride]);
    if (request.materialId) writeRanks(m_materials, frame.m_materialIds, sampleWeight, request.cryptoRanks, &frame.m_materialRanks[pixel * stride]);
}

}  // namespace streak::exposure
