#include "scene/gltf_writer.h"

#include "image/color.h"
#include "scene/gltf_document.h"
#include "util/error.h"

#include <glm/common.hpp>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <string>

namespace streak {

namespace {

using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

int wrapCode(WrapMode mode) {
    switch (mode) {
    case WrapMode::ClampToEdge: return 33071;
    case WrapMode::MirroredRepeat: return 33648;
    case WrapMode::Repeat:
    default: return 10497;
    }
}

// The document and its one binary buffer, built up together.
class GlbBuilder {
public:
    json doc = {{"asset", {{"version", "2.0"}, {"generator", "streak export"}}},
                {"buffers", json::array()},
                {"bufferViews", json::array()},
                {"accessors", json::array()}};

    // Appends bytes (4-aligned) as a buffer view; returns its index.
    int addView(const void* data, std::size_t bytes, int target = 0) {
        while (m_bin.size() % 4 != 0) m_bin.push_back(0);
        json view = {{"buffer", 0}, {"byteOffset", m_bin.size()}, {"byteLength", bytes}};
        if (target) view["target"] = target;
        const auto* p = static_cast<const std::uint8_t*>(data);
        m_bin.insert(m_bin.end(), p, p + bytes);
        doc["bufferViews"].push_back(view);
        return int(doc["bufferViews"].size()) - 1;
    }

    // A float accessor of `count` elements of `components` floats; min and max per component
    // where glTF requires them (positions, animation inputs).
    int addFloats(const float* data, std::size_t count, int components, bool withBounds, int target = 0) {
        static const char* const kTypes[] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};
        json accessor = {{"bufferView", addView(data, count * std::size_t(components) * sizeof(float), target)},
                         {"componentType", kFloat},
                         {"count", count},
                         {"type", kTypes[components]}};
        if (withBounds) {
            std::vector<float> lo(data, data + components), hi(lo);
            for (std::size_t i = 0; i < count; ++i)
                for (int c = 0; c < components; ++c) {
                    lo[std::size_t(c)] = std::min(lo[std::size_t(c)], data[i * std::size_t(components) + std::size_t(c)]);
                    hi[std::size_t(c)] = std::max(hi[std::size_t(c)], data[i * std::size_t(components) + std::size_t(c)]);
                }
            accessor["min"] = lo;
            accessor["max"] = hi;
        }
        doc["accessors"].push_back(accessor);
        return int(doc["accessors"].size()) - 1;
    }

    template <class Vec>
    int addVectors(const std::vector<Vec>& values, bool withBounds, int target = kArrayBuffer) {
        return addFloats(&values[0][0], values.size(), Vec::length(), withBounds, target);
    }

    int addIndices(const std::vector<glm::uvec3>& triangles) {
        json accessor = {{"bufferView", addView(triangles.data(), triangles.size() * sizeof(glm::uvec3), kElementArrayBuffer)},
                         {"componentType", kUnsignedInt},
                         {"count", triangles.size() * 3},
                         {"type", "SCALAR"}};
        doc["accessors"].push_back(accessor);
        return int(doc["accessors"].size()) - 1;
    }

    std::vector<std::uint8_t> finish() {
        while (m_bin.size() % 4 != 0) m_bin.push_back(0);
        doc["buffers"].push_back({{"byteLength", m_bin.size()}});
        std::string text = doc.dump();
        while (text.size() % 4 != 0) text.push_back(' ');
        std::vector<std::uint8_t> out;
        auto word = [&](std::uint32_t v) {
            for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
        };
        word(0x46546C67);  // "glTF"
        word(2);
        word(std::uint32_t(12 + 8 + text.size() + 8 + m_bin.size()));
        word(std::uint32_t(text.size()));
        word(0x4E4F534A);  // "JSON"
        out.insert(out.end(), text.begin(), text.end());
        word(std::uint32_t(m_bin.size()));
        word(0x004E4942);  // "BIN\0"
        out.insert(out.end(), m_bin.begin(), m_bin.end());
        return out;
    }

    // The document as .gltf text, the buffer inlined as a data: uri.
    std::string finishText() {
        while (m_bin.size() % 4 != 0) m_bin.push_back(0);
        doc["buffers"].push_back({{"byteLength", m_bin.size()}, {"uri", "data:application/octet-stream;base64," + gltf::base64(m_bin)}});
        return doc.dump();
    }

private:
    std::vector<std::uint8_t> m_bin;
};

// Level 0 of a texture as an 8-bit sRGB RGBA PNG.
std::vector<std::uint8_t> texturePng(const Texture& texture) {
    const int w = texture.width(), h = texture.height();
    std::vector<std::uint8_t> rgba(std::size_t(w) * std::size_t(h) * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec4& t = texture.texel(0, x, y);
            std::uint8_t* p = &rgba[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4];
            p[0] = linearToSrgb8(t.x), p[1] = linearToSrgb8(t.y), p[2] = linearToSrgb8(t.z);
            p[3] = std::uint8_t(std::lround(std::clamp(t.w, 0.0f, 1.0f) * 255.0f));
        }
    std::vector<std::uint8_t> png;
    auto append = [](void* context, void* data, int size) {
        auto* bytes = static_cast<std::vector<std::uint8_t>*>(context);
        bytes->insert(bytes->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
    };
    if (!stbi_write_png_to_func(append, &png, w, h, 4, rgba.data(), w * 4)) throw Error("cannot encode a texture as PNG");
    return png;
}

json material(const Material& m) {
    json pbr = {{"baseColorFactor", {m.baseColor.x, m.baseColor.y, m.baseColor.z, m.opacity}},
                {"metallicFactor", 0.0},
                {"roughnessFactor", 1.0}};
    if (m.baseColorTexture >= 0) pbr["baseColorTexture"] = {{"index", m.baseColorTexture}};
    json out = {{"name", m.name}, {"pbrMetallicRoughness", pbr}, {"doubleSided", m.doubleSided}};
    if (m.alphaMode == AlphaMode::Mask) {
        out["alphaMode"] = "MASK";
        out["alphaCutoff"] = m.alphaCutoff;
    } else if (m.alphaMode == AlphaMode::Blend || m.opacity < 1.0f) {
        out["alphaMode"] = "BLEND";  // streak blends an Opaque material whose opacity is below 1
    } else {
        out["alphaMode"] = "OPAQUE";
    }
    return out;
}

json quaternion(const glm::quat& q) { return {q.x, q.y, q.z, q.w}; }  // glTF order

}  // namespace

namespace {

void buildDocument(const Scene& scene, GlbBuilder& b) {
    json nodes = json::array(), meshes = json::array(), samplers = json::array(), channels = json::array();

    // Camera first, so a loader's default (the first camera a node places) is this one.
    const Camera& camera = scene.camera;
    const glm::vec3 p0 = camera.open.position;
    nodes.push_back({{"name", "camera"}, {"camera", 0}, {"translation", {p0.x, p0.y, p0.z}},
                     {"rotation", quaternion(camera.open.worldFromCamera)}});
    b.doc["cameras"] = json::array(
        {{{"type", "perspective"}, {"perspective", {{"yfov", camera.verticalFov}, {"znear", camera.zNear}}}}});
    std::map<int, int> keyTimes;  // numKeys -> accessor of k / (K-1) seconds
    auto times = [&](int numKeys) {
        if (auto it = keyTimes.find(numKeys); it != keyTimes.end()) return it->second;
        std::vector<float> t;
        for (int k = 0; k < numKeys; ++k) t.push_back(keyTime(k, numKeys));
        return keyTimes[numKeys] = b.addFloats(t.data(), t.size(), 1, true);
    };
    if (!camera.isStatic()) {
        const std::vector<glm::vec3> positions{camera.open.position, camera.close.position};
        glm::quat q1 = camera.close.worldFromCamera;
        if (glm::dot(camera.open.worldFromCamera, q1) < 0.0f) q1 = -q1;  // the same rotation, the short way
        const std::vector<glm::vec4> rotations{{camera.open.worldFromCamera.x, camera.open.worldFromCamera.y,
                                                camera.open.worldFromCamera.z, camera.open.worldFromCamera.w},
                                               {q1.x, q1.y, q1.z, q1.w}};
        for (const auto& [path, output] : {std::pair{"translation", b.addVectors(positions, false, 0)},
                                           std::pair{"rotation", b.addVectors(rotations, false, 0)}}) {
            samplers.push_back({{"input", times(2)}, {"output", output}, {"interpolation", "LINEAR"}});
            channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", 0}, {"path", path}}}});
        }
    }

    for (const Mesh& mesh : scene.meshes) {
        if (mesh.triangles.empty() || mesh.numVertices() == 0) continue;
        const bool moves = !mesh.isStatic();
        if (moves && mesh.isCurved())
            throw Error("mesh '" + mesh.name + "': Bezier keys cannot be written as glTF morph targets");
        const std::size_t n = mesh.numVertices();
        auto key = [&](const std::vector<glm::vec3>& values, int k) {
            return std::vector<glm::vec3>(values.begin() + std::ptrdiff_t(std::size_t(k) * n),
                                          values.begin() + std::ptrdiff_t(std::size_t(k + 1) * n));
        };
        json attributes = {{"POSITION", b.addVectors(key(mesh.positions, 0), true)}};
        if (mesh.hasNormals()) attributes["NORMAL"] = b.addVectors(key(mesh.normals, 0), false);
        if (mesh.hasUvs()) attributes["TEXCOORD_0"] = b.addVectors(mesh.uvs, false);
        if (mesh.hasColors()) attributes["COLOR_0"] = b.addVectors(mesh.colors, false);
        json primitive = {{"attributes", attributes}, {"indices", b.addIndices(mesh.triangles)},
                          {"material", mesh.material}, {"mode", 4}};
        json out = {{"name", mesh.name}, {"primitives", json::array()}};
        if (moves) {
            json targets = json::array();
            for (int k = 1; k < mesh.numKeys; ++k) {
                std::vector<glm::vec3> dp = key(mesh.positions, k), dn;
                for (std::size_t v = 0; v < n; ++v) dp[v] -= mesh.positions[v];
                json target = {{"POSITION", b.addVectors(dp, true)}};
                if (mesh.hasNormals()) {
                    dn = key(mesh.normals, k);
                    for (std::size_t v = 0; v < n; ++v) dn[v] -= mesh.normals[v];
                    target["NORMAL"] = b.addVectors(dn, false);
                }
                targets.push_back(target);
            }
            primitive["targets"] = targets;
            out["weights"] = std::vector<float>(std::size_t(mesh.numKeys - 1), 0.0f);
            // At key k's time the weights are one-hot on target k-1 (all zero at key 0).
            std::vector<float> weights(std::size_t(mesh.numKeys) * std::size_t(mesh.numKeys - 1), 0.0f);
            for (int k = 1; k < mesh.numKeys; ++k) weights[std::size_t(k) * std::size_t(mesh.numKeys - 1) + std::size_t(k - 1)] = 1.0f;
            samplers.push_back({{"input", times(mesh.numKeys)},
                                {"output", b.addFloats(weights.data(), weights.size(), 1, false)},
                                {"interpolation", "LINEAR"}});
            channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", nodes.size()}, {"path", "weights"}}}});
        }
        out["primitives"].push_back(primitive);
        nodes.push_back({{"name", mesh.name}, {"mesh", meshes.size()}});
        meshes.push_back(out);
    }

    json materials = json::array(), textures = json::array(), images = json::array(), textureSamplers = json::array();
    for (const Material& m : scene.materials) materials.push_back(material(m));
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& texture = scene.textures[i];
        const std::vector<std::uint8_t> png = texturePng(texture);
        images.push_back({{"bufferView", b.addView(png.data(), png.size())}, {"mimeType", "image/png"}});
        textureSamplers.push_back({{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", wrapCode(texture.wrapU())},
                                   {"wrapT", wrapCode(texture.wrapV())}});
        textures.push_back({{"sampler", i}, {"source", i}});
    }

    json roots = json::array();
    for (std::size_t i = 0; i < nodes.size(); ++i) roots.push_back(i);
    b.doc["scene"] = 0;
    b.doc["scenes"] = json::array({{{"name", scene.name}, {"nodes", roots}}});
    b.doc["nodes"] = nodes;
    if (!meshes.empty()) b.doc["meshes"] = meshes;
    if (!materials.empty()) b.doc["materials"] = materials;
    if (!textures.empty()) {
        b.doc["textures"] = textures;
        b.doc["images"] = images;
        b.doc["samplers"] = textureSamplers;
    }
    if (!channels.empty())
        b.doc["animations"] = json::array({{{"name", "shutter"}, {"samplers", samplers}, {"channels", channels}}});
}

}  // namespace

std::vector<std::uint8_t> writeGltfBinary(const Scene& scene) {
    GlbBuilder b;
    buildDocument(scene, b);
    return b.finish();
}

std::string writeGltfText(const Scene& scene) {
    GlbBuilder b;
    buildDocument(scene, b);
    return b.finishText();
}

}  // namespace streak
