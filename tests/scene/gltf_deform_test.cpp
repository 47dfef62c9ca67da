#include "scene/gltf_deform.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <numbers>

namespace streak::gltf {

namespace {

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

}  // namespace

TEST(DeformPrimitive, MorphTargetsAddWeightedDeltasThenTheNodeTransformApplies) {
    PrimitiveGeometry g;
    g.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    g.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    g.positionTargets = {{{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}, {}};  // target 1 moves nothing
    g.normalTargets = {{}, {{1, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
    const std::vector<float> weights{0.5f, 1.0f};
    const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -2));
    std::vector<glm::vec3> p(3), n(3);
    deformPrimitive(g, weights, world, {}, p, n);
    expectNear(p[0], {0, 0, -2});
    expectNear(p[1], {1.5f, 0, -2});  // 1 + 0.5 * 1
    expectNear(p[2], {0, 1, -2});
    expectNear(n[0], glm::normalize(glm::vec3(1, 0, 1)));  // (0,0,1) + 1 * (1,0,0), unit
    expectNear(n[1], {0, 0, 1});
}

TEST(DeformPrimitive, NormalsMoveByTheInverseTranspose) {
    // Non-uniform scale 2 in x: the plane x + y = 1 becomes x/2 + y = 1, whose normal is along
    // (1/2, 1), not the scaled (2, 1). A mirror (negative determinant) keeps normals outward.
    PrimitiveGeometry g;
    g.positions = {{1, 0, 0}};
    g.normals = {glm::normalize(glm::vec3(1, 1, 0))};
    std::vector<glm::vec3> p(1), n(1);
    deformPrimitive(g, {}, glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, 1)), {}, p, n);
    expectNear(n[0], glm::normalize(glm::vec3(0.5f, 1, 0)));
    deformPrimitive(g, {}, glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1)), {}, p, n);
    expectNear(n[0], glm::normalize(glm::vec3(-1, 1, 0)));
}

TEST(DeformPrimitive, SkinningBlendsJointMatricesAndIgnoresTheMeshNode) {
    // Two joints: joint 0 at rest, joint 1 rotated 90 degrees about z around the point
    // (0, 1, 0) (node at (0, 1, 0), inverse bind translating by (0, -1, 0)). The vertex
    // (1, 1, 0) weighted 0.25 / 0.75: joint 0 leaves it at (1, 1, 0); joint 1 takes its
    // offset (1, 0, 0) from the pivot to (0, 1, 0): (0, 2, 0). Blend: (0.25, 1.75, 0).
    NodePoses poses;
    poses.worldFromNode = {glm::mat4(1.0f),
                           glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)), std::numbers::pi_v<float> / 2, glm::vec3(0, 0, 1)),
                           glm::translate(glm::mat4(1.0f), glm::vec3(100, 0, 0))};  // the mesh node: ignored
    Skin skin;
    skin.joints = {0, 1};
    skin.inverseBindMatrices = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0))};
    const std::vector<glm::mat4> joints = jointMatrices(skin, poses);

    PrimitiveGeometry g;
    g.positions = {{1, 1, 0}, {1, 1, 0}, {1, 1, 0}};
    // Weights 0.25/0.75; the same unnormalized (sum 2, renormalized); all zero (takes the mesh node).
    g.joints = {{0, 1, 0, 0}, {0, 1, 0, 0}, {0, 1, 0, 0}};
    g.weights = {{0.25f, 0.75f, 0, 0}, {0.5f, 1.5f, 0, 0}, {0, 0, 0, 0}};
    std::vector<glm::vec3> p(3);
    deformPrimitive(g, {}, poses.worldFromNode[2], joints, p, {});
    expectNear(p[0], {0.25f, 1.75f, 0});
    expectNear(p[1], {0.25f, 1.75f, 0});
    expectNear(p[2], {101, 1, 0});
}

TEST(DeformPrimitive, SecondInfluenceSetAddsToTheFirst) {
    // JOINTS_1/WEIGHTS_1 hold influences 5-8: here half the weight goes to joint 2 (translate +x).
    NodePoses poses;
    poses.worldFromNode = {glm::mat4(1.0f), glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(4, 0, 0))};
    Skin skin;
    skin.joints = {0, 1, 2};
    skin.inverseBindMatrices.assign(3, glm::mat4(1.0f));
    PrimitiveGeometry g;
    g.positions = {{0, 0, 0}};
    g.joints = {{0, 1, 0, 0}, {2, 0, 0, 0}};
    g.weights = {{0.25f, 0.25f, 0, 0}, {0.5f, 0, 0, 0}};
    std::vector<glm::vec3> p(1);
    deformPrimitive(g, {}, glm::mat4(1.0f), jointMatrices(skin, poses), p, {});
    expectNear(p[0], {2, 0, 0});
}

}  // namespace streak::gltf
