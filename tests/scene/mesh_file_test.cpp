// OBJ and PLY meshes and numbered sequences of them: the readers against hand-written files in
// every PLY encoding, and sequences loaded as animations (files interpolated, topology changes
// held or moved by velocities, missing frames refused).

#include "scene/mesh_file.h"
#include "scene/mesh_sequence.h"
#include "util/error.h"

#include "support/expect_error.h"
#include "support/point_cache_files.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace streak {
namespace {

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

using test::expectErrorContaining;

// A quad (two triangles, fanned from a 4-gon) with velocities, as a PLY in `format`.
std::string plyQuad(const std::string& format) {
    const float v[4][6] = {{0, 0, 0, 1, 0, 0}, {1, 0, 0, 1, 0, 0}, {1, 1, 0, 1, 2, 0}, {0, 1, -1, 1, 0, 3}};
    std::string header = "ply\nformat " + format +
                         " 1.0\ncomment a quad\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                         "property uchar flag\nproperty float vx\nproperty float vy\nproperty float vz\n"
                         "element face 1\nproperty list uchar int vertex_indices\nelement note 1\nproperty short n\nend_header\n";
    if (format == "ascii") {
        std::string body;
        for (const auto& r : v) body += std::to_string(r[0]) + " " + std::to_string(r[1]) + " " + std::to_string(r[2]) + " 7 " + std::to_string(r[3]) + " " +
                                        std::to_string(r[4]) + " " + std::to_string(r[5]) + "\n";
        return header + body + "4 0 1 2 3\n5\n";
    }
    const bool isBig = format == "binary_big_endian";
    std::string body;
    auto put = [&](auto value) {
        char raw[sizeof value];
        std::memcpy(raw, &value, sizeof value);
        if (isBig) std::reverse(raw, raw + sizeof value);
        body.append(raw, sizeof value);
    };
    for (const auto& r : v) {
        put(r[0]), put(r[1]), put(r[2]), put(std::uint8_t(7)), put(r[3]), put(r[4]), put(r[5]);
    }
    put(std::uint8_t(4)), put(std::int32_t(0)), put(std::int32_t(1)), put(std::int32_t(2)), put(std::int32_t(3));
    put(std::int16_t(5));
    return header + body;
}

TEST(MeshFile, PlyReadsTheSameInEveryEncoding) {
    test::TempDir dir;
    for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
        SCOPED_TRACE(format);
        writeText(dir.file("quad.ply"), plyQuad(format));
        const MeshFile mesh = readMeshFile(dir.file("quad.ply"), 1u << 20);
        ASSERT_EQ(mesh.positions.size(), 4u);
        EXPECT_EQ(mesh.positions[3], glm::vec3(0, 1, -1));
        ASSERT_EQ(mesh.triangles.size(), 2u);
        EXPECT_EQ(mesh.triangles[0], glm::uvec3(0, 1, 2));
        EXPECT_EQ(mesh.triangles[1], glm::uvec3(0, 2, 3));
        ASSERT_EQ(mesh.velocities.size(), 4u);
        EXPECT_EQ(mesh.velocities[2], glm::vec3(1, 2, 0));
    }
}

TEST(MeshFile, ObjKeepsItsVertexOrderAndFansItsFaces) {
    test::TempDir dir;
    writeText(dir.file("quad.obj"), "# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 -1\nvt 0 0\nf 1/1 2/1 3/1 4/1\n");
    const MeshFile mesh = readMeshFile(dir.file("quad.obj"), 1u << 20);
    ASSERT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(mesh.positions[3], glm::vec3(0, 1, -1));
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.triangles[1], glm::uvec3(0, 2, 3));
    EXPECT_TRUE(mesh.velocities.empty());
    // Velocities come from the sidecar quad.vel, one line per vertex.
    writeText(dir.file("quad.vel"), "# vx vy vz\n1 0 0\n1 0 0\n0 2 0\n0 0 3\n");
    const MeshFile moving = readMeshFile(dir.file("quad.obj"), 1u << 20);
    ASSERT_EQ(moving.velocities.size(), 4u);
    EXPECT_EQ(moving.velocities[3], glm::vec3(0, 0, 3));
    writeText(dir.file("quad.vel"), "1 0 0\n");
    expectErrorContaining([&] { readMeshFile(dir.file("quad.obj"), 1u << 20); }, "1 velocities for the 4 vertices");
    writeText(dir.file("quad.vel"), "1 0\n1 0 0\n1 0 0\n1 0 0\n");
    expectErrorContaining([&] { readMeshFile(dir.file("quad.obj"), 1u << 20); }, "is not three numbers");
}

TEST(MeshFile, BadFilesAreOneErrorNamingTheProblem) {
    test::TempDir dir;
    writeText(dir.file("a.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                 "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n3 0 1 7\n");
    expectErrorContaining([&] { readMeshFile(dir.file("a.ply"), 1u << 20); }, "a face names vertex 7 of 3");
    writeText(dir.file("b.ply"), "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n");
    expectErrorContaining([&] { readMeshFile(dir.file("b.ply"), 1u << 20); }, "too short for its 2000000000 vertex elements");
    writeText(dir.file("b2.ply"), "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n");
    expectErrorContaining([&] { readMeshFile(dir.file("b2.ply"), 1u << 20); }, "too short for its 2000000000 vertex elements");
    writeText(dir.file("c.ply"), "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n");
    expectErrorContaining([&] { readMeshFile(dir.file("c.ply"), 1u << 20); }, "no x, y and z");
    writeText(dir.file("f.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                 "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n3 0 1 nan\n");
    expectErrorContaining([&] { readMeshFile(dir.file("f.ply"), 1u << 20); }, "an index is nan, not a whole number");
    writeText(dir.file("g.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                 "element face 1\nproperty list float int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n2.5 0 1 2\n");
    expectErrorContaining([&] { readMeshFile(dir.file("g.ply"), 1u << 20); }, "list's length is 2.500000, not a whole number");
    std::string corners = "f";
    for (int k = 1; k <= 300; ++k) corners += " " + std::to_string(k);
    std::string many;
    for (int k = 0; k < 300; ++k) many += "v " + std::to_string(std::cos(k * 0.02)) + " " + std::to_string(std::sin(k * 0.02)) + " 0\n";
    writeText(dir.file("h.obj"), many + corners + "\nf 1 2 3\n");
    expectErrorContaining([&] { readMeshFile(dir.file("h.obj"), 1u << 20); }, "256 or more corners");
    writeText(dir.file("i.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    expectErrorContaining([&] { readMeshFile(dir.file("i.obj"), 1u << 20, 1); }, "more than 1 triangles");
    writeText(dir.file("d.ply"), "plx\n");
    expectErrorContaining([&] { readMeshFile(dir.file("d.ply"), 1u << 20); }, "not a PLY file");
    writeText(dir.file("e.obj"), "v 0 0 0\nv 1 0 0\n");
    expectErrorContaining([&] { readMeshFile(dir.file("e.obj"), 1u << 20); }, "no triangles");
    expectErrorContaining([&] { readMeshFile(dir.file("missing.obj"), 1u << 20); }, "not a regular file");
}

// A numbered OBJ sequence of a triangle moving 1 along x per frame: the shutter over frames 1 to
// 3 takes files 1, 2 and 3 and moves on the lines between them; a topology change holds the first
// file still (and says so), or moves it along its velocities; a missing frame is refused.
TEST(MeshSequence, InterpolatesItsFilesAndHoldsATopologyChange) {
    test::TempDir dir;
    for (int k = 0; k <= 4; ++k) {
        const std::string x = std::to_string(k);
        writeText(dir.file("tri_000" + std::to_string(k) + ".obj"), "v " + x + " 0 -5\nv " + x + ".5 0 -5\nv " + x + " 1 -5\nf 1 2 3\n");
    }
    GltfOptions options;
    options.frame = 1.0, options.shutter = 2.0, options.motionKeys = 3;
    RenderStats stats;
    const Scene scene = loadMeshSequence(dir.file("tri_%04d.obj"), options, &stats);
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    ASSERT_EQ(mesh.numKeys, 3);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(mesh.positions[std::size_t(k) * 3].x, 1.0f + float(k), 1e-5f);
    EXPECT_EQ(stats.counter("sequence_files"), 3.0);
    EXPECT_EQ(stats.counter("sequence_topology_changes"), 0.0);

    options.frame = 1.5, options.shutter = 1.0;  // between files: keys at 1.5, 2, 2.5
    const Scene between = loadMeshSequence(dir.file("tri_%04d.obj"), options);
    EXPECT_NEAR(between.meshes[0].positions[0].x, 1.5f, 1e-5f);
    EXPECT_NEAR(between.meshes[0].positions[6].x, 2.5f, 1e-5f);

    // Frame 2 gains a vertex: the shutter from 1 holds file 1 still.
    writeText(dir.file("tri_0002.obj"), "v 2 0 -5\nv 2.5 0 -5\nv 2 1 -5\nv 3 1 -5\nf 1 2 3\nf 2 4 3\n");
    options.frame = 1.0, options.shutter = 2.0;
    RenderStats held;
    const Scene still = loadMeshSequence(dir.file("tri_%04d.obj"), options, &held);
    EXPECT_EQ(still.meshes[0].positions[0].x, 1.0f);
    EXPECT_EQ(still.meshes[0].positions[6].x, 1.0f);
    EXPECT_EQ(held.counter("sequence_topology_changes"), 1.0);
    EXPECT_EQ(held.counter("sequence_held_still"), 1.0);
    // The held file is the one at the velocities' frame (--frame: 2 under a centred shutter).
    options.frame = 1.5, options.shutter = 1.0, options.velocityFrame = 2.0;
    EXPECT_EQ(loadMeshSequence(dir.file("tri_%04d.obj"), options).meshes[0].positions[0].x, 2.0f);
    options.frame = 1.0, options.shutter = 2.0, options.velocityFrame.reset();

    // With velocities (PLY vx vy vz, 0.5 m per frame here) the held file moves along them.
    for (int k = 1; k <= 3; ++k) writeText(dir.file("quad_000" + std::to_string(k) + ".ply"), plyQuad(k == 2 ? "binary_big_endian" : "ascii"));
    writeText(dir.file("quad_0002.ply"), plyQuad("ascii").replace(plyQuad("ascii").find("4 0 1 2 3"), 9, "3 0 1 2"));
    options.isVelocityPerFrame = true;
    RenderStats moved;
    const Scene moving = loadMeshSequence(dir.file("quad_%04d.ply"), options, &moved);
    EXPECT_EQ(moved.counter("sequence_held_still"), 0.0);
    const Mesh& quad = moving.meshes[0];
    ASSERT_EQ(quad.numKeys, 3);
    EXPECT_NEAR(quad.positions[std::size_t(2) * 4 + 2].y, 1.0f + 2.0f * 2.0f, 1e-5f);  // vertex 2, vy = 2 per frame, 2 frames on
    EXPECT_NEAR(quad.positions[std::size_t(1) * 4 + 3].z, -1.0f + 3.0f * 1.0f, 1e-5f);  // vertex 3, vz = 3, 1 frame on

    // Forced, files of one vertex count interpolate whatever their triangles; of two, an Error.
    writeText(dir.file("tri_0002.obj"), "v 2 0 -5\nv 2.5 0 -5\nv 2 1 -5\nf 1 3 2\n");
    options.isVelocityPerFrame = false;
    const Scene flipped = loadMeshSequence(dir.file("tri_%04d.obj"), options);
    EXPECT_EQ(flipped.meshes[0].positions[3].x, 1.0f);  // held: the triangles differ
    options.isSequenceInterpolated = true;
    const Scene forced = loadMeshSequence(dir.file("tri_%04d.obj"), options);
    EXPECT_NEAR(forced.meshes[0].positions[3].x, 2.0f, 1e-5f);
    writeText(dir.file("tri_0002.obj"), "v 2 0 -5\nv 2.5 0 -5\nv 2 1 -5\nv 3 1 -5\nf 1 2 3\nf 2 4 3\n");
    expectErrorContaining([&] { loadMeshSequence(dir.file("tri_%04d.obj"), options); }, "frame 2 has 4 vertices and frame 1 3");
    options.isSequenceInterpolated = false;

    // Past the last file the mesh holds it (as an animation holds its end values); a file
    // missing between two that exist is refused.
    writeText(dir.file("tri_0002.obj"), "v 2 0 -5\nv 2.5 0 -5\nv 2 1 -5\nf 1 2 3\n");
    options.frame = 3.0;
    const Scene end = loadMeshSequence(dir.file("tri_%04d.obj"), options);
    EXPECT_NEAR(end.meshes[0].positions[3].x, 4.0f, 1e-5f);  // frame 4: file 4
    EXPECT_NEAR(end.meshes[0].positions[6].x, 4.0f, 1e-5f);  // frame 5: still file 4
    std::filesystem::remove(dir.file("tri_0002.obj"));
    options.frame = 1.0;
    expectErrorContaining([&] { loadMeshSequence(dir.file("tri_%04d.obj"), options); }, "frame 2 of the sequence is missing");
    options.frame = 10.0;
    expectErrorContaining([&] { loadMeshSequence(dir.file("tri_%04d.obj"), options); }, "no file for frames 10 to 12");
}

// A point cache moves an OBJ base mesh as it moves a glTF one: the OBJ's vertices in its order.
TEST(MeshSequence, APointCacheMovesAnObjBaseMesh) {
    test::TempDir dir;
    writeText(dir.file("tri.obj"), "v 0 0 -5\nv 1 0 -5\nv 0 1 -5\nf 1 2 3\n");
    const std::vector<glm::vec3> rest{{0, 0, -5}, {1, 0, -5}, {0, 1, -5}};
    std::vector<glm::vec3> moved = rest;
    for (glm::vec3& p : moved) p.x += 2.0f;
    test::writeBytes(dir.file("slide.pc2"), test::pc2Bytes({rest, moved}, 0.0f, 24.0f));  // 2 along x over 1 s
    GltfOptions options;
    options.frame = 12.0, options.shutter = 12.0, options.motionKeys = 2;  // 0.5 s to 1 s of a 2-wide slide over 1 s
    options.pointCache = GltfPointCache{dir.file("slide.pc2"), "", false};
    const Scene scene = loadMeshSequence(dir.file("tri.obj"), options);
    EXPECT_NEAR(scene.meshes[0].positions[1].x, 2.0f, 1e-5f);  // vertex 1 at 0.5 s: 1 + 1
    EXPECT_NEAR(scene.meshes[0].positions[3 + 1].x, 3.0f, 1e-5f);
}

}  // namespace
}  // namespace streak
