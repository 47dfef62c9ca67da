#include "scene/gltf_animation.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace streak::gltf {

namespace {

AnimationSampler sampler(Interpolation interpolation, std::vector<float> times, std::vector<float> values, int numComponents) {
    return {interpolation, std::move(times), std::move(values), numComponents};
}

float evaluate1(const AnimationSampler& s, float time) {
    float out = 0.0f;
    evaluateSampler(s, time, false, {&out, 1});
    return out;
}

glm::quat evaluateRotation(const AnimationSampler& s, float time) {
    float q[4];
    evaluateSampler(s, time, true, q);
    return glm::quat(q[3], q[0], q[1], q[2]);
}

// x, y, z, w of a rotation by `degrees` about +z.
std::vector<float> aboutZ(float degrees) {
    const float half = 0.5f * degrees * std::numbers::pi_v<float> / 180.0f;
    return {0.0f, 0.0f, std::sin(half), std::cos(half)};
}

float angleAboutZ(const glm::quat& q) { return 2.0f * std::atan2(q.z, q.w) * 180.0f / std::numbers::pi_v<float>; }

}  // namespace

TEST(AnimationSampler, StepHoldsEachKeyUntilTheNext) {
    const AnimationSampler s = sampler(Interpolation::Step, {1.0f, 2.0f, 4.0f}, {10.0f, 20.0f, 40.0f}, 1);
    EXPECT_EQ(evaluate1(s, 0.0f), 10.0f);  // before the first key: the first value
    EXPECT_EQ(evaluate1(s, 1.0f), 10.0f);
    EXPECT_EQ(evaluate1(s, 1.99f), 10.0f);
    EXPECT_EQ(evaluate1(s, 2.0f), 20.0f);
    EXPECT_EQ(evaluate1(s, 3.5f), 20.0f);
    EXPECT_EQ(evaluate1(s, 9.0f), 40.0f);  // after the last: the last value
}

TEST(AnimationSampler, LinearInterpolatesWithinTheKeyInterval) {
    const AnimationSampler s = sampler(Interpolation::Linear, {1.0f, 2.0f, 4.0f}, {10.0f, 20.0f, 40.0f, 0, 0, 0, 1, 2, 3}, 3);
    float v[3];
    evaluateSampler(s, 3.0f, false, v);  // halfway from key 1 (0, 0, 0) to key 2 (1, 2, 3)
    EXPECT_FLOAT_EQ(v[0], 0.5f);
    EXPECT_FLOAT_EQ(v[1], 1.0f);
    EXPECT_FLOAT_EQ(v[2], 1.5f);
    evaluateSampler(s, 1.25f, false, v);  // a quarter of the way from key 0 to key 1
    EXPECT_FLOAT_EQ(v[0], 10.0f - 2.5f);
    EXPECT_FLOAT_EQ(v[1], 20.0f - 5.0f);
    EXPECT_FLOAT_EQ(v[2], 40.0f - 10.0f);
}

TEST(AnimationSampler, LinearRotationSlerpsTheShorterArc) {
    // 0 to 90 degrees: a quarter of the way is 22.5 degrees (slerp is uniform in angle, where a
    // normalized lerp would give atan(0.25 sin90 / (0.75 + 0.25 cos90)) = 18.4 degrees).
    AnimationSampler s = sampler(Interpolation::Linear, {0.0f, 1.0f}, aboutZ(0.0f), 4);
    const std::vector<float> end = aboutZ(90.0f);
    s.values.insert(s.values.end(), end.begin(), end.end());
    EXPECT_NEAR(angleAboutZ(evaluateRotation(s, 0.25f)), 22.5f, 1e-4f);
    // The same end rotation written as -q: the shorter arc still turns +22.5 degrees.
    for (int i = 4; i < 8; ++i) s.values[std::size_t(i)] = -s.values[std::size_t(i)];
    const glm::quat q = evaluateRotation(s, 0.25f);
    EXPECT_NEAR(std::abs(angleAboutZ(q.w < 0 ? -q : q)), 22.5f, 1e-4f);
    EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
    // Nearly equal keys take the normalized-lerp branch and stay unit length.
    AnimationSampler close = sampler(Interpolation::Linear, {0.0f, 1.0f}, aboutZ(0.0f), 4);
    const std::vector<float> tiny = aboutZ(0.01f);
    close.values.insert(close.values.end(), tiny.begin(), tiny.end());
    EXPECT_NEAR(angleAboutZ(evaluateRotation(close, 0.5f)), 0.005f, 1e-5f);
}

TEST(AnimationSampler, CubicSplineIsHermiteWithTangentsScaledByTheInterval) {
    // Keys at t = 1 and 3 (td = 2): values 0 and 1, out-tangent of key 0 = 0.5, in-tangent of
    // key 1 = -1 (per second). At u = 1/2: h00 = 1/2, h10 = 1/8, h01 = 1/2, h11 = -1/8, so
    // p = 0 + 1/8 * 2 * 0.5 + 1/2 * 1 - 1/8 * 2 * (-1) = 0.125 + 0.5 + 0.25 = 0.875.
    // Layout per key: in-tangent, value, out-tangent.
    const AnimationSampler s = sampler(Interpolation::CubicSpline, {1.0f, 3.0f}, {9.0f, 0.0f, 0.5f, -1.0f, 1.0f, 9.0f}, 1);
    EXPECT_FLOAT_EQ(evaluate1(s, 2.0f), 0.875f);
    // u = 1/4: h00 = 27/32, h10 = 9/64, h01 = 5/32, h11 = -3/64:
    // p = 9/64 * 2 * 0.5 + 5/32 - 3/64 * 2 * (-1) = 9/64 + 10/64 + 6/64 = 25/64.
    EXPECT_FLOAT_EQ(evaluate1(s, 1.5f), 25.0f / 64.0f);
    EXPECT_FLOAT_EQ(evaluate1(s, 0.0f), 0.0f);  // clamped to the key values, not the tangents
    EXPECT_FLOAT_EQ(evaluate1(s, 5.0f), 1.0f);
}

TEST(AnimationSampler, CubicSplineRotationIsNormalized) {
    // Zero tangents between 0 and 90 degrees: the raw Hermite blend at u = 1/2 is the plain
    // average of the two quaternions (length cos 22.5 < 1); normalized it is 45 degrees.
    AnimationSampler s = sampler(Interpolation::CubicSpline, {0.0f, 2.0f}, {}, 4);
    for (float degrees : {0.0f, 90.0f}) {
        const std::vector<float> q = aboutZ(degrees);
        s.values.insert(s.values.end(), {0, 0, 0, 0});
        s.values.insert(s.values.end(), q.begin(), q.end());
        s.values.insert(s.values.end(), {0, 0, 0, 0});
    }
    const glm::quat q = evaluateRotation(s, 1.0f);
    EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
    EXPECT_NEAR(angleAboutZ(q), 45.0f, 1e-4f);
}

TEST(AnimationSampler, RandomLinearSamplesStayBetweenTheirKeys) {
    // Property: for random increasing times and values, a Linear sample lies between the values
    // of the two keys around it, and equals them at the key times (within float rounding).
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> step(0.01f, 1.0f), value(-10.0f, 10.0f);
    for (int trial = 0; trial < 100; ++trial) {
        AnimationSampler s;
        s.numComponents = 1;
        float t = value(rng);
        for (int k = 0; k < 6; ++k) {
            s.times.push_back(t += step(rng));
            s.values.push_back(value(rng));
        }
        for (std::size_t k = 0; k + 1 < s.times.size(); ++k) {
            EXPECT_FLOAT_EQ(evaluate1(s, s.times[k]), s.values[k]);
            const float mid = evaluate1(s, 0.5f * (s.times[k] + s.times[k + 1]));
            EXPECT_GE(mid, std::min(s.values[k], s.values[k + 1]) - 1e-4f);
            EXPECT_LE(mid, std::max(s.values[k], s.values[k + 1]) + 1e-4f);
        }
    }
}

TEST(PoseNodes, ParentsComposeAndChannelsReplaceRestValues) {
    // Root: translate (1, 0, 0). Child: rotated 90 degrees about z at rest, translation (0, 2, 0),
    // scale 3. Animated: the child's rotation goes 0 -> 170 degrees over [0, 1] (not 180, where
    // the shorter arc is a coin toss).
    std::vector<Node> nodes(2);
    nodes[0].translation = {1, 0, 0};
    nodes[1].parent = 0;
    nodes[1].translation = {0, 2, 0};
    nodes[1].rotation = glm::angleAxis(std::numbers::pi_v<float> / 2, glm::vec3(0, 0, 1));
    nodes[1].scale = glm::vec3(3.0f);
    Animation animation;
    std::vector<float> values = aboutZ(0.0f);
    const std::vector<float> end = aboutZ(170.0f);
    values.insert(values.end(), end.begin(), end.end());
    animation.samplers.push_back(sampler(Interpolation::Linear, {0.0f, 1.0f}, values, 4));
    animation.channels.push_back({0, 1, AnimationPath::Rotation});

    // The child's local (1, 0, 0) lands at root + (0, 2) + 3 (cos a, sin a).
    auto tipAt = [](float degrees) {
        const float a = glm::radians(degrees);
        return glm::vec2(1.0f + 3.0f * std::cos(a), 2.0f + 3.0f * std::sin(a));
    };
    auto tip = [](const NodePoses& poses) { return glm::vec2(poses.worldFromNode[1] * glm::vec4(1, 0, 0, 1)); };
    const glm::vec2 rest = tip(poseNodes(nodes, nullptr, 0.5f)), restExpected = tipAt(90.0f);
    EXPECT_NEAR(rest.x, restExpected.x, 1e-5f);
    EXPECT_NEAR(rest.y, restExpected.y, 1e-5f);
    // Animated: the channel replaces the rest rotation; half way is 85 degrees.
    for (const auto& [time, degrees] : {std::pair{0.5f, 85.0f}, std::pair{1.0f, 170.0f}}) {
        const glm::vec2 moved = tip(poseNodes(nodes, &animation, time)), expected = tipAt(degrees);
        EXPECT_NEAR(moved.x, expected.x, 1e-5f) << time;
        EXPECT_NEAR(moved.y, expected.y, 1e-5f) << time;
    }
}

TEST(PoseNodes, DeepChainsAndMatricesAndWeights) {
    // A chain 5000 deep (posed without recursion), each link translating by 1 in x; the last
    // node is given as a matrix, and a weights channel drives the first node's morph weights.
    const int depth = 5000;
    std::vector<Node> nodes(depth);
    for (int i = 0; i < depth; ++i) {
        nodes[std::size_t(i)].parent = i - 1;
        nodes[std::size_t(i)].translation = {1, 0, 0};
    }
    nodes.back().hasMatrix = true;
    nodes.back().matrix = glm::translate(glm::mat4(1.0f), glm::vec3(0, 7, 0));
    nodes[0].weights = {0.0f, 0.0f};
    Animation animation;
    animation.samplers.push_back(sampler(Interpolation::Linear, {0.0f, 2.0f}, {0.0f, 1.0f, 1.0f, 0.0f}, 2));
    animation.channels.push_back({0, 0, AnimationPath::Weights});
    const NodePoses poses = poseNodes(nodes, &animation, 0.5f);
    const glm::vec3 last(poses.worldFromNode.back()[3]);
    EXPECT_FLOAT_EQ(last.x, float(depth - 1));
    EXPECT_FLOAT_EQ(last.y, 7.0f);
    ASSERT_EQ(poses.weights[0].size(), 2u);
    EXPECT_FLOAT_EQ(poses.weights[0][0], 0.25f);
    EXPECT_FLOAT_EQ(poses.weights[0][1], 0.75f);
}

}  // namespace streak::gltf
