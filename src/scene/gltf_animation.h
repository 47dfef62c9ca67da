#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

// glTF 2.0 animation, evaluated exactly as the specification says (section 3.11 and Appendix
// C), on plain data the loader has already read and checked. Nothing here knows tinygltf.
namespace streak::gltf {

enum class Interpolation : std::uint8_t { Step, Linear, CubicSpline };
enum class AnimationPath : std::uint8_t { Translation, Rotation, Scale, Weights };

// AnimationSampler is keyframes of one value: times in seconds, strictly increasing, and per
// key numComponents floats (Step, Linear) or in-tangent, value, out-tangent of numComponents
// floats each (CubicSpline). Rotations are quaternions x, y, z, w; weights have one component
// per morph target.
struct AnimationSampler {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;
    std::vector<float> values;
    int numComponents = 0;
};

// The sampler's value at `time` (seconds) into out (numComponents floats). Before the first key
// the first value holds, after the last key the last. Step holds each key's value until the
// next key. Linear rotations take the shorter arc (slerp); CubicSpline uses Hermite splines
// with tangents scaled by the key interval, and normalizes rotations.
// Precondition: times non-empty and increasing, values sized for the interpolation.
void evaluateSampler(const AnimationSampler& sampler, float time, bool isRotation, std::span<float> out);

struct AnimationChannel {
    std::uint32_t sampler = 0;  ///< index into Animation::samplers
    std::uint32_t node = 0;     ///< target node
    AnimationPath path = AnimationPath::Translation;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;
};

// Node is one glTF node at rest: its local transform (a matrix, or translation, rotation,
// scale) and its morph weights (node.weights, else its mesh's weights, else none).
struct Node {
    int parent = -1;  ///< -1 for a root
    bool hasMatrix = false;
    glm::mat4 matrix{1.0f};
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
    std::vector<float> weights;
};

// NodePoses is every node at one time: world transform and morph weights.
struct NodePoses {
    std::vector<glm::mat4> worldFromNode;
    std::vector<std::vector<float>> weights;
};

// Poses all nodes at `time`: the animation's channels (if any) replace the rest values of
// the paths they target, and world = parent's world * translation * rotation * scale.
// Preconditions (the loader checks them): parents form a forest, a channel's node and sampler
// exist, an animated node has no matrix, a weights sampler has one component per node weight.
NodePoses poseNodes(std::span<const Node> nodes, const Animation* animation, float time);

}  // namespace streak::gltf
