// Point caches (PC2, MDD): parsed against hand-built files, and applied to a glTF mesh in place
// of its animation (object and world space, several meshes, bad caches).

#include "scene/gltf_loader.h"
#include "scene/point_cache.h"
#include "util/error.h"

#include "support/gltf_builder.h"
#include "support/point_cache_files.h"
#include "support/expect_error.h"
#include "support/temp_dir.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace streak {
namespace {

using test::mddBytes;
using test::pc2Bytes;
using test::writeBytes;

using test::expectErrorContaining;

glm::vec3 pointAt(const PointCache& cache, double seconds, std::size_t i) {
    std::vector<glm::vec3> out(1);
    cache.pointsAt(seconds, i, 1, out);
    return out[0];
}

// Two points over three samples from frame 10, one every 2 frames, at 24 fps: at a sample time a
// point is the sample; between two, on the line between them; outside, the nearest end.
TEST(PointCache, Pc2SamplesAtItsFramesAndLinesBetween) {
    const std::vector<std::vector<glm::vec3>> samples{{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {1, 3, 1}}, {{2, 4, 0}, {1, 3, 5}}};
    const PointCache cache = PointCache::parse(pc2Bytes(samples, 10.0f, 2.0f), false, 24.0, "test.pc2");
    EXPECT_EQ(cache.numPoints(), 2u);
    EXPECT_EQ(cache.numSamples(), 3u);
    EXPECT_DOUBLE_EQ(cache.firstTime(), 10.0 / 24.0);
    EXPECT_DOUBLE_EQ(cache.lastTime(), 14.0 / 24.0);
    EXPECT_EQ(pointAt(cache, 12.0 / 24.0, 1), glm::vec3(1, 3, 1));
    const glm::vec3 quarter = pointAt(cache, 12.5 / 24.0, 0);  // a quarter of the way from sample 1 to 2
    EXPECT_NEAR(quarter.x, 2.0f, 1e-6f); EXPECT_NEAR(quarter.y, 1.0f, 1e-6f); EXPECT_NEAR(quarter.z, 0.0f, 1e-6f);
    EXPECT_EQ(pointAt(cache, 0.0, 0), glm::vec3(0, 0, 0));
    EXPECT_EQ(pointAt(cache, 100.0, 1), glm::vec3(1, 3, 5));
}

// MDD is big-endian with times in seconds; Blender's export writes a rest pose before the frames,
// which is skipped. Both read as the PC2 of the same samples.
TEST(PointCache, MddReadsWithAndWithoutARestPose) {
    const std::vector<std::vector<glm::vec3>> frames{{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {1, 3, 1}}};
    const std::vector<glm::vec3> rest{{9, 9, 9}, {9, 9, 9}};
    for (const bool hasRest : {false, true}) {
        SCOPED_TRACE(hasRest);
        const PointCache cache = PointCache::parse(mddBytes(frames, {0.5f, 1.0f}, hasRest ? &rest : nullptr), true, 24.0, "test.mdd");
        EXPECT_EQ(cache.numSamples(), 2u);
        EXPECT_EQ(pointAt(cache, 0.5, 0), glm::vec3(0, 0, 0));
        EXPECT_EQ(pointAt(cache, 0.75, 1), glm::vec3(1, 2, 1));
        EXPECT_EQ(pointAt(cache, 2.0, 0), glm::vec3(2, 0, 0));
    }
}

TEST(PointCache, BadFilesAreOneErrorNamingTheProblem) {
    const std::vector<std::vector<glm::vec3>> samples{{{0, 0, 0}}, {{1, 0, 0}}};
    std::vector<char> bytes = pc2Bytes(samples, 0.0f, 1.0f);
    bytes[0] = 'X';
    expectErrorContaining([&] { PointCache::parse(bytes, false, 24.0, "a.pc2"); }, "no POINTCACHE2 signature");
    bytes = pc2Bytes(samples, 0.0f, 1.0f);
    bytes.pop_back();
    expectErrorContaining([&] { PointCache::parse(bytes, false, 24.0, "a.pc2"); }, "too short for 2 samples of 1 points");
    bytes = pc2Bytes(samples, 0.0f, 1.0f);
    bytes.push_back(0);
    expectErrorContaining([&] { PointCache::parse(bytes, false, 24.0, "a.pc2"); }, "do not make 2 samples of 1 points");
    bytes = pc2Bytes(samples, 0.0f, 1.0f);
    bytes[28] = bytes[29] = bytes[30] = char(0xff), bytes[31] = 0x7f;  // 2^31 - 1 samples in a 56-byte file
    expectErrorContaining([&] { PointCache::parse(bytes, false, 24.0, "a.pc2"); }, "too short for 2147483647 samples");
    expectErrorContaining([&] { PointCache::parse(pc2Bytes(samples, 0.0f, 0.0f), false, 24.0, "a.pc2"); }, "sample rate positive");
    bytes = pc2Bytes(samples, 0.0f, 1.0f);
    bytes[12] = 2;  // version
    expectErrorContaining([&] { PointCache::parse(bytes, false, 24.0, "a.pc2"); }, "version 2");
    expectErrorContaining([&] { PointCache::parse(mddBytes(samples, {1.0f, 0.5f}), true, 24.0, "a.mdd"); }, "finite and increasing");
    expectErrorContaining([&] { PointCache::parse(std::vector<char>(6, 0), true, 24.0, "a.mdd"); }, "ends inside its header");
    test::TempDir dir;
    expectErrorContaining([&] { PointCache::read(dir.file("missing.pc2"), 24.0, 1u << 20); }, "cannot read");
    expectErrorContaining([&] { PointCache::read(dir.file("cache.abc"), 24.0, 1u << 20); }, "a .pc2 or .mdd file");
    writeBytes(dir.file("big.pc2"), pc2Bytes(samples, 0.0f, 1.0f));
    expectErrorContaining([&] { PointCache::read(dir.file("big.pc2"), 24.0, 16); }, "is larger than 16 bytes");
}

// A triangle on node "tri" (translated by (0, 0, -5), no animation) and a still quad on node
// "quad": the cache moves the triangle's vertices in its node's space, the node places them.
test::GltfBuilder twoMeshes() {
    test::GltfBuilder b;
    nlohmann::json tri, quad;
    tri["attributes"]["POSITION"] = b.addFloats({-1, -1, 0, 1, -1, 0, 0, 1, 0}, "VEC3", 3);
    quad["attributes"]["POSITION"] = b.addFloats({-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1}, "VEC3", 3);
    quad["indices"] = b.addIndices({0, 1, 2, 0, 2, 3});
    const int t = b.addMeshNode(tri), q = b.addMeshNode(quad);
    b.json()["nodes"][t]["name"] = "tri";
    b.json()["nodes"][t]["translation"] = {0.0, 0.0, -5.0};
    b.json()["nodes"][q]["name"] = "quad";
    return b;
}

TEST(PointCache, MovesTheNamedMeshInItsNodesSpaceOrInWorldSpace) {
    test::TempDir dir;
    const std::string path = dir.file("tri.gltf");
    const std::vector<std::uint8_t> gltf = twoMeshes().gltfBytes();
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(gltf.data()), std::streamsize(gltf.size()));
    // The triangle slides 2 along x from frame 0 to frame 24 (two samples, 24 frames apart).
    const std::vector<glm::vec3> rest{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    std::vector<glm::vec3> moved = rest;
    for (glm::vec3& p : moved) p.x += 2.0f;
    writeBytes(dir.file("slide.pc2"), pc2Bytes({rest, moved}, 0.0f, 24.0f));
    GltfOptions options;
    options.frame = 6.0, options.shutter = 12.0, options.motionKeys = 3;  // 0.25 s to 0.75 s: x + 0.5, + 1, + 1.5
    options.pointCache = GltfPointCache{dir.file("slide.pc2"), "tri", false};
    RenderStats stats;
    const Scene scene = loadGltf(path, options, &stats);
    ASSERT_EQ(scene.meshes.size(), 2u);
    const Mesh& tri = scene.meshes[0].name == "tri" ? scene.meshes[0] : scene.meshes[1];
    const Mesh& quad = scene.meshes[0].name == "tri" ? scene.meshes[1] : scene.meshes[0];
    ASSERT_EQ(tri.numKeys, 3);
    for (int k = 0; k < 3; ++k)
        for (std::size_t v = 0; v < 3; ++v) {
            const glm::vec3 expected = rest[v] + glm::vec3(0.5f + 0.5f * float(k), 0.0f, -5.0f);
            const glm::vec3 got = tri.positions[std::size_t(k) * 3 + v];
            EXPECT_NEAR(got.x, expected.x, 1e-6f); EXPECT_NEAR(got.y, expected.y, 1e-6f); EXPECT_NEAR(got.z, expected.z, 1e-6f);
        }
    for (int k = 0; k < quad.numKeys; ++k) EXPECT_EQ(quad.positions[std::size_t(k) * 4], glm::vec3(-1, -1, -1));  // the quad stays
    EXPECT_EQ(stats.counter("point_cache_points"), 3.0);
    EXPECT_EQ(stats.counter("point_cache_samples"), 2.0);

    options.pointCache->isWorldSpace = true;  // the same points, not moved by the node
    const Scene world = loadGltf(path, options);
    const Mesh& worldTri = world.meshes[0].name == "tri" ? world.meshes[0] : world.meshes[1];
    EXPECT_NEAR(worldTri.positions[0].z, 0.0f, 1e-6f);
    EXPECT_NEAR(worldTri.positions[0].x, -0.5f, 1e-6f);

    options.pointCache->mesh = "";
    expectErrorContaining([&] { loadGltf(path, options); }, "the scene has 2 meshes; name the one it moves with --point-cache-mesh");
    options.pointCache->mesh = "cone";
    expectErrorContaining([&] { loadGltf(path, options); }, "--point-cache-mesh 'cone': no node or mesh");
    options.pointCache->mesh = "quad";
    expectErrorContaining([&] { loadGltf(path, options); }, "the cache has 3 points, the mesh it moves 4 vertices");
}

// A glTF file of one triangle (corners `rest`, normals +z, which the cache's points replace)
// on a node scaled by `scale`; returns its path.
std::string writeTriangleWithNormals(test::TempDir& dir, const std::string& name, const std::vector<glm::vec3>& rest, const glm::vec3& scale) {
    test::GltfBuilder b;
    nlohmann::json tri;
    std::vector<float> positions;
    for (const glm::vec3& p : rest) positions.insert(positions.end(), {p.x, p.y, p.z});
    tri["attributes"]["POSITION"] = b.addFloats(positions, "VEC3", 3);
    tri["attributes"]["NORMAL"] = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    const int node = b.addMeshNode(tri);
    if (scale != glm::vec3(1.0f)) b.json()["nodes"][node]["scale"] = {scale.x, scale.y, scale.z};
    const std::vector<std::uint8_t> gltf = b.gltfBytes();
    const std::string path = dir.file(name);
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(gltf.data()), std::streamsize(gltf.size()));
    return path;
}

// Under a mirroring node (scale -1 in x) the drawn triangles are flipped back to
// counter-clockwise in front (glTF 3.7.4), and the normals made from the cache's points face
// the way the drawn triangles do, in the node's space and in world space alike.
TEST(PointCache, NormalsFaceTheDrawnTrianglesUnderAMirroringNode) {
    test::TempDir dir;
    const std::vector<glm::vec3> rest{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    const std::string path = writeTriangleWithNormals(dir, "mirrored.gltf", rest, glm::vec3(-1.0f, 1.0f, 1.0f));
    std::vector<glm::vec3> moved = rest;
    for (glm::vec3& p : moved) p.y += 1.0f;
    writeBytes(dir.file("up.pc2"), pc2Bytes({rest, moved}, 0.0f, 24.0f));
    for (const bool isWorld : {false, true}) {
        SCOPED_TRACE(isWorld);
        GltfOptions options;
        options.motionKeys = 2;
        options.pointCache = GltfPointCache{dir.file("up.pc2"), "", isWorld};
        const Scene scene = loadGltf(path, options);
        ASSERT_EQ(scene.meshes.size(), 1u);
        const Mesh& mesh = scene.meshes[0];
        ASSERT_TRUE(mesh.hasNormals());
        const glm::uvec3 t = mesh.triangles[0];
        EXPECT_EQ(t, glm::uvec3(0, 2, 1));  // flipped: the node mirrors, and so did the animation the cache holds
        const glm::vec3 facing = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
        for (std::size_t v = 0; v < 3; ++v) EXPECT_GT(glm::dot(facing, mesh.normals[v]), 0.0f);
    }
}

// Keys the loader chooses (motionKeys 0) for a cache whose motion bends: the keys after the first
// two are posed from the cache after the meshes are made, and each still gets the normals of its
// triangle (a slanted one, whose normal is not the +z a point with none falls back to).
TEST(PointCache, ChosenKeysKeepTheTrianglesNormals) {
    test::TempDir dir;
    const std::vector<glm::vec3> rest{{-1, -1, 0}, {1, -1, 0}, {0, 1, 1}};
    const std::string path = writeTriangleWithNormals(dir, "slanted.gltf", rest, glm::vec3(1.0f));
    // The triangle goes 1.5 along x and comes back over the shutter: two keys miss its middle.
    std::vector<glm::vec3> away = rest;
    for (glm::vec3& p : away) p.x += 1.5f;
    writeBytes(dir.file("bounce.pc2"), pc2Bytes({rest, away, rest}, 0.0f, 12.0f));
    GltfOptions options;
    options.frame = 0.0, options.shutter = 24.0;
    options.pointCache = GltfPointCache{dir.file("bounce.pc2"), "", false};
    const Scene scene = loadGltf(path, options);
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    ASSERT_GT(mesh.numKeys, 2);
    ASSERT_TRUE(mesh.hasNormals());
    const glm::vec3 expected = glm::normalize(glm::vec3(0.0f, -2.0f, 4.0f));  // (2, 0, 0) x (1, 2, 1)
    for (int k = 0; k < mesh.numKeys; ++k)
        for (std::size_t v = 0; v < 3; ++v) {
            SCOPED_TRACE(testing::Message() << "key " << k << ", vertex " << v);
            const glm::vec3 n = mesh.normals[std::size_t(k) * 3 + v];
            EXPECT_NEAR(n.x, expected.x, 1e-5f); EXPECT_NEAR(n.y, expected.y, 1e-5f); EXPECT_NEAR(n.z, expected.z, 1e-5f);
        }
}

}  // namespace
}  // namespace streak
