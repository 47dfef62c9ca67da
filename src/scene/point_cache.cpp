#include "scene/point_cache.h"

#include "scene/gltf_document.h"
#include "util/error.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

namespace streak {

namespace {

// Reads fixed-size numbers of one byte order from a file's bytes, in sequence.
class Reader {
public:
    Reader(std::span<const char> bytes, bool isBigEndian, const std::string& name) : m_bytes(bytes), m_isBig(isBigEndian), m_name(name) {}

    std::uint32_t u32() {
        if (m_bytes.size() - m_pos < 4) throw Error(m_name + ": the file ends inside its header");
        std::uint32_t v;
        std::memcpy(&v, m_bytes.data() + m_pos, 4);
        m_pos += 4;
        if (m_isBig != (std::endian::native == std::endian::big)) v = __builtin_bswap32(v);
        return v;
    }
    std::int32_t i32() { return std::int32_t(u32()); }
    float f32() { return std::bit_cast<float>(u32()); }
    std::size_t position() const { return m_pos; }
    std::size_t remaining() const { return m_bytes.size() - m_pos; }
    void skip(std::size_t n) { m_pos += n; }

private:
    std::span<const char> m_bytes;
    bool m_isBig;
    const std::string& m_name;
    std::size_t m_pos = 0;
};

}  // namespace

PointCache PointCache::read(const std::string& path, double fps, std::uint64_t maxBytes) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".pc2" && extension != ".mdd") throw Error(path + ": a point cache is a .pc2 or .mdd file");
    const std::vector<std::uint8_t> bytes = gltf::readFileBytes(path, maxBytes);  // a regular file within the limit
    return parse(std::span<const char>(reinterpret_cast<const char*>(bytes.data()), bytes.size()), extension == ".mdd", fps, path);
}

PointCache PointCache::parse(std::span<const char> bytes, bool isMdd, double fps, const std::string& name) {
    PointCache cache;
    Reader r(bytes, isMdd, name);
    std::size_t numSamples = 0;
    if (isMdd) {
        const std::int32_t frames = r.i32(), points = r.i32();
        if (frames < 1 || points < 1) throw Error(name + ": an MDD needs at least one frame and one point, got " + std::to_string(frames) + " and " + std::to_string(points));
        numSamples = std::size_t(frames);
        cache.m_numPoints = std::size_t(points);
        // Every count is checked against the file's size before anything is allocated by it.
        if (r.remaining() / 4 < numSamples || (r.remaining() - 4 * numSamples) / 12 / cache.m_numPoints < numSamples)
            throw Error(name + ": the file is too short for " + std::to_string(numSamples) + " frames of " + std::to_string(points) + " points");
        for (std::size_t s = 0; s < numSamples; ++s) cache.m_times.push_back(double(r.f32()));
    } else {
        static constexpr char kSignature[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
        if (bytes.size() < 12 || std::memcmp(bytes.data(), kSignature, 12) != 0) throw Error(name + ": not a PC2 file (no POINTCACHE2 signature)");
        r.skip(12);
        const std::int32_t version = r.i32(), points = r.i32();
        const float startFrame = r.f32(), sampleRate = r.f32();
        const std::int32_t samples = r.i32();
        if (version != 1) throw Error(name + ": PC2 version " + std::to_string(version) + " (streak reads version 1)");
        if (samples < 1 || points < 1) throw Error(name + ": a PC2 needs at least one sample and one point, got " + std::to_string(samples) + " and " + std::to_string(points));
        if (!std::isfinite(startFrame) || !(sampleRate > 0.0f) || !std::isfinite(sampleRate))
            throw Error(name + ": the PC2's start frame must be finite and its sample rate positive, got " + std::to_string(startFrame) + " and " + std::to_string(sampleRate));
        numSamples = std::size_t(samples);
        cache.m_numPoints = std::size_t(points);
        if (r.remaining() / 12 / cache.m_numPoints < numSamples)
            throw Error(name + ": the file is too short for " + std::to_string(numSamples) + " samples of " + std::to_string(points) + " points");
        for (std::size_t s = 0; s < numSamples; ++s) cache.m_times.push_back((double(startFrame) + double(s) * double(sampleRate)) / fps);
    }
    for (std::size_t s = 0; s < numSamples; ++s)
        if (!std::isfinite(cache.m_times[s]) || (s > 0 && !(cache.m_times[s] > cache.m_times[s - 1])))
            throw Error(name + ": the samples' times must be finite and increasing (sample " + std::to_string(s) + ")");
    const std::size_t blockBytes = cache.m_numPoints * 12;
    if (blockBytes / 12 != cache.m_numPoints) throw Error(name + ": too many points");
    const std::size_t blocks = r.remaining() / blockBytes;
    // An MDD of one block more than its frames starts with a rest pose.
    const bool hasRest = isMdd && blocks == numSamples + 1 && r.remaining() % blockBytes == 0;
    if (!hasRest && (blocks != numSamples || r.remaining() % blockBytes != 0))
        throw Error(name + ": " + std::to_string(r.remaining()) + " bytes of points do not make " + std::to_string(numSamples) + " samples of " +
                    std::to_string(cache.m_numPoints) + " points");
    if (hasRest) r.skip(blockBytes);
    cache.m_points.resize(numSamples * cache.m_numPoints);
    for (glm::vec3& p : cache.m_points) {
        p.x = r.f32(), p.y = r.f32(), p.z = r.f32();
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) throw Error(name + ": a point is not finite");
    }
    return cache;
}

void PointCache::pointsAt(double seconds, std::size_t first, std::size_t count, std::span<glm::vec3> out) const {
    // The samples around `seconds` and the share of the later one.
    const auto after = std::upper_bound(m_times.begin(), m_times.end(), seconds);
    std::size_t s0 = 0, s1 = 0;
    float w = 0.0f;
    if (after == m_times.end()) {
        s0 = s1 = m_times.size() - 1;
    } else if (after != m_times.begin()) {
        s1 = std::size_t(after - m_times.begin()), s0 = s1 - 1;
        w = float((seconds - m_times[s0]) / (m_times[s1] - m_times[s0]));
    }
    const glm::vec3* a = &m_points[s0 * m_numPoints + first];
    const glm::vec3* b = &m_points[s1 * m_numPoints + first];
    for (std::size_t i = 0; i < count; ++i) out[i] = w == 0.0f ? a[i] : a[i] + w * (b[i] - a[i]);
}

}  // namespace streak
