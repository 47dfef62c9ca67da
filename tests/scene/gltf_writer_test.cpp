#include "scene/gltf_writer.h"

#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/scene_loader.h"
#include "util/error.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace streak {
namespace {

// Loads an exported scene back as `streak render x.glb --frame 0 --shutter 24 --fps 24
// --motion-keys K` would: the shutter is the animation's first second.
Scene loadBack(const std::vector<std::uint8_t>& bytes, int motionKeys) {
    GltfOptions options;
    options.frame = 0.0;
    options.shutter = 24.0;
    options.fps = 24.0;
    options.motionKeys = motionKeys;
    options.allowExternalFiles = false;
    return loadGltfFromMemory(bytes, "export.glb", "", options);
}

void expectSamePose(const CameraPose& a, const CameraPose& b) {
    EXPECT_LT(glm::length(a.position - b.position), 1e-5f * (1.0f + glm::length(a.position)));
    EXPECT_GT(std::abs(glm::dot(a.worldFromCamera, b.worldFromCamera)), 1.0f - 1e-6f);
}

void expectSameMaterial(const Scene& original, std::uint32_t a, const Scene& loaded, std::uint32_t b) {
    const Material& m = original.materials[a];
    const Material& n = loaded.materials[b];
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(m.baseColor[c], n.baseColor[c]) << m.name;
    EXPECT_FLOAT_EQ(m.opacity, n.opacity) << m.name;
    // streak blends an Opaque material whose opacity is below 1; glTF calls that BLEND.
    const AlphaMode expected = m.alphaMode == AlphaMode::Opaque && m.opacity < 1.0f ? AlphaMode::Blend : m.alphaMode;
    EXPECT_EQ(int(expected), int(n.alphaMode)) << m.name;
    EXPECT_EQ(m.isTranslucent(), n.isTranslucent()) << m.name;
    EXPECT_EQ(m.doubleSided, n.doubleSided) << m.name;
    ASSERT_EQ(m.baseColorTexture >= 0, n.baseColorTexture >= 0) << m.name;
    if (m.baseColorTexture < 0) return;
    const Texture& s = original.textures[std::size_t(m.baseColorTexture)];
    const Texture& t = loaded.textures[std::size_t(n.baseColorTexture)];
    ASSERT_EQ(s.width(), t.width());
    ASSERT_EQ(s.height(), t.height());
    EXPECT_EQ(int(s.wrapU()), int(t.wrapU()));
    EXPECT_EQ(int(s.wrapV()), int(t.wrapV()));
    float worst = 0.0f;
    for (int y = 0; y < s.height(); ++y)
        for (int x = 0; x < s.width(); ++x) worst = std::max(worst, glm::length(s.texel(0, x, y) - t.texel(0, x, y)));
    EXPECT_LT(worst, 1e-6f) << m.name << ": the built-in textures are 8-bit sRGB, so the PNG holds them exactly";
}

// One triangle, alone in a scene, through three keys; key k is offset by offsetX(k) in x.
template <class Offset>
Scene triangleScene(MotionInterpolation interpolation, Offset offsetX) {
    Scene scene;
    scene.materials.push_back(Material{});
    Mesh mesh;
    mesh.name = "tri";
    mesh.numKeys = 3;
    mesh.interpolation = interpolation;
    mesh.triangles = {{0, 1, 2}};
    for (int k = 0; k < 3; ++k)
        for (const glm::vec3& p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)})
            mesh.positions.push_back(p + glm::vec3(offsetX(k), 0.0f, -1.0f));
    scene.meshes.push_back(mesh);
    return scene;
}

class GltfWriter : public ::testing::TestWithParam<std::string> {};

// Every built-in scene written out and read back by streak's own glTF loader is the scene:
// every key pose of every vertex (at the loaded keys' times, which are the written keys'),
// triangles, uvs, materials, textures and the camera at shutter open and close.
TEST_P(GltfWriter, BuiltinSceneRoundTripsThroughTheGltfLoader) {
    Scene original = loadScene("builtin:" + GetParam());
    validateScene(original);
    int numKeys = 2;
    for (const Mesh& mesh : original.meshes) numKeys = std::max(numKeys, mesh.numKeys);
    const Scene loaded = loadBack(writeGltfBinary(original), numKeys);

    ASSERT_EQ(loaded.meshes.size(), original.meshes.size());
    for (std::size_t i = 0; i < original.meshes.size(); ++i) {
        const Mesh& m = original.meshes[i];
        const Mesh& n = loaded.meshes[i];
        SCOPED_TRACE(m.name);
        ASSERT_EQ(n.numVertices(), m.numVertices());
        ASSERT_EQ(n.triangles, m.triangles);
        // (The loader keeps uvs only where a texture needs them.)
        if (original.materials[m.material].baseColorTexture >= 0) {
            EXPECT_EQ(n.uvs, m.uvs);
        }
        ASSERT_EQ(n.numKeys, numKeys);
        float worst = 0.0f, scale = 1.0f;
        for (int k = 0; k < n.numKeys; ++k) {
            const MotionWeights w = m.weightsAt(keyTime(k, n.numKeys));
            for (std::uint32_t v = 0; v < m.numVertices(); ++v) {
                const glm::vec3 expected = m.positionAt(v, w);
                scale = std::max(scale, glm::length(expected));
                worst = std::max(worst, glm::length(n.keyPositions(k)[v] - expected));
            }
        }
        EXPECT_LT(worst, 1e-5f * scale);
        expectSameMaterial(original, m.material, loaded, n.material);
    }
    expectSamePose(loaded.camera.open, original.camera.open);
    expectSamePose(loaded.camera.close, original.camera.close);
    EXPECT_FLOAT_EQ(loaded.camera.verticalFov, original.camera.verticalFov);
    EXPECT_FLOAT_EQ(loaded.camera.zNear, original.camera.zNear);
}

INSTANTIATE_TEST_SUITE_P(Builtins, GltfWriter,
                         ::testing::Values("cubes?n=12&keys=3", "rotating-cube?keys=5", "crossing", "twist", "fence",
                                           "pan", "translucent"),
                         [](const auto& info) {
                             std::string name = info.param.substr(0, info.param.find('?'));
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

TEST(GltfWriterFormat, BinaryLayoutAndMorphWeights) {
    // One triangle moving through three keys: POSITION is key 0, two targets hold the offsets
    // of keys 1 and 2, and the weights are (0,0), (1,0), (0,1) at 0, 0.5 and 1 s.
    const Scene scene = triangleScene(MotionInterpolation::PiecewiseLinear, [](int k) { return 0.5f * float(k * k); });
    const std::vector<std::uint8_t> bytes = writeGltfBinary(scene);
    ASSERT_GE(bytes.size(), 28u);
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), "glTF");
    auto word = [&](std::size_t at) {
        return std::uint32_t(bytes[at]) | std::uint32_t(bytes[at + 1]) << 8 | std::uint32_t(bytes[at + 2]) << 16 |
               std::uint32_t(bytes[at + 3]) << 24;
    };
    EXPECT_EQ(word(4), 2u);
    EXPECT_EQ(word(8), bytes.size());
    EXPECT_EQ(word(12) % 4, 0u);
    // The motion between the keys is linear: half way to key 1 (0.25 s) the triangle is at
    // x + 0.25; between keys 1 and 2 (0.75 s) at x + 0.5 + 1.5 * 0.5 = x + 1.25.
    const Scene loaded = loadBack(bytes, 5);
    ASSERT_EQ(loaded.meshes.size(), 1u);
    const float expectedX[] = {0.0f, 0.25f, 0.5f, 1.25f, 2.0f};
    for (int k = 0; k < 5; ++k) EXPECT_NEAR(loaded.meshes[0].keyPositions(k)[1].x, 1.0f + expectedX[k], 1e-6f) << k;
}

TEST(GltfWriterFormat, BezierKeysAreRefused) {
    EXPECT_THROW(writeGltfBinary(triangleScene(MotionInterpolation::Bezier, [](int k) { return float(k); })), Error);
}

}  // namespace
}  // namespace streak
