#include "scene/builtin_scenes.h"
#include "util/error.h"

#include <gtest/gtest.h>

namespace streak {

TEST(BuiltinScenes, AllBuildValidAndDeterministic) {
    ASSERT_EQ(builtinScenes().size(), 7u);
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        SCOPED_TRACE(std::string(info.name));
        Scene a = makeBuiltinScene(info.name, OptionMap());
        Scene b = makeBuiltinScene(info.name, OptionMap());
        EXPECT_GT(a.numTriangles(), 0u);
        const SceneCleanup cleanup = validateScene(a);
        EXPECT_EQ(cleanup.numSkipped(), 0u);
        validateScene(b);
        ASSERT_EQ(a.meshes.size(), b.meshes.size());
        for (std::size_t m = 0; m < a.meshes.size(); ++m) EXPECT_EQ(a.meshes[m].positions, b.meshes[m].positions);
    }
}

// Sizes are bounded together, not only one by one: a million cubes of 64 keys would be 45 GB.
TEST(BuiltinScenes, CubesRejectsMorePosesThanItsBudget) {
    OptionMap huge;
    huge.set("n", "1000000");
    huge.set("keys", "64");
    try {
        makeBuiltinScene("cubes", huge);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("n * keys must be at most 2000000"), std::string::npos) << e.what();
    }
}

TEST(BuiltinScenes, EachShowsWhatItsNameSays) {
    // cubes: n cubes of 12 triangles, moving; a different seed moves them elsewhere.
    OptionMap n5;
    n5.set("n", "5");
    const Scene cubes = makeBuiltinScene("cubes", n5);
    EXPECT_EQ(cubes.numTriangles(), 60u);
    EXPECT_FALSE(cubes.meshes[0].isStatic());
    EXPECT_EQ(makeBuiltinScene("cubes", OptionMap()).numTriangles(), 12000u);
    // pan: everything static, only the camera moves.
    const Scene pan = makeBuiltinScene("pan", OptionMap());
    EXPECT_FALSE(pan.camera.isStatic());
    for (const Mesh& mesh : pan.meshes) EXPECT_TRUE(mesh.isStatic());
    // translucent: has translucent and opaque materials.
    const Scene translucent = makeBuiltinScene("translucent", OptionMap());
    EXPECT_TRUE(translucent.hasTranslucency());
    // twist: the triangle's bottom corners swap sides (x changes sign).
    const Scene twist = makeBuiltinScene("twist", OptionMap());
    const Mesh& tri = twist.meshes[0];
    EXPECT_LT(tri.positions[0].x * tri.positions[3].x, 0.0f);
    // crossing: the first triangle starts in front of the second and ends behind it.
    const Scene crossing = makeBuiltinScene("crossing", OptionMap());
    EXPECT_GT(crossing.meshes[0].positions[0].z, crossing.meshes[1].positions[0].z);
    EXPECT_LT(crossing.meshes[0].positions[3].z, crossing.meshes[1].positions[3].z);
}

}  // namespace streak
