#include "scene/scene.h"
#include "scene/scene_loader.h"
#include "support/test_scenes.h"
#include "util/error.h"

#include <gtest/gtest.h>

#include <limits>

namespace streak {

TEST(ValidateScene, SkipsAndCountsNonFiniteAndDegenerateTriangles) {
    Scene scene = test::emptyScene();
    const std::uint32_t m = test::addMaterial(scene, glm::vec3(1.0f));
    Mesh mesh;
    mesh.material = m;
    mesh.numKeys = 2;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // Vertices 0-2 fine; 3 is NaN at t = 1 only; 4-6 collinear in both keys; 7-9 collinear at
    // t = 0 only (still a moving triangle with area, so it stays).
    const std::vector<glm::vec3> open{{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {2, 2, -1}, {0, 0, -2}, {1, 1, -2},
                                      {2, 2, -2}, {0, 0, -3}, {1, 0, -3}, {2, 0, -3}};
    std::vector<glm::vec3> close = open;
    close[3].x = nan;
    close[9] = {2, 1, -3};
    mesh.positions = open;
    mesh.positions.insert(mesh.positions.end(), close.begin(), close.end());
    mesh.triangles = {{0, 1, 2}, {0, 1, 3}, {4, 5, 6}, {7, 8, 9}};
    scene.meshes.push_back(mesh);
    const SceneCleanup cleanup = validateScene(scene);
    EXPECT_EQ(cleanup.numNonFinite, 1u);
    EXPECT_EQ(cleanup.numDegenerate, 1u);
    EXPECT_EQ(scene.numTriangles(), 2u);
}

TEST(ValidateScene, RejectsBrokenStructure) {
    Scene scene = test::emptyScene();
    test::addMaterial(scene, glm::vec3(1.0f));
    test::PixelCamera cam{8, 8, 2.0f};
    test::addPixelQuad(scene, cam, 0, 1, 1, 4, 4);
    Scene badIndex = scene;
    badIndex.meshes[0].triangles.push_back({0, 1, 99});
    EXPECT_THROW(validateScene(badIndex), Error);
    Scene badMaterial = scene;
    badMaterial.meshes[0].material = 5;
    EXPECT_THROW(validateScene(badMaterial), Error);
    Scene badKeys = scene;
    badKeys.meshes[0].numKeys = 3;  // 8 positions are not 3 whole keys
    EXPECT_THROW(validateScene(badKeys), Error);
    // Bezier pieces must split the keys into pieces of one degree.
    Scene fiveKeys = scene;
    Mesh& mesh = fiveKeys.meshes[0];
    const std::vector<glm::vec3> pose(mesh.positions.begin(), mesh.positions.begin() + std::ptrdiff_t(mesh.numVertices()));
    mesh.positions.clear();
    for (int k = 0; k < 5; ++k) mesh.positions.insert(mesh.positions.end(), pose.begin(), pose.end());
    mesh.normals.clear();
    mesh.numKeys = 5;
    mesh.interpolation = MotionInterpolation::Bezier;
    for (const int pieces : {1, 2, 4}) {
        mesh.bezierPieces = pieces;
        EXPECT_NO_THROW(validateScene(fiveKeys)) << pieces;
    }
    for (const int pieces : {0, 3, 5}) {
        mesh.bezierPieces = pieces;
        EXPECT_THROW(validateScene(fiveKeys), Error) << pieces;
    }
    EXPECT_NO_THROW(validateScene(scene));
}

TEST(SceneLoader, ParsesBuiltinSpecsAndRejectsBadOnes) {
    EXPECT_EQ(loadScene("builtin:cubes?n=3").numTriangles(), 36u);
    EXPECT_EQ(loadScene("builtin:cubes?n=2&seed=9&keys=4").meshes[0].numKeys, 4);
    EXPECT_THROW(loadScene("builtin:nosuch"), Error);
    EXPECT_THROW(loadScene("builtin:cubes?n=-1"), Error);
    EXPECT_THROW(loadScene("builtin:cubes?n=abc"), Error);
    EXPECT_THROW(loadScene("builtin:cubes?colour=red"), Error);
    EXPECT_THROW(loadScene("builtin:cubes?n"), Error);
    EXPECT_THROW(loadScene("/no/such/file.gltf"), Error);
}

}  // namespace streak
