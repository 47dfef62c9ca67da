#include "scene/blur_shell.h"

#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_writer.h"
#include "support/shared_scenes.h"
#include "support/test_scenes.h"
#include "util/error.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace streak {
namespace {

Scene builtin(const std::string& name, OptionMap options = OptionMap()) { return test::validBuiltin(name, std::move(options)); }

Scene sphere(int triangles) {
    OptionMap options;
    options.set("triangles", std::to_string(triangles));
    return builtin("sphere", options);
}

const Mesh& sphereMesh(const Scene& scene) {
    for (const Mesh& mesh : scene.meshes)
        if (mesh.name == "sphere") return mesh;
    throw Error("no sphere");
}

std::size_t sphereIndex(const Scene& scene) { return std::size_t(&sphereMesh(scene) - scene.meshes.data()); }

// Every SoM edge of a sphere translating along +x has vertices whose normals are within the
// widest angle of one polygon of perpendicular to the motion: a backward vertex shares a polygon
// with a forward one, so n . x lies in (-sin(angle), 0).
TEST(BlurShell, SilhouetteEdgesOfATranslatingSphereLieOnItsGreatCircleFacingTheMotion) {
    const Scene scene = sphere(3840);
    const Mesh& mesh = sphereMesh(scene);
    float widest = 0.0f;  // the widest angle between two normals of one polygon
    for (const glm::uvec3& tri : mesh.triangles)
        for (int a = 0; a < 3; ++a) {
            const glm::vec3 n0 = mesh.normals[tri[a]], n1 = mesh.normals[tri[(a + 1) % 3]];
            widest = std::max(widest, std::acos(std::clamp(glm::dot(n0, n1), -1.0f, 1.0f)));
        }
    const BlurShell shell = buildBlurShell(scene, BlurShellOptions{});
    const auto& strips = shell.strips[sphereIndex(scene)];
    ASSERT_GT(strips.size(), 10u);
    EXPECT_EQ(shell.silhouetteEdges, strips.size());  // every polygon on the SoM now has a strip
    for (const ShellStrip& strip : strips)
        for (const glm::vec3& n : strip.edges[0].normals) {
            EXPECT_LT(n.x, 0.0f);
            EXPECT_GT(n.x, -std::sin(widest));
        }
}

// Glisse: O(sqrt(n)) SoM edges on a mesh of n polygons. Quadrupling the triangles doubles them.
TEST(BlurShell, SilhouetteEdgesGrowAsTheSquareRootOfTheTriangles) {
    std::vector<double> edges, triangles;
    for (const int n : {960, 3840, 15360, 61440}) {
        const Scene scene = sphere(n);
        edges.push_back(double(buildBlurShell(scene, BlurShellOptions{}).silhouetteEdges));
        triangles.push_back(double(sphereMesh(scene).triangles.size()));
    }
    for (std::size_t i = 1; i < edges.size(); ++i) {
        const double ratio = (edges[i] / edges[i - 1]) / std::sqrt(triangles[i] / triangles[i - 1]);
        EXPECT_NEAR(ratio, 1.0, 0.25) << triangles[i] << " triangles: " << edges[i] << " edges, " << edges[i - 1] << " before";
    }
}

// A flat-shaded sphere, each polygon with its own three vertices and its face normal: its
// vertices all face one way per polygon, so by the mesh's normals no polygon is on the SoM
// (the thesis' warning); welded, the vertices at one position share the mean normal of the
// polygons around it, and the SoM is the smooth sphere's.
TEST(BlurShell, AFlatShadedMeshHasASilhouetteOfMotionOnlyWhenWelded) {
    const Scene smooth = sphere(960);
    Scene flat = smooth;
    Mesh& mesh = flat.meshes[sphereIndex(flat)];
    Mesh split = mesh;
    split.positions.clear(), split.normals.clear(), split.uvs.clear(), split.triangles.clear();
    const std::size_t n = mesh.numVertices();
    for (int k = 0; k < mesh.numKeys; ++k)
        for (const glm::uvec3& tri : mesh.triangles) {
            const glm::vec3* p = mesh.positions.data() + std::size_t(k) * n;
            const glm::vec3 face = glm::normalize(glm::cross(p[tri.y] - p[tri.x], p[tri.z] - p[tri.x]));
            for (int c = 0; c < 3; ++c) split.positions.push_back(p[tri[c]]), split.normals.push_back(face);
        }
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) split.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    mesh = split;
    validateScene(flat);
    BlurShellOptions byMesh;
    byMesh.isFacingWelded = false;
    EXPECT_EQ(buildBlurShell(flat, byMesh).silhouetteEdges, 0u);
    const std::size_t welded = buildBlurShell(flat, BlurShellOptions{}).silhouetteEdges;
    const std::size_t reference = buildBlurShell(smooth, byMesh).silhouetteEdges;
    EXPECT_GT(welded, 20u);
    EXPECT_NEAR(double(welded), double(reference), 0.25 * double(reference));
}

TEST(BlurShell, StaticMeshesAndCameraMotionMakeNoShell) {
    for (const char* name : {"pan", "crossing"}) {
        Scene scene = builtin(name);
        if (std::string(name) == "crossing")  // make it stand still
            for (Mesh& mesh : scene.meshes)
                for (int k = 1; k < mesh.numKeys; ++k)
                    std::copy(mesh.positions.begin(), mesh.positions.begin() + std::ptrdiff_t(mesh.numVertices()),
                              mesh.positions.begin() + std::ptrdiff_t(std::size_t(k) * mesh.numVertices()));
        const BlurShell shell = buildBlurShell(scene, BlurShellOptions{});
        EXPECT_EQ(shell.numStrips, 0u) << name;
        EXPECT_EQ(shell.numTriangles, 0u) << name;
        EXPECT_EQ(makeShellScene(scene, shell).numShellTriangles(), 0u) << name;
    }
}

// The strips start at the deforming mesh where it stands at T: each first edge is that
// polygon's mesh edge in the close pose.
void expectAttached(const Scene& scene, const BlurShell& shell, std::size_t atLeast) {
    std::size_t checked = 0;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        const std::span<const glm::vec3> close = mesh.keyPositions(mesh.numKeys - 1);
        for (const ShellStrip& strip : shell.strips[m]) {
            const glm::uvec3& tri = mesh.triangles[strip.triangle];
            for (int k = 0; k < 2; ++k) {
                const std::uint32_t v = strip.edges[0].vertices[std::size_t(k)];
                EXPECT_TRUE(v == tri.x || v == tri.y || v == tri.z);
                EXPECT_EQ(strip.edges[0].positions[std::size_t(k)], close[v]);
            }
            ++checked;
        }
    }
    EXPECT_GE(checked, atLeast);
}

TEST(BlurShell, TheShellStaysAttachedToADeformingMesh) {
    OptionMap options;
    options.set("squash", "0.5");
    options.set("keys", "11");
    const Scene squashed = builtin("sphere", options);
    expectAttached(squashed, buildBlurShell(squashed, BlurShellOptions{}), 20);
}

TEST(BlurShell, TheShellStaysAttachedToASkinnedMesh) {
    STREAK_REQUIRE_SHARED_SCENES();
    GltfOptions options;
    options.frame = 16.0;  // the trail of 0.2 s before frame 20.8
    options.shutter = 0.2 * 24.0;
    options.motionKeys = 11;
    Scene scene = loadGltf(test::sharedScene("CesiumMan/glTF-Binary/CesiumMan.glb"), options);
    validateScene(scene);
    const BlurShell shell = buildBlurShell(scene, BlurShellOptions{});
    expectAttached(scene, shell, 100);
    // The thesis' Table 1 character: a few hundred SoM edges on about a thousand polygons.
    EXPECT_GT(shell.silhouetteEdges, 50u);
    EXPECT_LT(shell.silhouetteEdges, scene.numTriangles() / 2);
}

TEST(BlurShell, TheShellSceneIsTheMeshAtTPlusOneBlendedDoubleSidedMeshPerMovingMesh) {
    const Scene scene = sphere(960);
    const BlurShell shell = buildBlurShell(scene, BlurShellOptions{});
    const ShellScene out = makeShellScene(scene, shell);
    ASSERT_EQ(out.firstShellMesh, scene.meshes.size());
    ASSERT_EQ(out.scene.meshes.size(), scene.meshes.size() + 1);  // the sphere moves, the backdrop does not
    EXPECT_EQ(out.numShellTriangles(), shell.numTriangles);
    for (const Mesh& mesh : out.scene.meshes) EXPECT_TRUE(mesh.isStatic()) << mesh.name;
    const Mesh& shellMesh = out.scene.meshes.back();
    const Material& material = out.scene.materials[shellMesh.material];
    EXPECT_EQ(material.alphaMode, AlphaMode::Blend);
    EXPECT_TRUE(material.doubleSided);
    EXPECT_EQ(material.baseColorTexture, scene.materials[scene.meshes.back().material].baseColorTexture);
    ASSERT_TRUE(shellMesh.hasColors());
    for (const glm::vec4& c : shellMesh.colors) {
        EXPECT_GE(c.w, 0.0f);
        EXPECT_LE(c.w, 0.5f);
    }
    EXPECT_TRUE(out.scene.camera.isStatic());
}

TEST(BlurShell, ExportedAndLoadedBackKeepsItsTrianglesAndAlphas) {
    const Scene scene = sphere(960);
    const ShellScene out = makeShellScene(scene, buildBlurShell(scene, BlurShellOptions{}));
    for (const bool isText : {false, true}) {
        std::vector<std::uint8_t> bytes;
        if (isText) {
            const std::string text = writeGltfText(out.scene);
            bytes.assign(text.begin(), text.end());
        } else {
            bytes = writeGltfBinary(out.scene);
        }
        GltfOptions options;
        options.allowExternalFiles = false;
        Scene loaded = loadGltfFromMemory(bytes, isText ? "shell.gltf" : "shell.glb", "", options);
        validateScene(loaded);
        ASSERT_EQ(loaded.numTriangles(), out.scene.numTriangles()) << isText;
        const Mesh& original = out.scene.meshes.back();
        auto found = std::find_if(loaded.meshes.begin(), loaded.meshes.end(), [&](const Mesh& m) { return m.name == original.name; });
        ASSERT_NE(found, loaded.meshes.end());
        ASSERT_EQ(found->colors.size(), original.colors.size());
        for (std::size_t i = 0; i < original.colors.size(); ++i) EXPECT_FLOAT_EQ(found->colors[i].w, original.colors[i].w) << i;
        EXPECT_EQ(loaded.materials[found->material].alphaMode, AlphaMode::Blend);
        EXPECT_TRUE(loaded.materials[found->material].doubleSided);
    }
}

TEST(BlurShell, OptionsOutOfRangeAreErrors) {
    for (const auto& [key, value] : {std::pair{"subdivisions", "0"}, std::pair{"length", "0"}, std::pair{"length", "-1"},
                                     std::pair{"alpha", "1.5"}, std::pair{"fade", "0"}, std::pair{"subdivisions", "129"},
                                     std::pair{"facing", "camera"}}) {
        OptionMap options;
        options.set(key, value);
        EXPECT_THROW(BlurShellOptions::read(options), Error) << key << "=" << value;
    }
    OptionMap blend;
    blend.set("blend", "additive");
    EXPECT_THROW(BlurShellOptions::readIsSorted(blend), Error);
}

}  // namespace
}  // namespace streak
