#include "scene/builtin_scenes.h"
#include "util/error.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace streak {

TEST(BuiltinScenes, AllBuildValidAndDeterministic) {
    ASSERT_EQ(builtinScenes().size(), 10u);
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

TEST(BuiltinScenes, SphereRejectsMorePosesThanItsBudget) {
    OptionMap huge;
    huge.set("triangles", "1000000");
    huge.set("keys", "8");
    EXPECT_THROW(makeBuiltinScene("sphere", huge), Error);
}

// sphere: about `triangles` triangles (4 r (r - 1) for r rings), a closed unit sphere wound
// counter-clockwise seen from outside, translating by `travel` along +x.
TEST(BuiltinScenes, SphereIsAClosedUnitSphereTranslatingAlongX) {
    OptionMap options;
    options.set("triangles", "3968");
    options.set("travel", "2");
    Scene scene = makeBuiltinScene("sphere", options);
    validateScene(scene);
    const Mesh& sphere = scene.meshes.back();
    EXPECT_EQ(sphere.triangles.size(), 3968u);  // r = 32
    const std::size_t n = sphere.numVertices();
    for (std::size_t v = 0; v < n; ++v) {
        EXPECT_NEAR(glm::length(sphere.positions[v] - glm::vec3(-1.0f, 0.0f, 0.0f)), 1.0f, 1e-5f);
        EXPECT_NEAR(sphere.positions[n + v].x - sphere.positions[v].x, 2.0f, 1e-5f);
    }
    for (const glm::uvec3& tri : sphere.triangles) {
        const glm::vec3 a = sphere.positions[tri.x], b = sphere.positions[tri.y], c = sphere.positions[tri.z];
        const glm::vec3 outward = (a + b + c) / 3.0f - glm::vec3(-1.0f, 0.0f, 0.0f);
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), outward), 0.0f);  // front faces outside
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

TEST(BuiltinScenes, BezierKeysAreControlPointsOfTheCurveThroughThePoses) {
    // curve=bezier turns the poses at t = k / (keys - 1) into control points: the curve passes
    // through every pose (the linear keys of the same count are those poses), and between them
    // it follows the true motion (64 linear keys) closer than the chords do. For a 120-degree
    // turn the quadratic through three poses strays 0.52 as far as its two chords; clothball
    // turns its vertices by up to 168 degrees (0.68).
    for (const char* name : {"spin", "clothball", "rotating-cube"}) {
        SCOPED_TRACE(name);
        for (int keys : {3, 4}) {
            OptionMap linear, bezier, truth;
            linear.set("keys", std::to_string(keys));
            bezier.set("keys", std::to_string(keys));
            bezier.set("curve", "bezier");
            truth.set("keys", "64");
            const Scene l = makeBuiltinScene(name, linear), b = makeBuiltinScene(name, bezier), t = makeBuiltinScene(name, truth);
            double chordError = 0.0, curveError = 0.0;
            for (std::size_t m = 0; m < b.meshes.size(); ++m) {
                const Mesh &lm = l.meshes[m], &bm = b.meshes[m], &tm = t.meshes[m];
                if (lm.isStatic()) continue;
                for (int k = 0; k < keys; ++k) {
                    const MotionWeights w = bm.weightsAt(keyTime(k, keys)), wl = lm.weightsAt(keyTime(k, keys));
                    for (std::uint32_t v = 0; v < bm.numVertices(); v += 7)
                        EXPECT_LT(glm::distance(bm.positionAt(v, w), lm.positionAt(v, wl)), 1e-4f);
                }
                for (int k = 0; k <= 64; ++k) {
                    const float time = float(k) / 64.0f;
                    const MotionWeights wt = tm.weightsAt(time), wb = bm.weightsAt(time), wl = lm.weightsAt(time);
                    for (std::uint32_t v = 0; v < bm.numVertices(); v += 7) {
                        chordError = std::max(chordError, double(glm::distance(lm.positionAt(v, wl), tm.positionAt(v, wt))));
                        curveError = std::max(curveError, double(glm::distance(bm.positionAt(v, wb), tm.positionAt(v, wt))));
                    }
                }
            }
            EXPECT_LT(curveError, (keys == 3 ? 0.75 : 0.4) * chordError) << "keys " << keys << ": " << curveError << " vs chords " << chordError;
        }
    }
}

TEST(BuiltinScenes, BadCurveOptionsAreOneLineErrors) {
    const auto message = [](const std::string& keys, const std::string& curve) {
        OptionMap o;
        o.set("keys", keys);
        o.set("curve", curve);
        try {
            makeBuiltinScene("spin", o);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("2", "bezier").find("curve=bezier takes keys=3 or 4"), std::string::npos);
    EXPECT_NE(message("9", "bezier").find("Bezier order 2 or 3"), std::string::npos);
    EXPECT_NE(message("3", "spline").find("curve must be linear or bezier"), std::string::npos);
    EXPECT_EQ(message("3", "linear"), "no error");
}

}  // namespace streak
