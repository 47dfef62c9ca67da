// Broken, truncated and hostile glTF files: each is one Error naming the file and the
// problem, never a crash, a hang or a huge allocation. The sanitizer build runs these too.

#include "scene/gltf_document.h"
#include "scene/gltf_loader.h"
#include "support/gltf_samples.h"
#include "support/shared_scenes.h"
#include "support/temp_dir.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

namespace streak {

namespace {

using nlohmann::json;

// Small limits, as the fuzzer uses, so the absurd-size cases stay cheap.
GltfOptions smallLimits() {
    GltfOptions options;
    options.allowExternalFiles = false;
    options.limits.maxTriangles = 1000;
    options.limits.maxVertexWork = 100000;
    options.limits.maxTexels = 1 << 16;
    return options;
}

// The message of the Error loading `bytes` throws, or "" when it loads.
std::string errorOf(const std::vector<std::uint8_t>& bytes, const GltfOptions& options = smallLimits()) {
    try {
        loadGltfFromMemory(bytes, "broken.gltf", "", options);
        return "";
    } catch (const Error& e) {
        return e.what();
    }
}

// A valid indexed, textured, skinned, animated triangle that each case then breaks.
test::GltfBuilder validFile() { return test::skinnedTexturedTriangle(); }

}  // namespace

TEST(GltfBadInput, TheValidFilesLoad) {
    EXPECT_EQ(errorOf(validFile().gltfBytes()), "");
    EXPECT_EQ(errorOf(validFile().glb()), "");
    EXPECT_EQ(errorOf(test::morphingStripWithCamera().gltfBytes()), "");
    EXPECT_EQ(errorOf(test::morphingStripWithCamera().glb()), "");
}

TEST(GltfBadInput, EachBreakageIsOneLineErrorNamingFileAndProblem) {
    struct Case {
        const char* what;
        std::function<void(test::GltfBuilder&, json&)> breakIt;
        const char* expected;  // part of the message
    };
    using B = test::GltfBuilder;
    auto attribute = [](json& j, const char* name) -> json& { return j["meshes"][0]["primitives"][0]["attributes"][name]; };
    const std::vector<Case> cases{
        {"accessor index out of range", [&](B&, json& j) { attribute(j, "POSITION") = 99; }, "accessor 99 does not exist"},
        {"accessor beyond its view", [](B&, json& j) { j["accessors"][0]["count"] = 4; }, "exceed buffer view"},
        {"accessor offset beyond its view", [](B&, json& j) { j["accessors"][0]["byteOffset"] = 1u << 30; }, "exceed buffer view"},
        {"absurd accessor count", [](B&, json& j) { j["accessors"][0]["count"] = 4000000000u; }, "limit"},
        {"absurd animation accessor count", [](B&, json& j) { j["accessors"][5]["count"] = 4000000000u; }, "over the limit"},
        {"view beyond its buffer", [](B&, json& j) { j["bufferViews"][0]["byteLength"] = 1000000; }, "exceeds buffer"},
        {"view of a missing buffer", [](B&, json& j) { j["bufferViews"][0]["buffer"] = 3; }, "does not exist"},
        {"stride below the element size", [](B&, json& j) { j["bufferViews"][0]["byteStride"] = 4; }, "byteStride"},
        {"wrong element type", [](B&, json& j) { j["accessors"][0]["type"] = "VEC2"; }, "element type is VEC2, expected VEC3"},
        {"wrong component type", [](B&, json& j) { j["accessors"][0]["componentType"] = 5121; }, "component type 5121 is not allowed"},
        {"signed int components", [](B&, json& j) { j["accessors"][0]["componentType"] = 5124; }, ""},
        {"vertex index out of range", [](B& b, json& j) { j["meshes"][0]["primitives"][0]["indices"] = b.addIndices({0, 1, 7}); },
         "index 7 is out of range (3 vertices)"},
        {"index count not a multiple of 3", [](B&, json& j) { j["accessors"][4]["count"] = 2; }, "not a multiple of 3"},
        {"attribute count differs", [](B&, json& j) { j["accessors"][1]["count"] = 2; }, "2 elements for 3 vertices"},
        {"joint index out of range",
         [&](B& b, json& j) { attribute(j, "JOINTS_0") = b.addAccessor(std::vector<std::uint8_t>{0, 0, 0, 0, 5, 0, 0, 0, 0, 0, 0, 0}, "VEC4", 4, 5121); },
         "joint index 5 is out of range for skin 0"},
        {"joints without weights", [&](B&, json& j) { j["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0"); }, "no WEIGHTS_0"},
        {"skin without joints", [](B&, json& j) { j["skins"][0]["joints"] = json::array(); }, "skin 0: has no joints"},
        {"joint node missing", [](B&, json& j) { j["skins"][0]["joints"] = {42}; }, "joint node 42 does not exist"},
        {"unsupported required extension", [](B&, json& j) { j["extensionsRequired"] = {"KHR_draco_mesh_compression"}; },
         "requires extension KHR_draco_mesh_compression"},
        {"child out of range", [](B&, json& j) { j["nodes"][1]["children"] = {7}; }, "child 7 does not exist"},
        {"two parents", [](B&, json& j) { j["nodes"].push_back({{"children", {1}}}), j["nodes"][0]["children"] = {1}; }, "more than one parent"},
        {"cycle", [](B&, json& j) { j["nodes"].push_back({{"children", {3}}}), j["nodes"].push_back({{"children", {2}}}); }, "cycle"},
        {"scene node not a root", [](B&, json& j) { j["nodes"][0]["children"] = {1}; }, "is not a root"},
        {"transform beyond float", [](B&, json& j) { j["nodes"][1]["scale"] = {1, 1e300, 1}; }, "non-finite"},
        {"bad rotation", [](B&, json& j) { j["nodes"][1]["rotation"] = {0, 0, 0, 0}; }, "not a unit quaternion"},
        {"material missing", [](B&, json& j) { j["meshes"][0]["primitives"][0]["material"] = 5; }, "material 5 does not exist"},
        {"texture missing", [](B&, json& j) { j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 3; }, "texture 3 does not exist"},
        {"uv set missing", [](B&, json& j) { j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1; }, "TEXCOORD_1"},
        {"image not an image", [](B&, json& j) { j["images"][0]["uri"] = "data:image/png;base64,AAAA"; }, "not a PNG or JPEG"},
        {"image missing", [](B&, json& j) { j["images"][0] = {{"uri", "nosuch.png"}}; }, "image 0 'nosuch.png': missing"},
        {"image view beyond its buffer",
         [](B&, json& j) { j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 1 << 20}, {"byteLength", 64}}),
                           j["images"][0] = {{"bufferView", j["bufferViews"].size() - 1}, {"mimeType", "image/png"}}; },
         ""},
        {"bad alpha mode", [](B&, json& j) { j["materials"][0]["alphaMode"] = "SOMETIMES"; }, "unknown alphaMode"},
        {"bad wrap mode", [](B&, json& j) { j["samplers"] = {{{"wrapS", 1234}}}, j["textures"][0]["sampler"] = 0; }, "unknown wrap mode 1234"},
        {"animation times decrease", [](B& b, json& j) { j["animations"][0]["samplers"][0]["input"] = b.addFloats({1, 0}, "SCALAR", 1); },
         "key times are not finite and increasing"},
        {"animation output count", [](B&, json& j) { j["accessors"][6]["count"] = 1; }, "3 output values for 2 keys"},
        {"animation interpolation", [](B&, json& j) { j["animations"][0]["samplers"][0]["interpolation"] = "QUADRATIC"; }, "unknown interpolation"},
        {"animation sampler missing", [](B&, json& j) { j["animations"][0]["channels"][0]["sampler"] = 9; }, ""},
        {"animated matrix node", [](B&, json& j) { j["nodes"][1]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }, "has a matrix"},
        {"weights of a node without targets", [](B&, json& j) { j["animations"][0]["channels"][0]["target"]["path"] = "weights"; },
         "no morph targets"},
        {"missing scene", [](B&, json& j) { j["scene"] = 4; }, ""},
        {"too many morph weights (instancing)",
         [](B&, json& j) {
             j["meshes"][0]["primitives"][0]["targets"] = json::array();
             for (int t = 0; t < 2000; ++t) j["meshes"][0]["primitives"][0]["targets"].push_back({{"POSITION", 0}});
             for (int i = 0; i < 30; ++i) j["nodes"].push_back({{"mesh", 0}});
         },
         "morph weights times motion keys exceed the limit"},
        {"too many triangles (instancing)",
         [](B&, json& j) {
             for (int i = 0; i < 1200; ++i) j["nodes"].push_back({{"mesh", 0}}), j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
         },
         "more than 1000 triangles"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        test::GltfBuilder b = validFile();
        c.breakIt(b, b.json());
        for (const auto& bytes : {b.gltfBytes(), b.glb()}) {
            const std::string message = errorOf(bytes);
            EXPECT_NE(message, "") << "loaded";
            EXPECT_EQ(message.rfind("broken.gltf: ", 0), 0u) << message;
            EXPECT_NE(message.find(c.expected), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
}

TEST(GltfBadInput, NonTrianglesAndMissingPositionsAreSkippedNotErrors) {
    test::GltfBuilder b = validFile();
    b.json()["meshes"][0]["primitives"].push_back({{"attributes", json::object()}});
    b.json()["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"mode", 1}});
    RenderStats stats;
    GltfOptions options = smallLimits();
    EXPECT_EQ(loadGltfFromMemory(b.gltfBytes(), "x.gltf", "", options, &stats).meshes.size(), 1u);
    EXPECT_EQ(stats.counter("gltf_skipped_primitives"), 2.0);
}

TEST(GltfBadInput, MalformedAndTruncatedFilesAreErrors) {
    for (const std::string& text : {std::string(""), std::string("{"), std::string("{\"asset\": 5}"), std::string("[1, 2]"),
                                    std::string("glTF")}) {
        SCOPED_TRACE(text);
        EXPECT_NE(errorOf({text.begin(), text.end()}), "");
    }
    // Every prefix of a valid file (both forms) fails cleanly or, rarely, loads.
    for (const std::vector<std::uint8_t>& whole : {validFile().gltfBytes(), validFile().glb()})
        for (std::size_t length = 0; length < whole.size(); length += 7) errorOf({whole.begin(), whole.begin() + std::ptrdiff_t(length)});
    // A GLB whose chunk lengths lie.
    std::vector<std::uint8_t> glb = validFile().glb();
    for (const std::size_t at : {std::size_t(8), std::size_t(12), std::size_t(20 + glb[12] + 256 * glb[13])}) {
        std::vector<std::uint8_t> lying = glb;
        lying[at] = 0xff, lying[at + 1] = 0xff, lying[at + 2] = 0xff, lying[at + 3] = 0x7f;
        EXPECT_NE(errorOf(lying), "") << at;
    }
}

TEST(GltfBadInput, DeeplyNestedJsonIsRefusedBeforeParsing) {
    // tinygltf would recurse once per level of "extras"; 100000 levels would overflow the stack.
    test::GltfBuilder b = validFile();
    std::string text = b.gltf();
    text.insert(text.size() - 1, ",\"extras\":" + std::string(100000, '[') + std::string(100000, ']'));
    const std::string message = errorOf({text.begin(), text.end()});
    EXPECT_NE(message.find("nested deeper than"), std::string::npos) << message;
    // Brackets inside strings and in a .glb's binary chunk are not nesting.
    test::GltfBuilder brackets = validFile();
    brackets.json()["asset"]["generator"] = std::string(500, '[');
    const std::vector<std::uint8_t> binary(500, '[');
    brackets.addView(binary.data(), binary.size());
    EXPECT_EQ(errorOf(brackets.gltfBytes()), "");
    EXPECT_EQ(errorOf(brackets.glb()), "");
}

TEST(GltfBadInput, FilesOnDiskMissingBuffersAndExternalFiles) {
    test::TempDir dir;
    test::GltfBuilder b = validFile();
    json j = json::parse(b.gltf());
    j["buffers"][0]["uri"] = "missing.bin";
    std::ofstream(dir.file("scene.gltf")) << j.dump();
    GltfOptions options;
    try {
        loadGltf(dir.file("scene.gltf"), options);
        FAIL() << "loaded";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(dir.file("scene.gltf") + ": ", 0), 0u) << e.what();
    }
    // The buffer written beside it loads; a folder named as a buffer does not.
    std::ofstream(dir.file("missing.bin"), std::ios::binary).write(reinterpret_cast<const char*>(b.buffer().data()), std::streamsize(b.buffer().size()));
    EXPECT_NO_THROW(loadGltf(dir.file("scene.gltf"), options));
    std::filesystem::remove(dir.file("missing.bin"));
    std::filesystem::create_directory(dir.file("missing.bin"));
    EXPECT_THROW(loadGltf(dir.file("scene.gltf"), options), Error);
    // From memory with files not allowed, the same uri is an error too.
    const std::string text = j.dump();
    EXPECT_NE(errorOf({text.begin(), text.end()}), "");
    EXPECT_THROW(loadGltf(dir.file("nosuch.glb"), options), Error);
}

TEST(GltfBadInput, ImagesLargerThanTheLimitAreRefusedBeforeDecoding) {
    // A PNG header claiming 8192 x 8192 (and no data): refused from its size alone.
    test::GltfBuilder b = validFile();
    std::vector<std::uint8_t> png{0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52,
                                  0x00, 0x00, 0x20, 0x00, 0x00, 0x00, 0x20, 0x00, 0x08, 0x06, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00};
    b.json()["images"][0]["uri"] = "data:image/png;base64," + test::GltfBuilder::base64(png);
    const std::string message = errorOf(b.gltfBytes());
    EXPECT_NE(message.find("over the limit"), std::string::npos) << message;
}

TEST(GltfBadInput, CorruptedSampleModelsNeverCrash) {
    // Random byte flips in real files (seeded): each load either succeeds or throws Error.
    STREAK_REQUIRE_SHARED_SCENES();
    std::mt19937 rng(11);
    for (const char* model : {"RiggedSimple/glTF-Binary/RiggedSimple.glb", "AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb",
                              "BoxAnimated/glTF-Binary/BoxAnimated.glb"}) {
        SCOPED_TRACE(model);
        const std::vector<std::uint8_t> original = gltf::readFileBytes(test::sharedScene(model), 1 << 24);
        for (int trial = 0; trial < 40; ++trial) {
            std::vector<std::uint8_t> bytes = original;
            for (int flips = 0; flips < 4; ++flips) bytes[rng() % bytes.size()] = std::uint8_t(rng());
            if (trial % 4 == 0) bytes.resize(rng() % bytes.size());
            errorOf(bytes);
        }
    }
}

}  // namespace streak
