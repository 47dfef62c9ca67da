#pragma once

// Point cache files written by tests: PC2 (little-endian) and MDD (big-endian), as
// scene/point_cache.h reads them.

#include <glm/vec3.hpp>

#include <bit>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace streak::test {

// A cache file's bytes: numbers in one byte order, appended one by one.
struct CacheBytes {
    bool isBigEndian = false;
    std::vector<char> data;
    void u32(std::uint32_t v) {
        if (isBigEndian) v = __builtin_bswap32(v);
        const char* p = reinterpret_cast<const char*>(&v);
        data.insert(data.end(), p, p + 4);
    }
    void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
    void points(const std::vector<glm::vec3>& ps) {
        for (const glm::vec3& p : ps) f32(p.x), f32(p.y), f32(p.z);
    }
};

// PC2 of `samples` (each a pose of every point) from startFrame, one every sampleRate frames.
inline std::vector<char> pc2Bytes(const std::vector<std::vector<glm::vec3>>& samples, float startFrame, float sampleRate) {
    CacheBytes b;
    const char signature[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
    b.data.assign(signature, signature + 12);
    b.u32(1), b.u32(std::uint32_t(samples.front().size())), b.f32(startFrame), b.f32(sampleRate), b.u32(std::uint32_t(samples.size()));
    for (const auto& s : samples) b.points(s);
    return b.data;
}

// MDD of frames at `times` (seconds), with a rest pose block first if given (as Blender writes).
inline std::vector<char> mddBytes(const std::vector<std::vector<glm::vec3>>& frames, const std::vector<float>& times,
                                  const std::vector<glm::vec3>* rest = nullptr) {
    CacheBytes b{true, {}};
    b.u32(std::uint32_t(frames.size())), b.u32(std::uint32_t(frames.front().size()));
    for (float t : times) b.f32(t);
    if (rest) b.points(*rest);
    for (const auto& f : frames) b.points(f);
    return b.data;
}

inline void writeBytes(const std::string& path, const std::vector<char>& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

}  // namespace streak::test
