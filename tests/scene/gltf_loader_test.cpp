#include "scene/gltf_loader.h"

#include "scene/scene_loader.h"
#include "support/gltf_builder.h"
#include "support/gltf_samples.h"
#include "support/shared_scenes.h"
#include "util/error.h"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <cstdio>
#include <cmath>
#include <numbers>

namespace streak {

namespace {

using nlohmann::json;

Scene load(const test::GltfBuilder& builder, GltfOptions options = {}, RenderStats* stats = nullptr) {
    options.allowExternalFiles = false;
    return loadGltfFromMemory(builder.gltfBytes(), "test.gltf", "", options, stats);
}

// A triangle (0,0,0), (1,0,0), (0,1,0) in a node of its own; returns the node.
int addTriangle(test::GltfBuilder& b, json nodeExtras = json::object(), json primitiveExtras = json::object()) {
    json primitive = primitiveExtras;
    primitive["attributes"]["POSITION"] = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    return b.addMeshNode(primitive, nodeExtras);
}

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

// An RGBA PNG in memory, as a data uri.
std::string pngDataUri(int width, int height, const std::vector<std::uint8_t>& rgba) {
    std::vector<std::uint8_t> png;
    stbi_write_png_to_func([](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<std::uint8_t>*>(context);
        out->insert(out->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
    }, &png, width, height, 4, rgba.data(), width * 4);
    return "data:image/png;base64," + test::GltfBuilder::base64(png);
}

// Options whose shutter spans [seconds, seconds + shutterSeconds] of animation time.
GltfOptions atSeconds(double seconds, double shutterSeconds = 0.0, int motionKeys = 2) {
    GltfOptions options;
    options.fps = 1.0;
    options.frame = seconds;
    options.shutter = shutterSeconds;
    options.motionKeys = motionKeys;
    return options;
}

// The streak mesh made from the glTF node named `name`.
const Mesh& meshNamed(const Scene& scene, const std::string& name) {
    for (const Mesh& mesh : scene.meshes)
        if (mesh.name == name) return mesh;
    throw std::runtime_error("no mesh " + name);
}

}  // namespace

TEST(GltfLoader, NonIndexedTriangleBecomesAStaticMeshSeenFromPlusZ) {
    test::GltfBuilder b;
    addTriangle(b);
    const Scene scene = load(b);
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.numKeys, 2);
    EXPECT_EQ(mesh.triangles, std::vector<glm::uvec3>{glm::uvec3(0, 1, 2)});
    EXPECT_TRUE(mesh.isStatic());
    EXPECT_FALSE(mesh.hasNormals());
    expectNear(mesh.keyPositions(1)[1], {1, 0, 0});
    // glTF's default material: white, opaque, back faces culled.
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].baseColor, glm::vec3(1.0f));
    EXPECT_FALSE(scene.materials[0].doubleSided);
    EXPECT_FALSE(scene.materials[0].isTranslucent());
    // No camera in the file: one on +z looking at the middle of the bounds, far enough away to
    // see them (the bounds' corners project inside [-1, 1]).
    EXPECT_TRUE(scene.camera.isStatic());
    expectNear(scene.camera.open.position * glm::vec3(1, 1, 0), {0.5f, 0.5f, 0});
    EXPECT_GT(scene.camera.open.position.z, 0.5f);
    const glm::mat4 clip = scene.camera.clipFromWorld(0.0f, 4.0f / 3.0f);
    for (const glm::vec3& p : mesh.keyPositions(0)) {
        const glm::vec4 c = clip * glm::vec4(p, 1.0f);
        EXPECT_LT(std::abs(c.x / c.w), 1.0f);
        EXPECT_LT(std::abs(c.y / c.w), 1.0f);
    }
}

TEST(GltfLoader, StripsAndFansAreTriangulatedAndPointsAreSkippedAndCounted) {
    test::GltfBuilder b;
    const int positions = b.addFloats({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0}, "VEC3", 3);
    b.addMeshNode({{"attributes", {{"POSITION", positions}}}, {"mode", 5}}, {{"name", "strip"}});
    b.addMeshNode({{"attributes", {{"POSITION", positions}}}, {"mode", 6}}, {{"name", "fan"}});
    b.addMeshNode({{"attributes", {{"POSITION", positions}}}, {"mode", 0}}, {{"name", "points"}});
    RenderStats stats;
    const Scene scene = load(b, {}, &stats);
    // glTF 3.7.2.1: strip triangle i = (i, i + 1 + i%2, i + 2 - i%2); fan triangle i = (i+1, i+2, 0).
    EXPECT_EQ(meshNamed(scene, "strip").triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}}));
    EXPECT_EQ(meshNamed(scene, "fan").triangles, (std::vector<glm::uvec3>{{1, 2, 0}, {2, 3, 0}, {3, 4, 0}}));
    EXPECT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(stats.counter("gltf_skipped_primitives"), 1.0);
    EXPECT_EQ(stats.counter("gltf_instanced_primitives"), 2.0);
}

TEST(GltfLoader, HierarchiesComposeAndMirroringKeepsFrontFacesCounterClockwise) {
    test::GltfBuilder b;
    json& nodes = b.json()["nodes"];
    nodes.push_back({{"translation", {0, 0, -5}}, {"children", {1, 2}}});
    b.addToScene(0);
    addTriangle(b, {{"name", "turned"}, {"rotation", {0, 0, std::sin(std::numbers::pi / 4), std::cos(std::numbers::pi / 4)}}});
    addTriangle(b, {{"name", "mirrored"}, {"scale", {-1, 1, 1}}});
    // addMeshNode put the children in scene 0 too; they belong only to node 0.
    b.json()["scenes"][0]["nodes"] = {0};
    const Scene scene = load(b);
    ASSERT_EQ(scene.meshes.size(), 2u);
    const Mesh& turned = meshNamed(scene, "turned");  // 90 degrees about z: x -> y
    expectNear(turned.keyPositions(0)[1], {0, 1, -5});
    const Mesh& mirrored = meshNamed(scene, "mirrored");
    expectNear(mirrored.keyPositions(0)[1], {-1, 0, -5});
    EXPECT_EQ(mirrored.triangles[0], glm::uvec3(0, 2, 1));  // swapped: counter-clockwise again
    EXPECT_EQ(turned.triangles[0], glm::uvec3(0, 1, 2));
}

TEST(GltfLoader, MaterialsKeepAlphaModesFactorsTexturesAndVertexColours) {
    test::GltfBuilder b;
    // A 2x1 texture: left texel sRGB 188 (linear 0.5), alpha 255; right black with alpha 0.
    b.json()["images"] = {{{"uri", pngDataUri(2, 1, {188, 188, 188, 255, 0, 0, 0, 0})}}};
    b.json()["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}}};
    b.json()["textures"] = {{{"source", 0}, {"sampler", 0}}};
    b.json()["materials"] = {
        {{"name", "opaque"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 0.3}}}}},
        {{"name", "blend"}, {"alphaMode", "BLEND"}, {"doubleSided", true}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.3}}}}},
        {{"name", "mask"}, {"alphaMode", "MASK"}, {"alphaCutoff", 0.7},
         {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}}};
    addTriangle(b, {{"name", "a"}}, {{"material", 0}});
    addTriangle(b, {{"name", "b"}}, {{"material", 1}});
    json textured = {{"material", 2}};
    textured["attributes"]["TEXCOORD_0"] = b.addFloats({9, 9, 9, 9, 9, 9}, "VEC2", 2);  // not the set the texture reads
    textured["attributes"]["TEXCOORD_1"] = b.addAccessor(std::vector<std::uint16_t>{0, 0, 65535, 0, 0, 65535}, "VEC2", 2, 5123, true);
    textured["attributes"]["COLOR_0"] = b.addAccessor(std::vector<std::uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0}, "VEC4", 4, 5121, true);
    addTriangle(b, {{"name", "c"}}, textured);
    const Scene scene = load(b);
    ASSERT_EQ(scene.materials.size(), 3u);
    const Material& opaque = scene.materials[meshNamed(scene, "a").material];
    EXPECT_EQ(opaque.baseColor, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(opaque.alphaMode, AlphaMode::Opaque);
    EXPECT_EQ(opaque.opacity, 1.0f);  // OPAQUE ignores the factor's alpha
    const Material& blend = scene.materials[meshNamed(scene, "b").material];
    EXPECT_EQ(blend.alphaMode, AlphaMode::Blend);
    EXPECT_FLOAT_EQ(blend.opacity, 0.3f);
    EXPECT_TRUE(blend.doubleSided);
    const Material& mask = scene.materials[meshNamed(scene, "c").material];
    EXPECT_EQ(mask.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(mask.alphaCutoff, 0.7f);
    ASSERT_EQ(mask.baseColorTexture, 0);
    const Texture& texture = scene.textures[0];
    EXPECT_EQ(texture.width(), 2);
    EXPECT_NEAR(texture.texel(0, 0, 0).x, 0.5f, 0.003f);  // sRGB decoded
    EXPECT_EQ(texture.texel(0, 1, 0).w, 0.0f);
    EXPECT_EQ(texture.sample({1.6f, 0.5f}, 0.0f).w, 0.0f);  // clamp to edge in u: still the right texel
    const Mesh& c = meshNamed(scene, "c");
    EXPECT_EQ(c.uvs, (std::vector<glm::vec2>{{0, 0}, {1, 0}, {0, 1}}));  // TEXCOORD_1, normalized shorts
    ASSERT_EQ(c.colors.size(), 3u);
    EXPECT_EQ(c.colors[0], glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(c.colors[1].w, 128.0f / 255.0f, 1e-6f);
}

TEST(GltfLoader, TextureTransformMovesUvs) {
    // KHR_texture_transform: offset (0.5, 0), rotation 90 degrees, scale (2, 3):
    // uv (1, 0) -> scaled (2, 0) -> rotated (u' = cos u + sin v, v' = -sin u + cos v) (0, -2)
    // -> offset (0.5, -2).
    test::GltfBuilder b;
    b.json()["extensionsUsed"] = {"KHR_texture_transform"};
    b.json()["extensionsRequired"] = {"KHR_texture_transform"};
    b.json()["images"] = {{{"uri", pngDataUri(1, 1, {255, 255, 255, 255})}}};
    b.json()["textures"] = {{{"source", 0}}};
    json transform = {{"offset", {0.5, 0}}, {"rotation", std::numbers::pi / 2}, {"scale", {2, 3}}};
    b.json()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}}}}}};
    json primitive = {{"material", 0}};
    primitive["attributes"]["TEXCOORD_0"] = b.addFloats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
    addTriangle(b, {}, primitive);
    const Scene scene = load(b);
    const std::vector<glm::vec2>& uvs = scene.meshes[0].uvs;
    EXPECT_NEAR(uvs[0].x, 0.5f, 1e-6f);
    EXPECT_NEAR(uvs[0].y, 0.0f, 1e-6f);
    EXPECT_NEAR(uvs[1].x, 0.5f, 1e-6f);
    EXPECT_NEAR(uvs[1].y, -2.0f, 1e-6f);
    EXPECT_NEAR(uvs[2].x, 3.5f, 1e-6f);  // (0, 1) -> (0, 3) -> (3, 0) -> (3.5, 0)
    EXPECT_NEAR(uvs[2].y, 0.0f, 1e-6f);
}

TEST(GltfLoader, DefaultMorphWeightsComeFromTheNodeElseTheMesh) {
    // One target moving vertex 2 by (0, 1, 0). mesh.weights = [0.5]; the second node overrides
    // with node.weights = [2].
    test::GltfBuilder b;
    const int positions = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int target = b.addFloats({0, 0, 0, 0, 0, 0, 0, 1, 0}, "VEC3", 3);
    json primitive = {{"attributes", {{"POSITION", positions}}}, {"targets", {{{"POSITION", target}}}}};
    b.json()["meshes"] = {{{"primitives", {primitive}}, {"weights", {0.5}}}};
    b.json()["nodes"] = {{{"mesh", 0}, {"name", "mesh weights"}}, {{"mesh", 0}, {"name", "node weights"}, {"weights", {2.0}}}};
    b.json()["scenes"] = {{{"nodes", {0, 1}}}};
    const Scene scene = load(b);
    expectNear(meshNamed(scene, "mesh weights").keyPositions(0)[2], {0, 1.5f, 0});
    expectNear(meshNamed(scene, "node weights").keyPositions(0)[2], {0, 3.0f, 0});
}

TEST(GltfLoader, SparseAccessorsReplaceTheirElements) {
    // Positions without a buffer view (all zero) plus sparse values for vertices 1 and 2.
    test::GltfBuilder b;
    const int indices = b.addView(std::vector<std::uint8_t>{1, 2, 0, 0}.data(), 4);
    const std::vector<float> values{1, 0, 0, 0, 1, 0};
    const int valuesView = b.addView(values.data(), values.size() * 4);
    b.json()["accessors"].push_back({{"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
                                     {"sparse", {{"count", 2}, {"indices", {{"bufferView", indices}, {"componentType", 5121}}},
                                                 {"values", {{"bufferView", valuesView}}}}}});
    b.addMeshNode({{"attributes", {{"POSITION", 0}}}});
    const Scene scene = load(b);
    expectNear(scene.meshes[0].keyPositions(0)[0], {0, 0, 0});
    expectNear(scene.meshes[0].keyPositions(0)[1], {1, 0, 0});
    expectNear(scene.meshes[0].keyPositions(0)[2], {0, 1, 0});
}

TEST(GltfLoader, GlbContainerLoadsLikeTheJsonFile) {
    test::GltfBuilder b;
    json primitive;
    primitive["indices"] = b.addIndices({0, 1, 2});
    primitive["attributes"]["NORMAL"] = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    addTriangle(b, {{"translation", {1, 2, 3}}}, primitive);
    GltfOptions options;
    options.allowExternalFiles = false;
    const Scene fromGlb = loadGltfFromMemory(b.glb(), "test.glb", "", options);
    const Scene fromGltf = load(b);
    EXPECT_EQ(fromGlb.meshes[0].positions, fromGltf.meshes[0].positions);
    EXPECT_EQ(fromGlb.meshes[0].normals, fromGltf.meshes[0].normals);
    expectNear(fromGlb.meshes[0].keyPositions(0)[0], {1, 2, 3});
}

TEST(GltfLoader, TheShutterSamplesTheAnimationIntoKeyPoses) {
    // LINEAR translation from (0,0,0) at 0 s to (10,0,0) at 1 s, in an animation named "slide"
    // after an empty one. Frame 6, shutter 12 frames at 24 fps: [0.25, 0.75] s; 3 keys at
    // 0.25, 0.5, 0.75 s: x offsets 2.5, 5, 7.5.
    test::GltfBuilder b;
    addTriangle(b);
    const int times = b.addFloats({0, 1}, "SCALAR", 1);
    const int moves = b.addFloats({0, 0, 0, 10, 0, 0}, "VEC3", 3);
    json slide = {{"name", "slide"}};
    slide["samplers"] = json::array({{{"input", times}, {"output", moves}}});
    slide["channels"] = json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}});
    json still = {{"name", "still"}, {"samplers", json::array()}, {"channels", json::array()}};
    b.json()["animations"] = json::array({still, slide});
    GltfOptions options;
    options.frame = 6;
    options.shutter = 12;
    options.motionKeys = 3;
    for (const std::string animation : {"slide", "1"}) {
        options.animation = animation;
        const Mesh mesh = load(b, options).meshes[0];
        ASSERT_EQ(mesh.numKeys, 3);
        for (int k = 0; k < 3; ++k) expectNear(mesh.keyPositions(k)[0], {2.5f * float(k + 1), 0, 0});
    }
    options.animation = "";  // the first: "still"
    EXPECT_TRUE(load(b, options).meshes[0].isStatic());
    options.animation = "nosuch";
    try {
        load(b, options);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("0 'still', 1 'slide'"), std::string::npos) << e.what();
    }
}

TEST(GltfLoader, CamerasComeFromTheFileOrTheOptions) {
    // Camera 0 is orthographic; camera 1 (perspective) is placed by a node at (0, 0, 5) turned
    // 90 degrees about y, so it looks down world -x.
    test::GltfBuilder b;
    addTriangle(b);
    b.json()["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}},
                           {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.02}}}}};
    b.json()["nodes"].push_back({{"camera", 0}});
    b.json()["nodes"].push_back(
        {{"camera", 1}, {"translation", {0, 0, 5}}, {"rotation", {0, std::sin(std::numbers::pi / 4), 0, std::cos(std::numbers::pi / 4)}}});
    b.addToScene(1);
    b.addToScene(2);
    const Scene scene = load(b);  // the first perspective camera, skipping the orthographic one
    expectNear(scene.camera.open.position, {0, 0, 5});
    expectNear(scene.camera.open.worldFromCamera * glm::vec3(0, 0, -1), {-1, 0, 0});
    EXPECT_FLOAT_EQ(scene.camera.verticalFov, 0.5f);
    EXPECT_FLOAT_EQ(scene.camera.zNear, 0.02f);

    GltfOptions options;
    options.camera = 0;
    EXPECT_THROW(load(b, options), Error);  // orthographic
    options.camera = 7;
    EXPECT_THROW(load(b, options), Error);
    options.camera.reset();
    options.lookAt = GltfLookAt{{0, 0, 10}, {0, 0, 0}, {0, 1, 0}, glm::vec3(2, 0, 10), std::nullopt, 30.0f};
    const Scene looking = load(b, options);
    expectNear(looking.camera.open.position, {0, 0, 10});
    expectNear(looking.camera.close.position, {2, 0, 10});
    expectNear(looking.camera.close.worldFromCamera * glm::vec3(0, 0, -1), glm::normalize(glm::vec3(-2, 0, -10)));
    EXPECT_NEAR(looking.camera.verticalFov, 30.0f * std::numbers::pi_v<float> / 180.0f, 1e-6f);
    options.lookAt->target = options.lookAt->position;
    EXPECT_THROW(load(b, options), Error);
}

TEST(SceneLoader, LoadsGltfFilesByExtension) {
    EXPECT_TRUE(isGltfSpec("a/b/Model.GLB"));
    EXPECT_TRUE(isGltfSpec("model.gltf"));
    EXPECT_FALSE(isGltfSpec("model.obj"));
    EXPECT_FALSE(isGltfSpec("builtin:cubes"));
    STREAK_REQUIRE_SHARED_SCENES();
    EXPECT_EQ(loadScene(test::sharedScene("AnimatedTriangle/glTF/AnimatedTriangle.gltf")).numTriangles(), 1u);
}

// ---- The Khronos sample models, against values computed by hand from their JSON and buffers.

TEST(GltfModels, InterpolationTestEveryPathAndInterpolation) {
    // Each of the nine animations moves one cube (mesh vertices in [-1, 1]^3, no parent). At
    // time 0 every animated rotation is the identity, every scale 1, and translations take
    // their first key (or the node's rest value): so a vertex at 0.6 s is
    // p(0.6) = T(0.6) + R(0.6) S(0.6) (p(0) - T(0)). The values at 0.6 s, from the keys:
    //  - scales: keys at 0.0417, 0.4167, 0.875 s with 1, 0.5, 1: u = (0.6 - 0.4167) / 0.4583 = 0.4.
    //    STEP 0.5; LINEAR 0.5 + 0.4 * 0.5 = 0.7; CUBICSPLINE (zero tangents) h00 0.5 + h01 1
    //    with h01 = 3u^2 - 2u^3 = 0.352: 0.676.
    //  - rotations about -z, keys 0, 45, 90 degrees at 0, 0.4167, 0.875 s, u = 0.4: STEP 45;
    //    LINEAR (slerp) 45 + 0.4 * 45 = 63; CUBICSPLINE with the file's tangents 59.649
    //    (Hermite of the quaternions, normalized; see gltf_animation_test for the formula).
    //  - translations in y, keys 10 and 6 at 0.4167 (0.4583 for STEP) and 0.8333 s:
    //    u = 0.44; STEP 10; LINEAR 10 - 0.44 * 4 = 8.24; CUBICSPLINE (zero tangents)
    //    10 + (6 - 10) * h01(0.44) = 8.35827.
    STREAK_REQUIRE_SHARED_SCENES();
    const std::string path = test::sharedScene("InterpolationTest/glTF-Binary/InterpolationTest.glb");
    struct Case {
        const char* animation;
        const char* node;
        glm::vec3 translation0;    // T(0)
        glm::vec3 translation;     // T(0.6)
        float degreesAboutMinusZ;  // R(0.6)
        float scale;               // S(0.6)
    };
    const glm::vec3 t3(-3.2963297f, 0, 6.461143e-05f), t4(3.3401194f, 0, 0.008944988f), t5(0, 3.3564124f, 0), t6(3.3350618f, 3.3564124f, 0),
        t7(-3.3113992f, 3.3564124f, 0);
    const Case cases[] = {
        {"Step Scale", "Cube", glm::vec3(0), glm::vec3(0), 0, 0.5f},
        {"Linear Scale", "Cube.001", t3, t3, 0, 0.7f},
        {"CubicSpline Scale", "Cube.002", t4, t4, 0, 0.676f},
        {"Step Rotation", "Cube.003", t5, t5, 45, 1},
        {"Linear Rotation", "Cube.005", t7, t7, 63, 1},
        {"CubicSpline Rotation", "Cube.004", t6, t6, 59.649384f, 1},
        {"Step Translation", "Cube.006", {0, 6.6652265f, 0}, {0, 10, 0}, 0, 1},
        {"Linear Translation", "Cube.009", {-3.2975807f, 6.6210146f, 0}, {-3.2975807f, 8.24f, 0}, 0, 1},
        {"CubicSpline Translation", "Cube.008", {3.3051798f, 6.6401172f, 0}, {3.3051798f, 8.3582718f, 0}, 0, 1},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.animation);
        GltfOptions options = atSeconds(0.0);
        options.animation = c.animation;
        const Mesh rest = meshNamed(loadGltf(path, options), c.node);
        options.frame = 0.6;
        const Mesh moved = meshNamed(loadGltf(path, options), c.node);
        const glm::quat rotation = glm::angleAxis(glm::radians(c.degreesAboutMinusZ), glm::vec3(0, 0, -1));
        ASSERT_EQ(rest.numVertices(), moved.numVertices());
        for (std::size_t v = 0; v < rest.numVertices(); ++v)
            expectNear(moved.keyPositions(0)[v], c.translation + rotation * (c.scale * (rest.keyPositions(0)[v] - c.translation0)), 1e-4f);
    }
}

TEST(GltfModels, SimpleSkinVertexFromTheJointMatrices) {
    // Joint 0 (node 1) stays at the origin, inverse bind identity: J0 = I. Joint 1 (node 2,
    // child of node 1 at (0, 1, 0)) rotates about z; its inverse bind translates by (0, -1, 0),
    // so J1 = T(0,1,0) R(a) T(0,-1,0): a rotation by a about (0, 1, 0). At 0.25 s the rotation
    // is the slerp half way from identity to the key (0, 0, 0.383, 0.924): a = 22.5168 degrees.
    // Vertex 6 = (-0.5, 1.5, 0) with weights 0.25 (J0), 0.75 (J1):
    //   J1 v6 = (0, 1) + R(a) (-0.5, 0.5) = (-0.65336, 1.27041)
    //   v6' = 0.25 (-0.5, 1.5) + 0.75 (-0.65336, 1.27041) = (-0.61502, 1.32781).
    // Vertex 8 = (-0.5, 2, 0), weight 1 on J1: (0, 1) + R(a) (-0.5, 1) = (-0.84484, 1.73229).
    STREAK_REQUIRE_SHARED_SCENES();
    const Scene scene = loadGltf(test::sharedScene("SimpleSkin/glTF/SimpleSkin.gltf"), atSeconds(0.25));
    ASSERT_EQ(scene.meshes.size(), 1u);
    const std::span<const glm::vec3> p = scene.meshes[0].keyPositions(0);
    ASSERT_EQ(p.size(), 10u);
    expectNear(p[6], {-0.6150205f, 1.3278052f, 0}, 1e-5f);
    expectNear(p[8], {-0.8448375f, 1.7322907f, 0}, 1e-5f);
    expectNear(p[0], {-0.5f, 0, 0}, 1e-6f);  // joint 0 only: unmoved
}

TEST(GltfModels, SimpleMorphWeightsFollowTheAnimation) {
    // Vertex 2 = (0.5, 0.5, 0) with target deltas (-1, 1, 0) and (1, 1, 0). The weights keys
    // are (0,0), (0,1), (1,1), (1,0), (0,0) at 0..4 s: at 1.5 s (0.5, 1), at 2.5 s (1, 0.5).
    //   1.5 s: (0.5, 0.5) + 0.5 (-1, 1) + 1 (1, 1) = (1, 2); 2.5 s: (0.5,0.5) + (-1,1) + 0.5 (1,1) = (0, 2).
    // With the shutter over [1.5, 2.5] s and 3 keys, the middle key (2 s, weights (1, 1)) is (0.5, 2.5).
    STREAK_REQUIRE_SHARED_SCENES();
    const Scene scene = loadGltf(test::sharedScene("SimpleMorph/glTF/SimpleMorph.gltf"), atSeconds(1.5, 1.0, 3));
    const Mesh& mesh = scene.meshes[0];
    expectNear(mesh.keyPositions(0)[2], {1, 2, 0});
    expectNear(mesh.keyPositions(1)[2], {0.5f, 2.5f, 0});
    expectNear(mesh.keyPositions(2)[2], {0, 2, 0});
    expectNear(mesh.keyPositions(1)[0], {0, 0, 0});
}

TEST(GltfModels, ToyCarCameraPoseAndFieldOfView) {
    // Camera 0 is placed by node 3 ("Camera001", a root): translation
    // (-0.0169006381, 0.0253599286, 0.0302319955), rotation (x, y, z, w) =
    // (-0.330993533, -0.274300218, -0.101194724, 0.8971969), yfov 0.9, znear 0.001. Camera 1
    // (node 4) has yfov 0.41.
    STREAK_REQUIRE_SHARED_SCENES();
    const std::string path = test::sharedScene("ToyCar/glTF/ToyCar.gltf");
    const Scene scene = loadGltf(path, GltfOptions{});
    const Camera& camera = scene.camera;
    EXPECT_TRUE(camera.isStatic());
    expectNear(camera.open.position, {-0.0169006381f, 0.0253599286f, 0.0302319955f}, 1e-7f);
    const glm::quat expected = glm::normalize(glm::quat(0.8971969f, -0.330993533f, -0.274300218f, -0.101194724f));
    EXPECT_NEAR(std::abs(glm::dot(camera.open.worldFromCamera, expected)), 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(camera.verticalFov, 0.9f);
    EXPECT_FLOAT_EQ(camera.zNear, 0.001f);
    GltfOptions second;
    second.camera = 1;
    const Scene other = loadGltf(path, second);
    EXPECT_FLOAT_EQ(other.camera.verticalFov, 0.41f);
    expectNear(other.camera.open.position, {-0.04332856f, 0.0235993266f, 0.0760967f}, 1e-7f);
}

}  // namespace streak

namespace streak {

namespace {

// A triangle on a node turning 90 degrees about z over 1 s (LINEAR: constant angular speed).
test::GltfBuilder quarterTurn() {
    test::GltfBuilder b;
    addTriangle(b);
    const float s = std::sin(std::numbers::pi_v<float> / 4), c = std::cos(std::numbers::pi_v<float> / 4);
    const int times = b.addFloats({0, 1}, "SCALAR", 1);
    const int turns = b.addFloats({0, 0, 0, 1, 0, 0, s, c}, "VEC4", 4);
    json turn;
    turn["samplers"] = json::array({{{"input", times}, {"output", turns}}});
    turn["channels"] = json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}});
    b.json()["animations"] = json::array({turn});
    return b;
}

// The farthest the keyed path of quarterTurn()'s vertex (1, 0, 0) strays on screen from the
// true turn (cos 90t, sin 90t, 0), over 1001 times, in pixels of an image 240 tall.
double quarterTurnScreenError(const Scene& scene, float aspect) {
    const Mesh& mesh = scene.meshes[0];
    double worst = 0.0;
    for (int i = 0; i <= 1000; ++i) {
        const float t = float(i) / 1000.0f;
        const glm::mat4 clipFromWorld = scene.camera.clipFromWorld(t, aspect);
        const glm::vec3 keyed = mesh.positionAt(1, mesh.weightsAt(t));
        const float angle = std::numbers::pi_v<float> / 2 * t;
        const glm::vec4 a = clipFromWorld * glm::vec4(keyed, 1.0f), b = clipFromWorld * glm::vec4(std::cos(angle), std::sin(angle), 0.0f, 1.0f);
        const glm::vec2 d = (glm::vec2(a) / a.w - glm::vec2(b) / b.w) * glm::vec2(0.5f * 240.0f * aspect, 0.5f * 240.0f);
        worst = std::max(worst, double(glm::length(d)));
    }
    return worst;
}

}  // namespace

TEST(GltfLoader, APrimitivePlacedByTwoNodesGivesEachMeshAllItsTrianglesAndColours) {
    // quarterTurn()'s triangle, with vertex colours, placed a second time by a still mirrored
    // node. The turn makes the default keys refine after the meshes were first written to place
    // the camera, so the meshes are written twice. A mesh may take its primitive's arrays only
    // where one node places it: here both must keep the whole of them, the mirrored one flipped.
    test::GltfBuilder b = quarterTurn();
    b.json()["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = b.addFloats({1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3", 3);
    b.json()["nodes"].push_back({{"mesh", 0}, {"scale", {-1, 1, 1}}, {"translation", {3, 0, 0}}});
    b.addToScene(1);
    GltfOptions options;
    options.shutter = 24;
    RenderStats stats;
    const Scene scene = load(b, options, &stats);
    ASSERT_EQ(scene.meshes.size(), 2u);
    const Mesh& turning = scene.meshes[0];
    const Mesh& mirrored = scene.meshes[1];
    ASSERT_GT(turning.numKeys, 2);  // refined after the first write
    EXPECT_EQ(stats.counter("motion_keys"), double(turning.numKeys));
    EXPECT_EQ(mirrored.numKeys, turning.numKeys);
    EXPECT_EQ(turning.triangles, std::vector<glm::uvec3>{glm::uvec3(0, 1, 2)});
    EXPECT_EQ(mirrored.triangles, std::vector<glm::uvec3>{glm::uvec3(0, 2, 1)});
    const std::vector<glm::vec4> colours = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};
    EXPECT_EQ(turning.colors, colours);
    EXPECT_EQ(mirrored.colors, colours);
    for (const Mesh* mesh : {&turning, &mirrored}) EXPECT_EQ(mesh->positions.size(), 3u * std::size_t(mesh->numKeys));
    // Every key holds its own time's pose: the turning vertex (1, 0, 0) ends at (0, 1, 0); the
    // still mirrored one stays at (3 - 1, 0, 0).
    expectNear(turning.keyPositions(0)[1], {1, 0, 0});
    expectNear(turning.keyPositions(turning.numKeys - 1)[1], {0, 1, 0});
    for (int k = 0; k < mirrored.numKeys; ++k) expectNear(mirrored.keyPositions(k)[1], {2, 0, 0});
}

TEST(GltfLoader, DefaultKeysFollowARotationWithinTheTolerance) {
    // A node turning 90 degrees about z over 1 s (LINEAR: constant angular speed), the whole
    // second in the shutter. Vertex (1, 0, 0) truly sits at (cos 90t, sin 90t, 0); the chosen
    // piecewise-linear keys must stay within the tolerance of it on screen at every time.
    test::GltfBuilder b = quarterTurn();
    GltfOptions options;
    options.shutter = 24;
    options.imageHeight = 240;
    options.aspect = 4.0f / 3.0f;
    RenderStats stats;
    const Scene scene = load(b, options, &stats);
    const Mesh& mesh = scene.meshes[0];
    const int keys = mesh.numKeys;
    EXPECT_EQ(stats.counter("motion_keys"), double(keys));
    EXPECT_GT(keys, 2);
    EXPECT_LE(keys, options.maxMotionKeys);
    EXPECT_EQ((keys - 1) & (keys - 2), 0) << "2^m + 1 keys, so coarser keys stay keys";
    EXPECT_LE(stats.counter("motion_key_deviation_px"), options.keyTolerancePixels);
    const double worst = quarterTurnScreenError(scene, options.aspect);
    EXPECT_LE(worst, options.keyTolerancePixels * 1.05);
    std::printf("%d keys, %.4f px measured, %.4f px by the loader\n", keys, worst, stats.counter("motion_key_deviation_px"));

    // Two keys leave the quarter turn's chord 29% of the radius off; an explicit count wins.
    options.motionKeys = 2;
    EXPECT_EQ(load(b, options).meshes[0].numKeys, 2);
    // A still animation needs no more than two.
    options.motionKeys = 0;
    options.shutter = 0;
    EXPECT_EQ(load(b, options).meshes[0].numKeys, 2);
}

}  // namespace streak

namespace streak {

TEST(GltfLoader, BezierKeysFollowARotationByLeastSquaresOrThroughThePoses) {
    // The node turning 90 degrees about z over the shutter, as Bezier keys: --motion-curve bezier
    // with 3 keys is the quadratic fitted by least squares to 9 poses by default, or with
    // --motion-fit-samples 0 the quadratic through 3 of them (it meets the circle there). Both
    // follow the quarter circle far closer than the chord of two keys (0.29 radii); least
    // squares has the smaller largest error.
    test::GltfBuilder b = quarterTurn();
    const float s = std::sin(std::numbers::pi_v<float> / 4), c = std::cos(std::numbers::pi_v<float> / 4);
    GltfOptions options;
    options.shutter = 24;
    options.motionKeys = 3;
    options.motionCurve = MotionInterpolation::Bezier;
    const auto worstError = [&](const Scene& scene) {
        const Mesh& mesh = scene.meshes[0];
        EXPECT_EQ(mesh.numKeys, 3);
        EXPECT_EQ(mesh.interpolation, MotionInterpolation::Bezier);
        double worst = 0.0;
        for (int i = 0; i <= 1000; ++i) {
            const float t = float(i) / 1000.0f, angle = std::numbers::pi_v<float> / 2 * t;
            worst = std::max(worst, double(glm::distance(mesh.positionAt(1, mesh.weightsAt(t)), glm::vec3(std::cos(angle), std::sin(angle), 0.0f))));
        }
        return worst;
    };
    RenderStats stats;
    const double fitted = worstError(load(b, options, &stats));
    EXPECT_EQ(stats.counter("motion_fit_samples"), 9.0);
    options.motionFitSamples = 0;
    const Scene through = load(b, options);
    const double interpolated = worstError(through);
    // Through the poses: exact at t = 1/2.
    expectNear(through.meshes[0].positionAt(1, through.meshes[0].weightsAt(0.5f)), {c, s, 0.0f}, 1e-5f);
    EXPECT_LT(interpolated, 0.05);
    EXPECT_LT(fitted, interpolated);
    // Least squares needs Bezier keys and more poses than keys.
    options.motionFitSamples = 3;
    EXPECT_THROW(load(b, options), Error);
}

TEST(GltfLoader, ChosenBezierPiecesFollowARotationWithinTheToleranceInFewerPiecesThanLinearKeys) {
    // --motion-curve bezier without --motion-keys: quadratic (or cubic) pieces through evenly
    // spaced poses, 1, 2, 4... of them until they stay within the tolerance of the animation, as
    // linear keys are chosen. The quarter turn's true path is a circle: the chosen pieces must
    // follow it within the tolerance at every time, joined where they meet, and take fewer pieces
    // than the linear keys take segments.
    test::GltfBuilder b = quarterTurn();
    GltfOptions options;
    options.shutter = 24;
    options.imageHeight = 240;
    RenderStats linearStats;
    const int segments = load(b, options, &linearStats).meshes[0].numKeys - 1;
    EXPECT_EQ(linearStats.info().at("motion_keys_chosen_by"), "screen");  // not the cap
    options.motionCurve = MotionInterpolation::Bezier;
    for (const int order : {2, 3}) {
        options.bezierOrder = order;
        RenderStats stats;
        const Scene scene = load(b, options, &stats);
        const Mesh& mesh = scene.meshes[0];
        EXPECT_EQ(mesh.interpolation, MotionInterpolation::Bezier);
        EXPECT_EQ(mesh.bezierOrder(), order);
        EXPECT_EQ(mesh.numKeys, mesh.bezierPieces * order + 1);
        EXPECT_EQ(mesh.bezierPieces & (mesh.bezierPieces - 1), 0) << "1, 2, 4... pieces";
        EXPECT_EQ(stats.counter("motion_bezier_pieces"), double(mesh.bezierPieces));
        EXPECT_EQ(stats.counter("motion_bezier_order"), double(order));
        EXPECT_EQ(stats.info().at("motion_keys_chosen_by"), "screen");
        EXPECT_LE(stats.counter("motion_key_deviation_px"), options.keyTolerancePixels);
        const double worst = quarterTurnScreenError(scene, options.aspect);
        EXPECT_LE(worst, options.keyTolerancePixels * 1.25);
        EXPECT_LE(4 * mesh.bezierPieces, segments);  // chords measured in their place would give segments / order
        // Each piece passes through the animation at its poses (the curve through them): at the
        // first piece's first inner pose and at its joint the vertex sits on the circle.
        for (const float t : {1.0f / float(order * mesh.bezierPieces), 1.0f / float(mesh.bezierPieces)}) {
            const float angle = std::numbers::pi_v<float> / 2 * t;
            expectNear(mesh.positionAt(1, mesh.weightsAt(t)), {std::cos(angle), std::sin(angle), 0.0f}, 1e-5f);
        }
        std::printf("degree %d: %d pieces (%d keys), %.4f px measured, %.4f px by the loader; linear keys: %d segments (%.4f px)\n", order,
                    mesh.bezierPieces, mesh.numKeys, worst, stats.counter("motion_key_deviation_px"), segments,
                    linearStats.counter("motion_key_deviation_px"));
    }
    // The degree takes 2 or 3, and --motion-keys with bezier stays one curve of 3 or 4 keys.
    options.bezierOrder = 4;
    EXPECT_THROW(load(b, options), Error);
    options.bezierOrder = 2;
    options.motionKeys = 5;
    EXPECT_THROW(load(b, options), Error);
}

}  // namespace streak

namespace streak {

// A node translated along a zigzag, LINEAR keys at 0, 1, 2 and 3 s: (0,0,0), (1,0,0), (1,1,0),
// (0,1,0). With the shutter over all of it, the motion kinks at a third and two thirds of the
// shutter, which halving (2, 3, 5, 9... keys) never puts a key on: its keys cut the corners. Four
// even keys hold the kinks, and the chosen keys are those four, each the animation's own pose,
// the path between them the animation's to float rounding. With the shutter over [0, 2] s
// (one kink, at the middle), halving's three keys already hold it and stay.
TEST(GltfLoader, DefaultKeysFallOnTheAnimationsOwnKeyframesWhereAnEvenGridHoldsThem) {
    test::GltfBuilder b;
    addTriangle(b);
    const int times = b.addFloats({0, 1, 2, 3}, "SCALAR", 1);
    const int moves = b.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
    json zigzag;
    zigzag["samplers"] = json::array({{{"input", times}, {"output", moves}}});
    zigzag["channels"] = json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}});
    b.json()["animations"] = json::array({zigzag});
    GltfOptions options = atSeconds(0.0, 3.0, 0);
    options.imageHeight = 240;
    options.aspect = 4.0f / 3.0f;
    RenderStats stats;
    const Scene scene = load(b, options, &stats);
    const Mesh& mesh = scene.meshes[0];
    ASSERT_EQ(mesh.numKeys, 4);
    ASSERT_TRUE(stats.info().count("motion_keys_on"));
    EXPECT_EQ(stats.info().at("motion_keys_on"), "keyframes");
    EXPECT_LE(stats.counter("motion_key_deviation_px"), 1e-3);
    const std::array<glm::vec3, 4> corner{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)};
    for (int i = 0; i <= 300; ++i) {
        const float t = float(i) / 300.0f;  // the vertex at (0,0,0), t * 3 seconds in
        const float seconds = 3.0f * t;
        const int leg = std::min(int(seconds), 2);
        const glm::vec3 truth = glm::mix(corner[std::size_t(leg)], corner[std::size_t(leg + 1)], seconds - float(leg));
        expectNear(mesh.positionAt(0, mesh.weightsAt(t)), truth, 1e-5f);
    }

    options.shutter = 2.0;
    RenderStats halving;
    EXPECT_EQ(load(b, options, &halving).meshes[0].numKeys, 3);
    EXPECT_EQ(halving.info().count("motion_keys_on"), 0u);
}

TEST(GltfLoader, DefaultKeysBoundTheDepthWhereSurfacesCanPassInFrontOfEachOther) {
    // Two quads passing through each other along the view axis: their corners move a tenth of a
    // pixel on screen, but their depths swing 2 pixels' worth (0.005 at 3 units, through yfov 0.2,
    // 240 pixels tall), so the keys are chosen by depth (17). Alone, the same quad is chosen by
    // its screen path and takes 5: a lone surface's depth error hides nothing.
    GltfOptions options;
    options.shutter = 24.0;
    options.imageHeight = 240;
    RenderStats both, alone;
    const Scene two = load(test::quadsThroughEachOther(2), options, &both);
    const Scene one = load(test::quadsThroughEachOther(1), options, &alone);
    EXPECT_EQ(both.info().at("motion_keys_chosen_by"), "depth");
    EXPECT_EQ(alone.info().at("motion_keys_chosen_by"), "screen");
    EXPECT_EQ(alone.counter("motion_key_depth_deviation_px"), 0.0);
    EXPECT_GT(two.meshes[0].numKeys, 2 * one.meshes[0].numKeys);
    EXPECT_LE(both.counter("motion_key_depth_deviation_px"), options.keyTolerancePixels);
    EXPECT_LE(both.counter("motion_key_deviation_px"), options.keyTolerancePixels);
    std::printf("together %d keys (depth %.3f px, screen %.3f px); alone %d keys (screen %.3f px)\n", two.meshes[0].numKeys,
                both.counter("motion_key_depth_deviation_px"), both.counter("motion_key_deviation_px"), one.meshes[0].numKeys,
                alone.counter("motion_key_deviation_px"));
}

}  // namespace streak
