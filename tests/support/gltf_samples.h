#pragma once

#include "support/gltf_builder.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace streak::test {

// Small valid glTF files that reach most of the loader: tests break them on purpose, and the
// fuzz target starts from them (tests/fuzz/write_seeds.cpp).

// A 1x1 white, opaque PNG.
inline std::vector<std::uint8_t> whitePng() {
    return {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
            0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
            0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8, 0xff, 0xff, 0xff, 0x3f, 0x00, 0x05, 0xfe, 0x02, 0xfe,
            0xa7, 0x35, 0x81, 0x84, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
}

// An indexed, textured triangle skinned to one joint (node 1) that an animation translates.
// Accessors: 0 POSITION, 1 TEXCOORD_0, 2 JOINTS_0, 3 WEIGHTS_0, 4 indices, 5 times, 6 values.
inline GltfBuilder skinnedTexturedTriangle() {
    using nlohmann::json;
    GltfBuilder b;
    json primitive;
    primitive["attributes"]["POSITION"] = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    primitive["attributes"]["TEXCOORD_0"] = b.addFloats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
    primitive["attributes"]["JOINTS_0"] = b.addAccessor(std::vector<std::uint8_t>(12, 0), "VEC4", 4, 5121);
    primitive["attributes"]["WEIGHTS_0"] = b.addFloats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
    primitive["indices"] = b.addIndices({0, 1, 2});
    primitive["material"] = 0;
    b.addMeshNode(primitive, {{"skin", 0}});
    b.json()["nodes"].push_back(json::object());  // node 1: the joint
    b.addToScene(1);
    b.json()["skins"] = {{{"joints", {1}}}};
    b.json()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    b.json()["textures"] = {{{"source", 0}}};
    b.json()["images"] = {{{"uri", "data:image/png;base64," + GltfBuilder::base64(whitePng())}}};
    const int times = b.addFloats({0, 1}, "SCALAR", 1);
    const int values = b.addFloats({0, 0, 0, 1, 0, 0}, "VEC3", 3);
    json animation;
    animation["samplers"] = json::array({{{"input", times}, {"output", values}}});
    animation["channels"] = json::array({{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}});
    b.json()["animations"] = json::array({animation});
    return b;
}

// A morphing strip with a sparse target, vertex colours, a masked texture with
// KHR_texture_transform, a cubic-spline weights animation and a perspective camera.
inline GltfBuilder morphingStripWithCamera() {
    using nlohmann::json;
    GltfBuilder b;
    b.json()["extensionsUsed"] = {"KHR_texture_transform"};
    json primitive = {{"mode", 5}, {"material", 0}};
    primitive["attributes"]["POSITION"] = b.addFloats({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0}, "VEC3", 3);
    primitive["attributes"]["NORMAL"] = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    primitive["attributes"]["TEXCOORD_0"] = b.addAccessor(std::vector<std::uint8_t>{0, 0, 0, 255, 255, 0, 255, 255}, "VEC2", 2, 5121, true);
    primitive["attributes"]["COLOR_0"] = b.addFloats({1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}, "VEC3", 3);
    const int sparseIndices = b.addView(std::vector<std::uint16_t>{3}.data(), 2);
    const std::vector<float> sparseValues{0, 0, 1};
    const int sparseView = b.addView(sparseValues.data(), 12);
    b.json()["accessors"].push_back({{"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                                     {"sparse", {{"count", 1}, {"indices", {{"bufferView", sparseIndices}, {"componentType", 5123}}},
                                                 {"values", {{"bufferView", sparseView}}}}}});
    primitive["targets"] = {{{"POSITION", b.json()["accessors"].size() - 1}}};
    b.json()["meshes"] = {{{"primitives", {primitive}}, {"weights", {0.5}}}};
    b.json()["nodes"] = {{{"mesh", 0}, {"rotation", {0, 0, std::sin(0.3), std::cos(0.3)}}},
                         {{"camera", 0}, {"translation", {0.5, 0.5, 3}}}};
    b.json()["scenes"] = {{{"nodes", {0, 1}}}};
    b.json()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}}}}};
    json transform = {{"offset", {0.25, 0}}, {"rotation", 0.5}, {"scale", {2, 2}}};
    b.json()["materials"] = {{{"alphaMode", "MASK"}, {"doubleSided", true},
                              {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}}}}}};
    b.json()["samplers"] = {{{"wrapS", 33648}, {"wrapT", 33071}}};
    b.json()["textures"] = {{{"source", 0}, {"sampler", 0}}};
    b.json()["images"] = {{{"uri", "data:image/png;base64," + GltfBuilder::base64(whitePng())}}};
    // CUBICSPLINE weights: in-tangent, value, out-tangent per key.
    const int times = b.addFloats({0, 0.5f, 1}, "SCALAR", 1);
    const int values = b.addFloats({0, 0, 1, 1, 1, 0, 0, 0, 0}, "SCALAR", 1);
    json animation = {{"name", "wobble"}};
    animation["samplers"] = json::array({{{"input", times}, {"output", values}, {"interpolation", "CUBICSPLINE"}}});
    animation["channels"] = json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}});
    b.json()["animations"] = json::array({animation});
    return b;
}

// Two square quads facing a camera 3 units away (through a narrow lens, yfov 0.2), red and
// green, slightly offset so both show, oscillating along the view axis in opposite phase
// (z = -3 -+ 0.005 sin(3 pi t)) over the first second (65 LINEAR keys, at t = k / 64): they pass
// through each other at t = 1/3 and 2/3, and which one shows flips there, while on screen
// their corners move by a tenth of a pixel of 240. With `quads` 1, only the red one.
inline GltfBuilder quadsThroughEachOther(int quads = 2) {
    using nlohmann::json;
    GltfBuilder b;
    b.json()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.1, 0.1, 1}}}}},
                             {{"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.8, 0.2, 1}}}}}};
    const int times = [&] {
        std::vector<float> t;
        for (int k = 0; k <= 64; ++k) t.push_back(float(k) / 64.0f);
        return b.addFloats(t, "SCALAR", 1);
    }();
    json animation;
    for (int q = 0; q < quads; ++q) {
        const float x = q == 0 ? -0.02f : 0.02f, y = q == 0 ? -0.015f : 0.015f, h = 0.12f;
        json primitive = {{"material", q}};
        primitive["attributes"]["POSITION"] = b.addFloats({x - h, y - h, 0, x + h, y - h, 0, x + h, y + h, 0, x - h, y + h, 0}, "VEC3", 3);
        primitive["indices"] = b.addIndices({0, 1, 2, 0, 2, 3});
        const int node = b.addMeshNode(primitive);
        std::vector<float> path;
        const float sign = q == 0 ? 1.0f : -1.0f;
        for (int k = 0; k <= 64; ++k) {
            const float t = float(k) / 64.0f;
            path.insert(path.end(), {0.0f, 0.0f, -3.0f + sign * 0.005f * float(std::sin(3.0 * 3.14159265358979 * double(t)))});
        }
        animation["samplers"].push_back({{"input", times}, {"output", b.addFloats(path, "VEC3", 3)}});
        animation["channels"].push_back({{"sampler", q}, {"target", {{"node", node}, {"path", "translation"}}}});
    }
    b.json()["animations"] = json::array({animation});
    b.json()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.2}, {"znear", 0.01}}}}};
    b.json()["nodes"].push_back({{"camera", 0}});
    b.addToScene(int(b.json()["nodes"].size() - 1));
    return b;
}

// A quad coloured by its corners, off the axis of a node that turns `degrees` about z at a
// steady speed over the animation's first second (rotation keys every 1/64 s, so the turn is a
// circle to well within a thousandth of a pixel), seen by a glTF camera 2 units up the z axis.
inline GltfBuilder spinningQuad(double degrees) {
    using nlohmann::json;
    GltfBuilder b;
    json primitive;
    primitive["attributes"]["POSITION"] = b.addFloats({0.1f, -0.25f, 0, 0.6f, -0.25f, 0, 0.6f, 0.25f, 0, 0.1f, 0.25f, 0}, "VEC3", 3);
    primitive["attributes"]["COLOR_0"] = b.addFloats({1, 0.2f, 0.1f, 1, 0.1f, 0.9f, 0.2f, 1, 0.2f, 0.3f, 1, 1, 0.9f, 0.9f, 0.1f, 1}, "VEC4", 4);
    primitive["indices"] = b.addIndices({0, 1, 2, 0, 2, 3});
    const int node = b.addMeshNode(primitive);
    std::vector<float> times, turns;
    for (int k = 0; k <= 64; ++k) {
        const double t = double(k) / 64.0, half = 0.5 * degrees * t * 3.14159265358979 / 180.0;
        times.push_back(float(t));
        turns.insert(turns.end(), {0.0f, 0.0f, float(std::sin(half)), float(std::cos(half))});
    }
    json animation;
    animation["samplers"].push_back({{"input", b.addFloats(times, "SCALAR", 1)}, {"output", b.addFloats(turns, "VEC4", 4)}});
    animation["channels"].push_back({{"sampler", 0}, {"target", {{"node", node}, {"path", "rotation"}}}});
    b.json()["animations"] = json::array({animation});
    b.json()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}}}}};
    b.json()["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 2}}});
    b.addToScene(int(b.json()["nodes"].size() - 1));
    return b;
}

}  // namespace streak::test
