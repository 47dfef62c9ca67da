#include "scene/gltf_animation.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace streak::gltf {

namespace {

// The slerp of glTF Appendix C (the spec's reference implementation), in double: the shorter
// arc, and a normalized lerp where the quaternions are nearly equal (sin -> 0).
void slerp(const float* a, const float* b, double u, float* out) {
    double d = 0.0;
    for (int i = 0; i < 4; ++i) d += double(a[i]) * double(b[i]);
    const double sign = d < 0.0 ? -1.0 : 1.0;
    d *= sign;
    double wa = 1.0 - u, wb = u;
    if (d < 0.9995) {
        const double theta0 = std::acos(d), theta = u * theta0;
        wb = std::sin(theta) / std::sin(theta0);
        wa = std::cos(theta) - d * wb;
    }
    double q[4], length = 0.0;
    for (int i = 0; i < 4; ++i) {
        q[i] = wa * a[i] + wb * sign * b[i];
        length += q[i] * q[i];
    }
    // Exact slerp keeps unit length; the lerp branch and unnormalized keys need the division.
    length = std::sqrt(length);
    for (int i = 0; i < 4; ++i) out[i] = float(length > 0.0 ? q[i] / length : q[i]);
}

void normalizeQuaternion(std::span<float> q) {
    double length = 0.0;
    for (float c : q) length += double(c) * c;
    length = std::sqrt(length);
    if (length > 0.0)
        for (float& c : q) c = float(c / length);
}

glm::mat4 localTransform(const Node& node, const glm::vec3& t, const glm::quat& r, const glm::vec3& s) {
    if (node.hasMatrix) return node.matrix;
    return glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
}

}  // namespace

void evaluateSampler(const AnimationSampler& sampler, float time, bool isRotation, std::span<float> out) {
    const std::size_t n = std::size_t(sampler.numComponents);
    const std::size_t numKeys = sampler.times.size();
    assert(numKeys > 0 && out.size() == n);
    const bool isCubic = sampler.interpolation == Interpolation::CubicSpline;
    // Element e of key k: CubicSpline stores (in-tangent, value, out-tangent) per key.
    auto element = [&](std::size_t k, int e) { return sampler.values.data() + (isCubic ? (3 * k + std::size_t(e)) * n : k * n); };
    auto copyValue = [&](std::size_t k) { std::copy_n(element(k, 1), n, out.begin()); };

    if (!(time > sampler.times.front())) return copyValue(0);
    if (!(time < sampler.times.back())) return copyValue(numKeys - 1);
    // times[k] <= time < times[k + 1]
    const std::size_t k = std::size_t(std::upper_bound(sampler.times.begin(), sampler.times.end(), time) - sampler.times.begin()) - 1;
    const double t0 = sampler.times[k], t1 = sampler.times[k + 1];
    const double td = t1 - t0;
    const double u = (double(time) - t0) / td;

    switch (sampler.interpolation) {
    case Interpolation::Step:
        return copyValue(k);
    case Interpolation::Linear:
        if (isRotation && n == 4) return slerp(element(k, 1), element(k + 1, 1), u, out.data());
        for (std::size_t i = 0; i < n; ++i) out[i] = float((1.0 - u) * element(k, 1)[i] + u * element(k + 1, 1)[i]);
        return;
    case Interpolation::CubicSpline: {
        // Hermite basis (glTF Appendix C): p(u) = h00 v_k + h10 td b_k + h01 v_k+1 + h11 td a_k+1,
        // with b_k the out-tangent of key k and a_k+1 the in-tangent of key k+1.
        const double u2 = u * u, u3 = u2 * u;
        const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
        const float* v0 = element(k, 1);
        const float* b0 = element(k, 2);
        const float* a1 = element(k + 1, 0);
        const float* v1 = element(k + 1, 1);
        for (std::size_t i = 0; i < n; ++i) out[i] = float(h00 * v0[i] + h10 * td * b0[i] + h01 * v1[i] + h11 * td * a1[i]);
        if (isRotation) normalizeQuaternion(out);
        return;
    }
    }
}

NodePoses poseNodes(std::span<const Node> nodes, const Animation* animation, float time) {
    const std::size_t numNodes = nodes.size();
    std::vector<glm::vec3> translation(numNodes), scale(numNodes);
    std::vector<glm::quat> rotation(numNodes);
    NodePoses poses;
    poses.weights.resize(numNodes);
    for (std::size_t i = 0; i < numNodes; ++i) {
        translation[i] = nodes[i].translation;
        rotation[i] = nodes[i].rotation;
        scale[i] = nodes[i].scale;
        poses.weights[i] = nodes[i].weights;
    }
    if (animation) {
        float value[4];
        for (const AnimationChannel& channel : animation->channels) {
            const AnimationSampler& sampler = animation->samplers[channel.sampler];
            const std::uint32_t node = channel.node;
            switch (channel.path) {
            case AnimationPath::Translation:
                evaluateSampler(sampler, time, false, {value, 3});
                translation[node] = glm::vec3(value[0], value[1], value[2]);
                break;
            case AnimationPath::Rotation:
                evaluateSampler(sampler, time, true, {value, 4});
                rotation[node] = glm::quat(value[3], value[0], value[1], value[2]);  // glTF stores x, y, z, w
                break;
            case AnimationPath::Scale:
                evaluateSampler(sampler, time, false, {value, 3});
                scale[node] = glm::vec3(value[0], value[1], value[2]);
                break;
            case AnimationPath::Weights:
                evaluateSampler(sampler, time, false, poses.weights[node]);
                break;
            }
        }
    }

    // Parents before children without recursion (hierarchies may be deep): walk up to the first
    // posed ancestor, then pose the chain downwards.
    poses.worldFromNode.resize(numNodes);
    std::vector<bool> isPosed(numNodes, false);
    std::vector<std::size_t> chain;
    for (std::size_t start = 0; start < numNodes; ++start) {
        chain.clear();
        for (int i = int(start); i >= 0 && !isPosed[std::size_t(i)]; i = nodes[std::size_t(i)].parent) chain.push_back(std::size_t(i));
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const std::size_t i = *it;
            const glm::mat4 local = localTransform(nodes[i], translation[i], rotation[i], scale[i]);
            const int parent = nodes[i].parent;
            poses.worldFromNode[i] = parent >= 0 ? poses.worldFromNode[std::size_t(parent)] * local : local;
            isPosed[i] = true;
        }
    }
    return poses;
}

}  // namespace streak::gltf
