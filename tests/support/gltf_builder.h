#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace streak::test {

// GltfBuilder writes small glTF 2.0 files for tests: one binary buffer, accessors appended to
// it, and the JSON open to any edit (tests break files on purpose). gltf() embeds the buffer
// as a base64 data uri; glb() writes the binary container.
class GltfBuilder {
public:
    GltfBuilder() { m_json = {{"asset", {{"version", "2.0"}}}}; }

    nlohmann::json& json() { return m_json; }

    // Appends raw bytes (4-byte aligned) as a new buffer view; returns its index.
    int addView(const void* data, std::size_t size, int byteStride = 0) {
        while (m_buffer.size() % 4) m_buffer.push_back(0);
        nlohmann::json view = {{"buffer", 0}, {"byteOffset", m_buffer.size()}, {"byteLength", size}};
        if (byteStride) view["byteStride"] = byteStride;
        const auto* bytes = static_cast<const std::uint8_t*>(data);
        m_buffer.insert(m_buffer.end(), bytes, bytes + size);
        m_json["bufferViews"].push_back(view);
        return int(m_json["bufferViews"].size() - 1);
    }

    // An accessor over new data: `type` is "SCALAR", "VEC3"... with `components` values each.
    template <class T>
    int addAccessor(const std::vector<T>& values, const std::string& type, int components, int componentType, bool normalized = false) {
        const int view = addView(values.data(), values.size() * sizeof(T));
        nlohmann::json accessor = {{"bufferView", view}, {"componentType", componentType}, {"count", values.size() / std::size_t(components)},
                                   {"type", type}};
        if (normalized) accessor["normalized"] = true;
        m_json["accessors"].push_back(accessor);
        return int(m_json["accessors"].size() - 1);
    }
    int addFloats(const std::vector<float>& values, const std::string& type, int components) {
        return addAccessor(values, type, components, 5126);
    }
    int addIndices(const std::vector<std::uint16_t>& indices) { return addAccessor(indices, "SCALAR", 1, 5123); }

    // A node with a one-primitive mesh; returns the node index. The node is added to scene 0.
    int addMeshNode(const nlohmann::json& primitive, const nlohmann::json& nodeExtras = nlohmann::json::object()) {
        m_json["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
        nlohmann::json node = nodeExtras;
        node["mesh"] = m_json["meshes"].size() - 1;
        m_json["nodes"].push_back(node);
        const int index = int(m_json["nodes"].size() - 1);
        addToScene(index);
        return index;
    }
    void addToScene(int node) {
        if (!m_json.contains("scenes")) m_json["scenes"] = {{{"nodes", nlohmann::json::array()}}};
        m_json["scenes"][0]["nodes"].push_back(node);
    }

    const std::vector<std::uint8_t>& buffer() const { return m_buffer; }

    std::string gltf() const {
        nlohmann::json j = m_json;
        if (!m_buffer.empty())
            j["buffers"] = {{{"byteLength", m_buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(m_buffer)}}};
        return j.dump();
    }
    std::vector<std::uint8_t> gltfBytes() const {
        const std::string text = gltf();
        return {text.begin(), text.end()};
    }

    std::vector<std::uint8_t> glb() const {
        nlohmann::json j = m_json;
        std::vector<std::uint8_t> bin = m_buffer;
        while (bin.size() % 4) bin.push_back(0);
        if (!bin.empty()) j["buffers"] = {{{"byteLength", m_buffer.size()}}};
        std::string text = j.dump();
        while (text.size() % 4) text.push_back(' ');
        std::vector<std::uint8_t> out;
        auto u32 = [&](std::uint32_t v) {
            for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
        };
        const std::uint32_t length = std::uint32_t(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size()));
        for (const char c : {'g', 'l', 'T', 'F'}) out.push_back(std::uint8_t(c));
        u32(2);
        u32(length);
        u32(std::uint32_t(text.size()));
        u32(0x4E4F534A);  // JSON
        out.insert(out.end(), text.begin(), text.end());
        if (!bin.empty()) {
            u32(std::uint32_t(bin.size()));
            u32(0x004E4942);  // BIN
            out.insert(out.end(), bin.begin(), bin.end());
        }
        return out;
    }

    static std::string base64(const std::vector<std::uint8_t>& data) {
        static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string out;
        for (std::size_t i = 0; i < data.size(); i += 3) {
            const std::uint32_t n = std::uint32_t(data[i]) << 16 | (i + 1 < data.size() ? std::uint32_t(data[i + 1]) << 8 : 0) |
                                    (i + 2 < data.size() ? data[i + 2] : 0);
            out += kAlphabet[n >> 18 & 63];
            out += kAlphabet[n >> 12 & 63];
            out += i + 1 < data.size() ? kAlphabet[n >> 6 & 63] : '=';
            out += i + 2 < data.size() ? kAlphabet[n & 63] : '=';
        }
        return out;
    }

private:
    nlohmann::json m_json;
    std::vector<std::uint8_t> m_buffer;
};

}  // namespace streak::test
