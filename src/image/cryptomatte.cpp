#include "image/cryptomatte.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace streak {

namespace {

std::uint32_t rotl32(std::uint32_t x, int r) { return (x << r) | (x >> (32 - r)); }

}  // namespace

std::uint32_t murmurHash3(std::string_view bytes, std::uint32_t seed) {
    constexpr std::uint32_t c1 = 0xcc9e2d51u, c2 = 0x1b873593u;
    const std::size_t n = bytes.size(), blocks = n / 4;
    std::uint32_t h = seed;
    for (std::size_t i = 0; i < blocks; ++i) {
        std::uint32_t k = 0;
        for (int b = 3; b >= 0; --b) k = (k << 8) | std::uint8_t(bytes[4 * i + std::size_t(b)]);  // little-endian
        k *= c1, k = rotl32(k, 15), k *= c2;
        h ^= k, h = rotl32(h, 13), h = h * 5u + 0xe6546b64u;
    }
    std::uint32_t k = 0;
    const std::size_t tail = blocks * 4;
    switch (n & 3u) {
    case 3: k ^= std::uint32_t(std::uint8_t(bytes[tail + 2])) << 16; [[fallthrough]];
    case 2: k ^= std::uint32_t(std::uint8_t(bytes[tail + 1])) << 8; [[fallthrough]];
    case 1:
        k ^= std::uint8_t(bytes[tail]);
        k *= c1, k = rotl32(k, 15), k *= c2;
        h ^= k;
    }
    h ^= std::uint32_t(n);
    h ^= h >> 16, h *= 0x85ebca6bu, h ^= h >> 13, h *= 0xc2b2ae35u, h ^= h >> 16;
    return h;
}

float cryptomatteId(std::string_view name) {
    const std::uint32_t hash = murmurHash3(name);
    const std::uint32_t exponent = std::clamp<std::uint32_t>((hash >> 23) & 0xffu, 1u, 254u);
    const std::uint32_t bits = (hash & 0x807fffffu) | (exponent << 23);
    float id;
    std::memcpy(&id, &bits, sizeof id);
    return id;
}

std::string cryptomatteHex(float id) {
    std::uint32_t bits;
    std::memcpy(&bits, &id, sizeof bits);
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", bits);
    return hex;
}

std::string cryptomatteKey(std::string_view typeName) {
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", murmurHash3(typeName));
    return std::string(hex, 7);
}

std::string cryptomatteManifest(const std::vector<std::string>& names) {
    nlohmann::json manifest = nlohmann::json::object();
    for (const std::string& name : names) manifest[name] = cryptomatteHex(cryptomatteId(name));
    // A name that is not UTF-8 keeps its place, its bad bytes replaced (the ID hashes the bytes).
    return manifest.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::vector<std::string> cryptomatteManifestNames(const std::string& manifest) {
    const nlohmann::json json = nlohmann::json::parse(manifest, nullptr, /*allow_exceptions=*/false);
    std::vector<std::string> names;
    if (json.is_object())
        for (const auto& item : json.items()) names.push_back(item.key());
    return names;
}

int cryptomatteLayers(int ranks) { return (ranks + 1) / 2; }

std::string cryptomatteChannel(std::string_view typeName, int rank, bool isCoverage) {
    char layer[12];  // "%02d" of any int fits
    std::snprintf(layer, sizeof layer, "%02d", rank / 2);
    static constexpr const char* kChannels[] = {"r", "g", "b", "a"};  // as the specification and Blender name them
    return std::string(typeName) + layer + "." + kChannels[(rank % 2) * 2 + (isCoverage ? 1 : 0)];
}

}  // namespace streak
