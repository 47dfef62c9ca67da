#include "scene/gltf_loader.h"

#include "scene/gltf_accessor.h"
#include "scene/gltf_animation.h"
#include "scene/gltf_deform.h"
#include "scene/gltf_document.h"
#include "scene/point_cache.h"
#include "util/error.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>

namespace streak {

namespace {

using gltf::AccessorReader;

constexpr int kMaxMotionKeys = 256;

template <class Integer>
std::string str(Integer i) { return std::to_string(i); }

// Finite also as float: JSON numbers beyond float range would become infinities.
bool isFinite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(float(v)); });
}

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The vertex data of one glTF primitive, read and checked once, however many nodes instance it.
struct PrimitiveData {
    gltf::PrimitiveGeometry geometry;
    std::vector<glm::uvec3> triangles;
    std::vector<glm::vec2> uvs;     ///< the base-colour texture's set, transformed; or empty
    std::vector<glm::vec4> colors;  ///< COLOR_0, or empty
    std::uint32_t material = 0;     ///< streak material
    std::uint32_t numJointsUsed = 0;  ///< 1 + the largest joint index with a nonzero weight; 0 if none
    std::vector<glm::vec3> velocities;  ///< _VELOCITY, in the mesh's space; or empty
};

// One (node, primitive) of the scene: it becomes one streak Mesh.
struct Instance {
    std::uint32_t node = 0;
    int skin = -1;
    PrimitiveData* data = nullptr;  ///< shared by the instances of one primitive (makeMeshes may take its arrays)
    std::string name;
    std::optional<std::size_t> cacheFirst;  ///< moved by the point cache: its first point there
};

// A streak material made from a glTF one, and how its base-colour texture reads uvs.
struct MaterialInfo {
    std::uint32_t index = 0;
    int texCoord = -1;             ///< the TEXCOORD_n set the texture reads; -1: untextured
    glm::mat3 uvTransform{1.0f};   ///< KHR_texture_transform, as a 2D affine matrix
};

WrapMode wrapMode(int glMode, const std::string& what) {
    switch (glMode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return WrapMode::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return WrapMode::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return WrapMode::MirroredRepeat;
    default: throw Error(what + ": unknown wrap mode " + str(glMode));
    }
}

// KHR_texture_transform on a textureInfo: uv' = offset + rotation * (scale * uv), with the
// extension's rotation convention (u' = cos u + sin v, v' = -sin u + cos v for unit scale).
glm::mat3 textureTransform(const tinygltf::ExtensionMap& extensions, int& texCoord, const std::string& what) {
    const auto it = extensions.find("KHR_texture_transform");
    if (it == extensions.end() || !it->second.IsObject()) return glm::mat3(1.0f);
    const tinygltf::Value& ext = it->second;
    auto number = [&](const tinygltf::Value& v) {
        if (!v.IsNumber()) throw Error(what + ": KHR_texture_transform has a non-number");
        const double d = v.GetNumberAsDouble();
        if (!std::isfinite(d)) throw Error(what + ": KHR_texture_transform has a non-finite number");
        return float(d);
    };
    auto pair = [&](const char* key, glm::vec2 fallback) {
        if (!ext.Has(key)) return fallback;
        const tinygltf::Value& v = ext.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2) throw Error(what + ": KHR_texture_transform " + key + " is not two numbers");
        return glm::vec2(number(v.Get(0)), number(v.Get(1)));
    };
    const glm::vec2 offset = pair("offset", glm::vec2(0.0f)), scale = pair("scale", glm::vec2(1.0f));
    const float rotation = ext.Has("rotation") ? number(ext.Get("rotation")) : 0.0f;
    if (ext.Has("texCoord")) {
        const tinygltf::Value& v = ext.Get("texCoord");
        if (!v.IsInt() || v.GetNumberAsInt() < 0) throw Error(what + ": KHR_texture_transform texCoord is not a set index");
        texCoord = v.GetNumberAsInt();
    }
    const float c = std::cos(rotation), s = std::sin(rotation);
    // Columns: u axis, v axis, offset.
    return glm::mat3(glm::vec3(c * scale.x, -s * scale.x, 0.0f), glm::vec3(s * scale.y, c * scale.y, 0.0f), glm::vec3(offset, 1.0f));
}

// A camera pose from a node's world matrix: its position and orthonormalized axes (a camera
// looks down its local -z with +y up, in glTF as in streak). Scale is dropped.
CameraPose poseFromMatrix(const glm::mat4& m, const std::string& what) {
    const glm::vec3 y(m[1]), z(m[2]);
    const glm::vec3 x = glm::cross(y, z);
    if (!(glm::length(x) > 0.0f) || !(glm::length(z) > 0.0f) || !isFinite(glm::vec3(m[3])))
        throw Error(what + ": its node's transform is degenerate");
    const glm::vec3 zAxis = glm::normalize(z), xAxis = glm::normalize(glm::cross(y, zAxis)), yAxis = glm::cross(zAxis, xAxis);
    CameraPose pose;
    pose.position = glm::vec3(m[3]);
    pose.worldFromCamera = glm::normalize(glm::quat_cast(glm::mat3(xAxis, yAxis, zAxis)));
    return pose;
}

class SceneBuilder {
public:
    SceneBuilder(const gltf::Document& document, const GltfOptions& options, RenderStats* stats)
        : m_document(document),
          m_model(document.model),
          m_options(options),
          m_stats(stats),
          m_reader(document.model, std::min(options.limits.maxVertexWork, std::size_t(1) << 31)),
          m_documentLimits{options.allowExternalFiles, options.limits.maxFileBytes, options.limits.maxTexels} {}

    Scene build() {
        checkOptions();
        readNodes();
        chooseSceneNodes();
        readAnimation();
        collectInstances();
        readPointCache();
        sampleKeys();
        placeCamera();
        curveKeys();
        if (m_stats) {
            m_stats->setCounter("gltf_instanced_primitives", double(m_instances.size()));
            m_stats->setCounter("gltf_skipped_primitives", double(m_numSkipped));
        }
        return std::move(m_scene);
    }

private:
    void checkOptions() {
        const GltfOptions& o = m_options;
        if (!std::isfinite(o.frame)) throw Error("--frame must be a finite number");
        if (!(o.shutter >= 0.0) || !std::isfinite(o.shutter)) throw Error("--shutter must be 0 or more frames");
        if (!(o.fps > 0.0) || !std::isfinite(o.fps)) throw Error("--fps must be positive");
        if (o.motionKeys != 0 && (o.motionKeys < 2 || o.motionKeys > kMaxMotionKeys))
            throw Error("--motion-keys must be in [2, " + str(kMaxMotionKeys) + "], got " + str(o.motionKeys));
        const bool isBezier = o.motionCurve == MotionInterpolation::Bezier;
        if (isBezier && o.motionKeys != 0 && o.motionKeys != 3 && o.motionKeys != 4)
            throw Error("--motion-curve bezier takes --motion-keys 3 or 4 (one curve of order 2 or 3), or none (pieces chosen), got " +
                        str(o.motionKeys));
        if (isBezier && o.motionKeys == 0 && o.bezierOrder != 2 && o.bezierOrder != 3)
            throw Error("--motion-curve-order must be 2 or 3, got " + str(o.bezierOrder));
        if (o.motionFitSamples > 0 && (!isBezier || o.motionKeys == 0 || o.motionFitSamples <= o.motionKeys ||
                                       o.motionFitSamples > kMaxMotionKeys))
            throw Error("--motion-fit-samples takes --motion-curve bezier with --motion-keys and more samples than keys, at most " +
                        str(kMaxMotionKeys) + ", got " + str(o.motionFitSamples));
        if (!(o.keyTolerancePixels > 0.0) || !std::isfinite(o.keyTolerancePixels)) throw Error("--key-tolerance must be a positive number of pixels");
        if (o.imageHeight < 1) throw Error("the image height must be positive");
        if (!(o.aspect > 0.0f) || !std::isfinite(o.aspect)) throw Error("the image aspect ratio must be positive");
        if (o.camera && o.lookAt) throw Error("a glTF camera and an explicit camera cannot both be given");
        // Chosen keys start from one piece: two keys, or one Bezier piece's.
        m_pieceOrder = isBezier && o.motionKeys == 0 ? o.bezierOrder : 1;
        m_numKeys = o.motionKeys == 0 ? m_pieceOrder + 1 : o.motionKeys;
        m_fitSamples = !isBezier || o.motionKeys == 0 ? 0 : o.motionFitSamples < 0 ? 4 * (o.motionKeys - 1) + 1 : o.motionFitSamples;
        if (m_fitSamples != 0) m_numKeys = m_fitSamples;  // fitted down to motionKeys in curveKeys
    }

    // Seconds of animation time of key k of numKeys, evenly over the shutter.
    float keyTime(int k, int numKeys) const {
        const double t0 = m_options.frame / m_options.fps, t1 = (m_options.frame + m_options.shutter) / m_options.fps;
        return float(t0 + (t1 - t0) * double(k) / double(numKeys - 1));
    }

    // Nodes with their parents, checking that the hierarchy is a forest and transforms are finite.
    void readNodes() {
        const std::size_t n = m_model.nodes.size();
        m_nodes.resize(n);
        std::size_t numWeights = 0;  // over all nodes: each key pose copies them
        for (std::size_t i = 0; i < n; ++i) {
            const tinygltf::Node& src = m_model.nodes[i];
            const std::string what = "node " + str(i);
            gltf::Node& node = m_nodes[i];
            for (const int child : src.children) {
                if (child < 0 || std::size_t(child) >= n) throw Error(what + ": child " + str(child) + " does not exist");
                if (m_nodes[std::size_t(child)].parent >= 0 || std::size_t(child) == i)
                    throw Error("node " + str(child) + " has more than one parent");
                m_nodes[std::size_t(child)].parent = int(i);
            }
            if (!isFinite(src.matrix) || !isFinite(src.translation) || !isFinite(src.rotation) || !isFinite(src.scale))
                throw Error(what + ": transform has a non-finite number");
            if (!src.matrix.empty()) {
                if (src.matrix.size() != 16) throw Error(what + ": matrix does not have 16 numbers");
                node.hasMatrix = true;
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r) node.matrix[c][r] = float(src.matrix[std::size_t(c * 4 + r)]);
            }
            if (!src.translation.empty()) {
                if (src.translation.size() != 3) throw Error(what + ": translation does not have 3 numbers");
                node.translation = glm::vec3(float(src.translation[0]), float(src.translation[1]), float(src.translation[2]));
            }
            if (!src.rotation.empty()) {
                if (src.rotation.size() != 4) throw Error(what + ": rotation does not have 4 numbers");
                const glm::quat q(float(src.rotation[3]), float(src.rotation[0]), float(src.rotation[1]), float(src.rotation[2]));
                if (!(glm::length(q) > 0.0f)) throw Error(what + ": rotation is not a unit quaternion");
                node.rotation = glm::normalize(q);
            }
            if (!src.scale.empty()) {
                if (src.scale.size() != 3) throw Error(what + ": scale does not have 3 numbers");
                node.scale = glm::vec3(float(src.scale[0]), float(src.scale[1]), float(src.scale[2]));
            }
            if (src.mesh >= 0) {
                const int numTargets = this->numTargets(src.mesh);
                numWeights += std::size_t(numTargets);
                if (numWeights > m_options.limits.maxVertexWork / std::size_t(m_numKeys))
                    throw Error("the nodes' morph weights times motion keys exceed the limit of " + str(m_options.limits.maxVertexWork));
                const std::vector<double>& weights = !src.weights.empty() ? src.weights : m_model.meshes[std::size_t(src.mesh)].weights;
                if (!weights.empty() && weights.size() != std::size_t(numTargets))
                    throw Error(what + ": has " + str(weights.size()) + " morph weights for " + str(numTargets) + " targets");
                if (!isFinite(weights)) throw Error(what + ": morph weights have a non-finite number");
                node.weights.assign(std::size_t(numTargets), 0.0f);
                for (std::size_t w = 0; w < weights.size(); ++w) node.weights[w] = float(weights[w]);
            }
        }
        // Each node has at most one parent, so a cycle is a walk upwards that meets itself. A
        // walk stops at a node an earlier walk visited: all above it is known to be acyclic.
        std::vector<std::size_t> walk(n, 0);
        for (std::size_t start = 0; start < n; ++start) {
            for (int i = int(start); i >= 0; i = m_nodes[std::size_t(i)].parent) {
                if (walk[std::size_t(i)] == start + 1) throw Error("node hierarchy has a cycle through node " + str(i));
                if (walk[std::size_t(i)] != 0) break;
                walk[std::size_t(i)] = start + 1;
            }
        }
    }

    // Morph targets of a mesh: every primitive must have the same number.
    int numTargets(int mesh) {
        if (mesh < 0 || std::size_t(mesh) >= m_model.meshes.size()) throw Error("mesh " + str(mesh) + " does not exist");
        const auto& primitives = m_model.meshes[std::size_t(mesh)].primitives;
        const std::size_t count = primitives.empty() ? 0 : primitives[0].targets.size();
        for (const tinygltf::Primitive& p : primitives)
            if (p.targets.size() != count) throw Error("mesh " + str(mesh) + ": primitives have different numbers of morph targets");
        return int(count);
    }

    // The nodes of the default scene (scene 0 if none is named, every root if there are no scenes).
    void chooseSceneNodes() {
        std::vector<int> roots;
        if (m_model.scenes.empty()) {
            for (std::size_t i = 0; i < m_nodes.size(); ++i)
                if (m_nodes[i].parent < 0) roots.push_back(int(i));
        } else {
            const int scene = m_model.defaultScene >= 0 ? m_model.defaultScene : 0;
            if (std::size_t(scene) >= m_model.scenes.size()) throw Error("scene " + str(scene) + " does not exist");
            roots = m_model.scenes[std::size_t(scene)].nodes;
        }
        m_isInScene.assign(m_nodes.size(), false);
        std::vector<int> stack;
        for (const int root : roots) {
            if (root < 0 || std::size_t(root) >= m_nodes.size()) throw Error("scene node " + str(root) + " does not exist");
            if (m_nodes[std::size_t(root)].parent >= 0) throw Error("scene node " + str(root) + " is not a root node");
            if (m_isInScene[std::size_t(root)]) throw Error("scene lists node " + str(root) + " twice");
            stack.push_back(root);
            while (!stack.empty()) {
                const int i = stack.back();
                stack.pop_back();
                m_isInScene[std::size_t(i)] = true;
                for (const int child : m_model.nodes[std::size_t(i)].children) stack.push_back(child);
            }
        }
    }

    int chooseAnimation() const {
        const auto& animations = m_model.animations;
        const std::string& wanted = m_options.animation;
        if (wanted.empty()) return animations.empty() ? -1 : 0;
        for (std::size_t i = 0; i < animations.size(); ++i)
            if (animations[i].name == wanted) return int(i);
        if (std::all_of(wanted.begin(), wanted.end(), [](char c) { return c >= '0' && c <= '9'; }) && wanted.size() < 9) {
            const int index = std::stoi(wanted);
            if (std::size_t(index) < animations.size()) return index;
        }
        std::string known;
        for (std::size_t i = 0; i < animations.size(); ++i)
            known += (i ? ", " : "") + str(i) + (animations[i].name.empty() ? "" : " '" + animations[i].name + "'");
        throw Error("no animation '" + wanted + "' (" + (known.empty() ? "the file has none" : "it has " + known) + ")");
    }

    void readAnimation() {
        const int index = chooseAnimation();
        if (index < 0) return;
        const tinygltf::Animation& src = m_model.animations[std::size_t(index)];
        gltf::Animation animation;
        animation.name = src.name;
        // A sampler is read once per number of components its channels need.
        std::map<std::pair<int, int>, std::uint32_t> samplerIndex;
        for (std::size_t c = 0; c < src.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = src.channels[c];
            const std::string what = "animation " + str(index) + " channel " + str(c);
            if (channel.target_node < 0) continue;  // targets something other than a node (an extension)
            if (std::size_t(channel.target_node) >= m_nodes.size()) throw Error(what + ": node " + str(channel.target_node) + " does not exist");
            const gltf::Node& node = m_nodes[std::size_t(channel.target_node)];
            gltf::AnimationChannel out;
            out.node = std::uint32_t(channel.target_node);
            int numComponents = 3;
            if (channel.target_path == "translation") out.path = gltf::AnimationPath::Translation;
            else if (channel.target_path == "rotation") out.path = gltf::AnimationPath::Rotation, numComponents = 4;
            else if (channel.target_path == "scale") out.path = gltf::AnimationPath::Scale;
            else if (channel.target_path == "weights") out.path = gltf::AnimationPath::Weights, numComponents = int(node.weights.size());
            else continue;  // e.g. "pointer" (KHR_animation_pointer): not ours
            if (node.hasMatrix && out.path != gltf::AnimationPath::Weights) throw Error(what + ": animates node " + str(out.node) + ", which has a matrix");
            if (numComponents == 0) throw Error(what + ": animates the weights of node " + str(out.node) + ", which has no morph targets");
            const auto key = std::make_pair(channel.sampler, numComponents);
            if (!samplerIndex.count(key)) {
                samplerIndex[key] = std::uint32_t(animation.samplers.size());
                animation.samplers.push_back(readSampler(src, channel.sampler, numComponents, "animation " + str(index) + " sampler " + str(channel.sampler),
                                                         out.path == gltf::AnimationPath::Translation || out.path == gltf::AnimationPath::Scale));
            }
            out.sampler = samplerIndex[key];
            animation.channels.push_back(out);
        }
        m_animation = std::move(animation);
    }

    gltf::AnimationSampler readSampler(const tinygltf::Animation& animation, int index, int numComponents, const std::string& what, bool isFloatOnly) {
        if (index < 0 || std::size_t(index) >= animation.samplers.size()) throw Error(what + ": does not exist");
        const tinygltf::AnimationSampler& src = animation.samplers[std::size_t(index)];
        gltf::AnimationSampler sampler;
        if (src.interpolation.empty() || src.interpolation == "LINEAR") sampler.interpolation = gltf::Interpolation::Linear;
        else if (src.interpolation == "STEP") sampler.interpolation = gltf::Interpolation::Step;
        else if (src.interpolation == "CUBICSPLINE") sampler.interpolation = gltf::Interpolation::CubicSpline;
        else throw Error(what + ": unknown interpolation '" + src.interpolation + "'");
        sampler.times = m_reader.readFloats(src.input, 1, gltf::kFloat, what + " input");
        for (std::size_t k = 0; k < sampler.times.size(); ++k)
            if (!std::isfinite(sampler.times[k]) || (k > 0 && sampler.times[k] < sampler.times[k - 1]))
                throw Error(what + ": key times are not finite and increasing");
        const int outputComponents = m_reader.numComponents(src.output, what + " output");
        sampler.values = m_reader.readFloats(src.output, outputComponents, isFloatOnly ? gltf::kFloat : gltf::kFloatOrNormalized, what + " output");
        sampler.numComponents = numComponents;
        const std::size_t perKey = std::size_t(numComponents) * (sampler.interpolation == gltf::Interpolation::CubicSpline ? 3 : 1);
        if (sampler.values.size() != sampler.times.size() * perKey)
            throw Error(what + ": has " + str(sampler.values.size()) + " output values for " + str(sampler.times.size()) + " keys of " +
                        str(perKey) + " values");
        return sampler;
    }

    // Every (node, primitive) of the scene, with the totals checked against the limits before
    // any vertex is read.
    void collectInstances() {
        std::size_t numTriangles = 0, vertexWork = 0;
        const std::size_t numKeys = std::size_t(m_numKeys);
        for (std::size_t i = 0; i < m_nodes.size(); ++i) {
            const tinygltf::Node& node = m_model.nodes[i];
            if (!m_isInScene[i] || node.mesh < 0) continue;
            const tinygltf::Mesh& mesh = m_model.meshes[std::size_t(node.mesh)];  // checked by readNodes
            if (node.skin >= 0 && std::size_t(node.skin) >= m_model.skins.size()) throw Error("node " + str(i) + ": skin " + str(node.skin) + " does not exist");
            for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
                const tinygltf::Primitive& primitive = mesh.primitives[p];
                const std::string what = "mesh " + str(node.mesh) + " primitive " + str(p);
                const auto position = primitive.attributes.find("POSITION");
                if (primitive.mode < TINYGLTF_MODE_TRIANGLES || primitive.mode > TINYGLTF_MODE_TRIANGLE_FAN || position == primitive.attributes.end()) {
                    ++m_numSkipped;  // points, lines, or no positions: nothing to fill
                    continue;
                }
                const std::size_t numVertices = m_reader.count(position->second, what + " POSITION");
                const std::size_t numIndices = primitive.indices >= 0 ? m_reader.count(primitive.indices, what + " indices") : numVertices;
                numTriangles += primitive.mode == TINYGLTF_MODE_TRIANGLES ? numIndices / 3 : (numIndices >= 2 ? numIndices - 2 : 0);
                std::size_t numSets = 0;
                while (primitive.attributes.count("JOINTS_" + str(numSets))) ++numSets;
                const std::size_t factor = numKeys * (1 + primitive.targets.size() + numSets);
                if (numVertices > m_options.limits.maxVertexWork / factor || vertexWork + numVertices * factor > m_options.limits.maxVertexWork)
                    throw Error("the scene's vertices times motion keys exceed the limit of " + str(m_options.limits.maxVertexWork));
                vertexWork += numVertices * factor;
                m_vertexWorkPerKey += numVertices * (factor / numKeys);
                if (numTriangles > m_options.limits.maxTriangles)
                    throw Error("the scene has more than " + str(m_options.limits.maxTriangles) + " triangles");
                Instance instance;
                instance.node = std::uint32_t(i);
                instance.skin = node.skin;
                instance.name = !node.name.empty() ? node.name : !mesh.name.empty() ? mesh.name : "node " + str(i);
                instance.data = &primitiveData(node.mesh, int(p));
                if (node.skin >= 0 && instance.data->geometry.isSkinned()) {
                    const gltf::Skin& skin = this->skin(node.skin);
                    if (instance.data->numJointsUsed > skin.joints.size())
                        throw Error(what + ": joint index " + str(instance.data->numJointsUsed - 1) + " is out of range for skin " + str(node.skin) +
                                    " (" + str(skin.joints.size()) + " joints)");
                }
                m_instances.push_back(std::move(instance));
            }
        }
    }

    // --point-cache: the mesh it moves (options.pointCache->mesh, a node's or a mesh's name; or
    // the one mesh the scene instances), whose triangle primitives take its points in order.
    void readPointCache() {
        if (!m_options.pointCache) return;
        const GltfPointCache& options = *m_options.pointCache;
        m_pointCache.emplace(PointCache::read(options.path, m_options.fps, m_options.limits.maxFileBytes));
        std::set<std::uint32_t> nodes;
        for (const Instance& instance : m_instances) nodes.insert(instance.node);
        auto isTarget = [&](std::uint32_t node) {
            if (options.mesh.empty()) return nodes.size() == 1;
            const tinygltf::Node& n = m_model.nodes[node];
            return n.name == options.mesh || m_model.meshes[std::size_t(n.mesh)].name == options.mesh;
        };
        // Each node moved by it (several where they instance one named mesh) takes the points from
        // the first, its primitives in order.
        std::map<std::uint32_t, std::size_t> points;  // by node: the points its primitives take
        for (Instance& instance : m_instances) {
            if (!isTarget(instance.node)) continue;
            std::size_t& first = points[instance.node];
            instance.cacheFirst = first;
            first += instance.data->geometry.numVertices();
        }
        if (options.mesh.empty() && nodes.size() != 1)
            throw Error("--point-cache: the scene has " + str(nodes.size()) + " meshes; name the one it moves with --point-cache-mesh");
        if (points.empty()) throw Error("--point-cache-mesh '" + options.mesh + "': no node or mesh of the scene has that name");
        for (const auto& [node, count] : points)
            if (count != m_pointCache->numPoints())
                throw Error(options.path + ": the cache has " + str(m_pointCache->numPoints()) + " points, the mesh it moves " + str(count) + " vertices");
        if (m_stats) {
            m_stats->setCounter("point_cache_points", double(m_pointCache->numPoints()));
            m_stats->setCounter("point_cache_samples", double(m_pointCache->numSamples()));
            m_stats->setCounter("point_cache_nodes", double(points.size()));
        }
    }

    // Whether the node's transform mirrors the instance's vertices (negative determinant): glTF
    // 3.7.4 then turns the winding clockwise, and makeMeshes flips it back. A skinned mesh's
    // joints place it instead, unless a point cache in the node's space does; a cache in world
    // space holds what the animation made, so it follows the animation's rule.
    bool isMirrored(const Instance& instance, const glm::mat4& worldFromNode) const {
        const bool isPlacedByNode = (instance.cacheFirst && !m_options.pointCache->isWorldSpace) ||
                                    !(instance.skin >= 0 && instance.data->geometry.isSkinned());
        return isPlacedByNode && glm::determinant(glm::mat3(worldFromNode)) < 0.0f;
    }

    // The instance's vertices from the point cache at `time` (world space, or through the node's
    // world transform), and normals of its triangles as they are drawn (counter-clockwise in
    // front, after makeMeshes' flip), area-weighted, where it has normals.
    void cachedPose(const Instance& instance, float time, const glm::mat4& worldFromNode, std::vector<glm::vec3>& positions,
                    std::vector<glm::vec3>& normals) const {
        const std::size_t n = instance.data->geometry.numVertices();
        positions.resize(n);
        m_pointCache->pointsAt(double(time), *instance.cacheFirst, n, positions);
        if (!m_options.pointCache->isWorldSpace)
            for (glm::vec3& p : positions) p = glm::vec3(worldFromNode * glm::vec4(p, 1.0f));
        if (instance.data->geometry.normals.empty()) return;
        normals.assign(n, glm::vec3(0.0f));
        const float facing = isMirrored(instance, worldFromNode) ? -1.0f : 1.0f;
        for (const glm::uvec3& t : instance.data->triangles) {
            const glm::vec3 area = facing * glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x]);
            normals[t.x] += area, normals[t.y] += area, normals[t.z] += area;
        }
        for (glm::vec3& v : normals) {
            const float length = glm::length(v);
            v = length > 0.0f ? v / length : glm::vec3(0.0f, 0.0f, 1.0f);
        }
    }

    const gltf::Skin& skin(int index) {
        if (auto it = m_skins.find(index); it != m_skins.end()) return it->second;
        const tinygltf::Skin& src = m_model.skins[std::size_t(index)];
        const std::string what = "skin " + str(index);
        gltf::Skin skin;
        if (src.joints.empty()) throw Error(what + ": has no joints");
        for (const int joint : src.joints) {
            if (joint < 0 || std::size_t(joint) >= m_nodes.size()) throw Error(what + ": joint node " + str(joint) + " does not exist");
            skin.joints.push_back(std::uint32_t(joint));
        }
        skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
        if (src.inverseBindMatrices >= 0) {
            const std::vector<float> m = m_reader.readFloats(src.inverseBindMatrices, 16, gltf::kFloat, what + " inverseBindMatrices");
            if (m.size() < 16 * skin.joints.size()) throw Error(what + ": fewer inverse bind matrices than joints");
            for (std::size_t j = 0; j < skin.joints.size(); ++j)
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r) skin.inverseBindMatrices[j][c][r] = m[16 * j + std::size_t(c * 4 + r)];
        }
        return m_skins[index] = std::move(skin);
    }

    template <class Vec, int N>
    std::vector<Vec> readVectors(int accessor, std::uint32_t allowed, std::size_t expectedCount, const std::string& what) {
        const std::vector<float> values = m_reader.readFloats(accessor, N, allowed, what);
        if (values.size() != expectedCount * N)
            throw Error(what + ": has " + str(values.size() / N) + " elements for " + str(expectedCount) + " vertices");
        std::vector<Vec> out(expectedCount);
        for (std::size_t i = 0; i < expectedCount; ++i)
            for (int c = 0; c < N; ++c) out[i][c] = values[i * N + std::size_t(c)];
        return out;
    }

    PrimitiveData& primitiveData(int meshIndex, int primitiveIndex) {
        const auto key = std::make_pair(meshIndex, primitiveIndex);
        if (auto it = m_primitives.find(key); it != m_primitives.end()) return it->second;
        const tinygltf::Primitive& primitive = m_model.meshes[std::size_t(meshIndex)].primitives[std::size_t(primitiveIndex)];
        const std::string what = "mesh " + str(meshIndex) + " primitive " + str(primitiveIndex);
        auto attribute = [&](const std::string& name) {
            const auto it = primitive.attributes.find(name);
            return it == primitive.attributes.end() ? -1 : it->second;
        };
        PrimitiveData data;
        gltf::PrimitiveGeometry& g = data.geometry;
        g.positions = readVectors<glm::vec3, 3>(attribute("POSITION"), gltf::kFloat, m_reader.count(attribute("POSITION"), what), what + " POSITION");
        const std::size_t n = g.positions.size();
        if (attribute("NORMAL") >= 0) g.normals = readVectors<glm::vec3, 3>(attribute("NORMAL"), gltf::kFloat, n, what + " NORMAL");
        for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
            const auto& target = primitive.targets[t];
            const std::string where = what + " target " + str(t);
            auto position = target.find("POSITION"), normal = target.find("NORMAL");
            g.positionTargets.push_back(position == target.end() ? std::vector<glm::vec3>{}
                                                                 : readVectors<glm::vec3, 3>(position->second, gltf::kFloatOrNormalized, n, where + " POSITION"));
            g.normalTargets.push_back(normal == target.end() || g.normals.empty()
                                          ? std::vector<glm::vec3>{}
                                          : readVectors<glm::vec3, 3>(normal->second, gltf::kFloatOrNormalized, n, where + " NORMAL"));
        }
        for (std::size_t set = 0; attribute("JOINTS_" + str(set)) >= 0; ++set) {
            const std::string joints = "JOINTS_" + str(set), weights = "WEIGHTS_" + str(set);
            if (attribute(weights) < 0) throw Error(what + ": has " + joints + " but no " + weights);
            const std::vector<std::uint32_t> j = m_reader.readUints(attribute(joints), 4, gltf::kUnsignedInts, what + " " + joints);
            if (j.size() != 4 * n) throw Error(what + " " + joints + ": does not have one element per vertex");
            const std::vector<glm::vec4> w = readVectors<glm::vec4, 4>(attribute(weights), gltf::kFloatOrNormalized, n, what + " " + weights);
            for (std::size_t v = 0; v < n; ++v) {
                g.joints.emplace_back(j[4 * v], j[4 * v + 1], j[4 * v + 2], j[4 * v + 3]);
                for (int c = 0; c < 4; ++c)
                    if (w[v][c] != 0.0f) data.numJointsUsed = std::max(data.numJointsUsed, j[4 * v + std::size_t(c)] + 1);
            }
            g.weights.insert(g.weights.end(), w.begin(), w.end());
        }
        if (const int velocity = attribute("_VELOCITY"); velocity >= 0)
            data.velocities = readVectors<glm::vec3, 3>(velocity, gltf::kFloat, n, what + " _VELOCITY");
        if (const int color = attribute("COLOR_0"); color >= 0) {
            const int numComponents = m_reader.numComponents(color, what + " COLOR_0");
            const std::uint32_t allowed = gltf::kFloat | gltf::kUnsignedByte | gltf::kUnsignedShort;
            if (numComponents == 3) {
                for (const glm::vec3& c : readVectors<glm::vec3, 3>(color, allowed, n, what + " COLOR_0")) data.colors.emplace_back(c, 1.0f);
            } else {
                data.colors = readVectors<glm::vec4, 4>(color, allowed, n, what + " COLOR_0");
            }
            for (glm::vec4& c : data.colors) c = glm::clamp(c, glm::vec4(0.0f), glm::vec4(1.0f));  // also maps NaN to 0
        }

        const MaterialInfo& material = this->material(primitive.material);
        data.material = material.index;
        if (material.texCoord >= 0) {
            const int uvs = attribute("TEXCOORD_" + str(material.texCoord));
            if (uvs < 0) throw Error(what + ": its material's texture reads TEXCOORD_" + str(material.texCoord) + ", which it does not have");
            for (const glm::vec2& uv : readVectors<glm::vec2, 2>(uvs, gltf::kFloatOrNormalized, n, what + " TEXCOORD_" + str(material.texCoord))) {
                const glm::vec2 transformed(material.uvTransform * glm::vec3(uv, 1.0f));
                data.uvs.push_back(std::isfinite(transformed.x) && std::isfinite(transformed.y) ? transformed : glm::vec2(0.0f));
            }
        }

        std::vector<std::uint32_t> indices;
        if (primitive.indices >= 0) {
            indices = m_reader.readUints(primitive.indices, 1, gltf::kUnsignedInts, what + " indices");
            for (const std::uint32_t i : indices)
                if (i >= n) throw Error(what + ": index " + str(std::size_t(i)) + " is out of range (" + str(n) + " vertices)");
        } else {
            indices.resize(n);
            for (std::size_t i = 0; i < n; ++i) indices[i] = std::uint32_t(i);
        }
        data.triangles = triangulate(indices, primitive.mode, what);
        return m_primitives[key] = std::move(data);
    }

    static std::vector<glm::uvec3> triangulate(const std::vector<std::uint32_t>& v, int mode, const std::string& what) {
        std::vector<glm::uvec3> triangles;
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (v.size() % 3 != 0) throw Error(what + ": " + str(v.size()) + " triangle indices are not a multiple of 3");
            for (std::size_t i = 0; i < v.size(); i += 3) triangles.emplace_back(v[i], v[i + 1], v[i + 2]);
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // glTF 3.7.2.1: triangle i is (v_i, v_i+1+i%2, v_i+2-i%2), keeping the winding.
            for (std::size_t i = 0; i + 2 < v.size(); ++i) triangles.emplace_back(v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]);
        } else {
            // Fan: triangle i is (v_i+1, v_i+2, v_0).
            for (std::size_t i = 0; i + 2 < v.size(); ++i) triangles.emplace_back(v[i + 1], v[i + 2], v[0]);
        }
        return triangles;
    }

    const MaterialInfo& material(int index) {
        if (auto it = m_materials.find(index); it != m_materials.end()) return it->second;
        MaterialInfo info;
        info.index = std::uint32_t(m_scene.materials.size());
        Material material;
        if (index < 0) {
            material.name = "default";  // glTF's default material: white, opaque, single-sided
        } else {
            if (std::size_t(index) >= m_model.materials.size()) throw Error("material " + str(index) + " does not exist");
            const tinygltf::Material& src = m_model.materials[std::size_t(index)];
            const std::string what = "material " + str(index);
            material.name = src.name;
            const std::vector<double>& factor = src.pbrMetallicRoughness.baseColorFactor;
            if (factor.size() != 4 || !isFinite(factor)) throw Error(what + ": baseColorFactor is not four finite numbers");
            material.baseColor = glm::clamp(glm::vec3(float(factor[0]), float(factor[1]), float(factor[2])), 0.0f, 1.0f);
            if (src.alphaMode.empty() || src.alphaMode == "OPAQUE") material.alphaMode = AlphaMode::Opaque;
            else if (src.alphaMode == "MASK") material.alphaMode = AlphaMode::Mask;
            else if (src.alphaMode == "BLEND") material.alphaMode = AlphaMode::Blend;
            else throw Error(what + ": unknown alphaMode '" + src.alphaMode + "'");
            // glTF: an opaque material ignores every alpha, its base colour's included.
            if (material.alphaMode != AlphaMode::Opaque) material.opacity = std::clamp(float(factor[3]), 0.0f, 1.0f);
            if (!std::isfinite(src.alphaCutoff)) throw Error(what + ": alphaCutoff is not finite");
            material.alphaCutoff = std::clamp(float(src.alphaCutoff), 0.0f, 1.0f);
            material.doubleSided = src.doubleSided;
            const tinygltf::TextureInfo& texture = src.pbrMetallicRoughness.baseColorTexture;
            if (texture.index >= 0) {
                if (texture.texCoord < 0) throw Error(what + ": baseColorTexture texCoord is negative");
                info.texCoord = texture.texCoord;
                info.uvTransform = textureTransform(texture.extensions, info.texCoord, what + " baseColorTexture");
                material.baseColorTexture = int(this->texture(texture.index, what + " baseColorTexture"));
            }
        }
        m_scene.materials.push_back(material);
        return m_materials[index] = info;
    }

    // A streak texture per (image, wrap modes); the minification and magnification filters are
    // not honoured: streak always filters trilinearly from the pixel (or path) footprint.
    std::uint32_t texture(int index, const std::string& what) {
        if (std::size_t(index) >= m_model.textures.size()) throw Error(what + ": texture " + str(index) + " does not exist");
        const tinygltf::Texture& src = m_model.textures[std::size_t(index)];
        const std::string where = what + " (texture " + str(index) + ")";
        if (src.source < 0) throw Error(where + ": has no PNG or JPEG image");
        WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
        if (src.sampler >= 0) {
            if (std::size_t(src.sampler) >= m_model.samplers.size()) throw Error(where + ": sampler " + str(src.sampler) + " does not exist");
            const tinygltf::Sampler& sampler = m_model.samplers[std::size_t(src.sampler)];
            wrapS = wrapMode(sampler.wrapS, where + " wrapS");
            wrapT = wrapMode(sampler.wrapT, where + " wrapT");
        }
        const auto key = std::make_tuple(src.source, wrapS, wrapT);
        if (auto it = m_textures.find(key); it != m_textures.end()) return it->second;
        const gltf::DecodedImage image = gltf::decodeImage(m_document, src.source, m_documentLimits);
        m_scene.textures.push_back(Texture::fromSrgb8(image.width, image.height, image.rgba, wrapS, wrapT));
        return m_textures[key] = std::uint32_t(m_scene.textures.size() - 1);
    }

    // One instance's vertices (or normals) at one time. Poses share them: an instance whose
    // inputs did not change since the previous pose (a still part, or a whole still scene) holds
    // the previous pose's vertices, not a copy. On the million-triangle still spheres the copies
    // into the second key and the middle pose, and the fresh pages they took, were most of
    // poseAt's time.
    using SharedVertices = std::shared_ptr<const std::vector<glm::vec3>>;
    static SharedVertices share(std::vector<glm::vec3>&& vertices) { return std::make_shared<const std::vector<glm::vec3>>(std::move(vertices)); }

    // The vertices of every instance at one animation time, and what they were computed from.
    struct PosedInstances {
        std::vector<SharedVertices> positions, normals;  ///< per instance
        gltf::NodePoses nodes;
        std::map<int, std::vector<glm::mat4>> joints;            ///< by skin
    };

    // Every instance deformed at `time`. Where an instance's inputs (world matrix, morph weights,
    // joint matrices) equal those of `previous`, its vertices are copied rather than computed.
    PosedInstances poseAt(float time, const PosedInstances* previous) {
        PosedInstances out;
        out.nodes = gltf::poseNodes(m_nodes, m_animation ? &*m_animation : nullptr, time);
        for (const Instance& instance : m_instances)
            if (instance.skin >= 0 && instance.data->geometry.isSkinned() && !out.joints.count(instance.skin))
                out.joints[instance.skin] = gltf::jointMatrices(skin(instance.skin), out.nodes);
        out.positions.resize(m_instances.size());
        out.normals.resize(m_instances.size());
        for (std::size_t i = 0; i < m_instances.size(); ++i) {
            const Instance& instance = m_instances[i];
            const std::size_t n = instance.data->geometry.numVertices(), node = instance.node;
            if (instance.cacheFirst) {
                // The cache holds the deformation: skin and morph targets are not applied.
                std::vector<glm::vec3> positions, normals;
                cachedPose(instance, time, out.nodes.worldFromNode[node], positions, normals);
                out.positions[i] = share(std::move(positions));
                out.normals[i] = share(std::move(normals));
                continue;
            }
            const bool isSkinned = instance.skin >= 0 && instance.data->geometry.isSkinned();
            const bool isUnchanged = previous && instance.data->velocities.empty() && out.nodes.worldFromNode[node] == previous->nodes.worldFromNode[node] &&
                                     out.nodes.weights[node] == previous->nodes.weights[node] &&
                                     (!isSkinned || out.joints[instance.skin] == previous->joints.at(instance.skin));
            if (isUnchanged) {
                out.positions[i] = previous->positions[i];
                out.normals[i] = previous->normals[i];
                continue;
            }
            std::vector<glm::vec3> positions(n), normals(instance.data->geometry.normals.empty() ? 0 : n);
            const std::span<const glm::mat4> jointMatrices =
                isSkinned ? std::span<const glm::mat4>(out.joints[instance.skin]) : std::span<const glm::mat4>();
            gltf::deformPrimitive(instance.data->geometry, out.nodes.weights[node], out.nodes.worldFromNode[node], jointMatrices,
                                  positions, normals);
            addVelocities(*instance.data, time, out.nodes.worldFromNode[node], positions);
            out.positions[i] = share(std::move(positions));
            out.normals[i] = share(std::move(normals));
        }
        return out;
    }

    // _VELOCITY (fluids, remeshers: meshes whose topology changes between frames): each vertex
    // moves along its velocity, turned and scaled by the node, from where it is at the
    // velocity's frame (GltfOptions::velocityFrame), in metres per second or per frame.
    void addVelocities(const PrimitiveData& data, float time, const glm::mat4& worldFromNode, std::vector<glm::vec3>& positions) const {
        if (data.velocities.empty()) return;
        const double seconds = double(time) - m_options.velocityFrame.value_or(m_options.frame) / m_options.fps;
        const float scale = float(m_options.isVelocityPerFrame ? seconds * m_options.fps : seconds);
        const glm::mat3 linear(worldFromNode);
        for (std::size_t v = 0; v < positions.size(); ++v) positions[v] += linear * (scale * data.velocities[v]);
    }

    // How far the keys' path strays from the animation at the middle between each two keys, seen
    // through the scene's camera at that time, in pixels of an image options.imageHeight tall.
    // The path is the curve of degree m_pieceOrder through each piece's keys: the chords of
    // linear keys (1), or the Bezier pieces through evenly spaced poses, whose value between
    // two of them is the polynomial through the piece's poses there. Camera motion is not
    // counted: every method follows the camera itself.
    struct KeyDeviation {
        double screen = 0.0;  ///< on screen: the largest distance between the two projections
        // In depth, where a surface can pass in front of another: the largest error along the
        // view axis, in the pixels it would span across the view at that distance. Two surfaces
        // passing through each other along the view axis barely move on screen, yet which one
        // shows changes when their depths cross; keys that miss the depths by d put the crossing
        // where the depth gap is d. Counted for the instances whose screen boxes over the shutter
        // meet another instance's (not a lone mesh's folds).
        double depth = 0.0;
        double worst() const { return std::max(screen, depth); }
    };
    KeyDeviation keyDeviation(const std::vector<PosedInstances>& keys, const std::vector<PosedInstances>& middles) const {
        const int numSegments = int(middles.size());
        const float aspect = m_options.aspect;
        const double pixelsPerView = 0.5 * double(m_options.imageHeight) / std::tan(0.5 * double(m_scene.camera.verticalFov));
        // One pass: the screen deviation, and per instance its depth deviation and the NDC box its
        // true positions cover over the shutter; the depth counts where the boxes meet.
        KeyDeviation worst;
        std::vector<double> depths(m_instances.size(), 0.0);
        std::vector<glm::dvec4> boxes(m_instances.size(), glm::dvec4(1e300, 1e300, -1e300, -1e300));
        const int order = m_pieceOrder;
        for (int k = 0; k < numSegments; ++k) {
            const glm::mat4 clipFromWorld = m_scene.camera.clipFromWorld((float(k) + 0.5f) / float(numSegments), aspect);
            // The piece's keys, and the Lagrange weights of its polynomial half way after key k.
            const int first = k / order * order;
            std::array<float, 4> weight{};
            for (int j = 0; j <= order; ++j) {
                double w = 1.0;
                for (int m = 0; m <= order; ++m)
                    if (m != j) w *= (double(k - first) + 0.5 - m) / double(j - m);
                weight[std::size_t(j)] = float(w);
            }
            for (std::size_t i = 0; i < m_instances.size(); ++i) {
                const std::vector<glm::vec3>& m = *middles[std::size_t(k)].positions[i];
                std::array<const glm::vec3*, 4> key{};
                for (int j = 0; j <= order; ++j) key[std::size_t(j)] = keys[std::size_t(first + j)].positions[i]->data();
                for (std::size_t v = 0; v < m.size(); ++v) {
                    glm::vec3 path = weight[0] * key[0][v];
                    for (int j = 1; j <= order; ++j) path += weight[std::size_t(j)] * key[std::size_t(j)][v];
                    const glm::vec4 lin = clipFromWorld * glm::vec4(path, 1.0f);
                    const glm::vec4 truth = clipFromWorld * glm::vec4(m[v], 1.0f);
                    if (!(lin.w > m_scene.camera.zNear) || !(truth.w > m_scene.camera.zNear)) continue;
                    const double pixels = Camera::pixelsOfNdc(glm::dvec2(lin.x / lin.w - truth.x / truth.w, lin.y / lin.w - truth.y / truth.w),
                                                              aspect, double(m_options.imageHeight));
                    if (std::isfinite(pixels)) worst.screen = std::max(worst.screen, pixels);
                    const double depth = std::abs(double(lin.w) - double(truth.w)) / double(truth.w) * pixelsPerView;
                    if (std::isfinite(depth)) depths[i] = std::max(depths[i], depth);
                    const glm::dvec2 ndc = glm::dvec2(truth.x / truth.w, truth.y / truth.w);
                    boxes[i] = glm::dvec4(glm::min(glm::dvec2(boxes[i]), ndc), glm::max(glm::dvec2(boxes[i].z, boxes[i].w), ndc));
                }
            }
        }
        for (std::size_t i = 0; i < boxes.size(); ++i)
            for (std::size_t j = i + 1; j < boxes.size(); ++j)
                if (boxes[i].x <= boxes[j].z && boxes[j].x <= boxes[i].z && boxes[i].y <= boxes[j].w && boxes[j].y <= boxes[i].w)
                    worst.depth = std::max({worst.depth, depths[i], depths[j]});
        return worst;
    }

    // The key poses: options.motionKeys evenly spaced keys, or, with motionKeys 0, 2, 3, 5, 9...
    // keys (each level adds the middles of the last, so every coarser key stays a key and the
    // pieces of exact methods stay exact; Bezier pieces of degree n: n + 1, 2n + 1, 4n + 1...
    // poses, 1, 2, 4... pieces) until the keys stay within options.keyTolerancePixels of the
    // animation on screen and, where surfaces can pass in front of others, in depth
    // (KeyDeviation), or the cap (maxMotionKeys, the vertex-work limit) is reached.
    void sampleKeys() {
        std::vector<PosedInstances> keys;
        for (int k = 0; k < m_numKeys; ++k) keys.push_back(poseAt(keyTime(k, m_numKeys), keys.empty() ? nullptr : &keys.back()));
        m_openPoses = keys.front().nodes;
        m_closePoses = keys.back().nodes;
        const bool isAdaptive = m_options.motionKeys == 0;
        std::optional<KeyDeviation> deviation;
        // The meshes are made once; where the keys change after that, only the keys are written again.
        bool isMade = false, holdsKeys = false;
        if (isAdaptive && m_options.shutter > 0.0 && !m_instances.empty()) {
            makeMeshes(keys);
            isMade = holdsKeys = true;
            placeCamera();  // the deviation is measured through it
            const std::size_t cap = std::size_t(std::clamp(m_options.maxMotionKeys, 2, kMaxMotionKeys));
            while (true) {
                const int numKeys = int(keys.size());
                if (std::size_t(2 * numKeys - 1) * m_vertexWorkPerKey > m_options.limits.maxVertexWork) break;
                std::vector<PosedInstances> middles;
                for (int k = 0; k + 1 < numKeys; ++k) middles.push_back(poseAt(keyTime(2 * k + 1, 2 * numKeys - 1), &keys[std::size_t(k)]));
                deviation = keyDeviation(keys, middles);
                if (deviation->worst() <= m_options.keyTolerancePixels || std::size_t(2 * numKeys - 1) > cap) break;
                std::vector<PosedInstances> refined;
                for (int k = 0; k < numKeys; ++k) {
                    refined.push_back(std::move(keys[std::size_t(k)]));
                    if (k + 1 < numKeys) refined.push_back(std::move(middles[std::size_t(k)]));
                }
                keys = std::move(refined);
                holdsKeys = false;
            }
            // Keys on the animation's own: where its keyframes inside the shutter fall on an even
            // grid of fewer pieces than the halving found (or the halving missed the tolerance),
            // keys on that grid follow piecewise linear channels (morph weights, translations)
            // exactly, kinks and all, as the grid's measured deviation must show. Its poses and
            // middles are posed while the halving's keys are held: the vertex-work limit counts both.
            const int numKeys = int(keys.size());
            const bool isMissed = deviation && deviation->worst() > m_options.keyTolerancePixels;
            if (const int pieces = keyframeGridPieces(); m_pieceOrder == 1 && numKeys > 2 && pieces > 0 &&
                                                         (pieces + 1 < numKeys || (isMissed && pieces + 1 > numKeys && std::size_t(pieces + 1) <= cap)) &&
                                                         std::size_t(2 * pieces + 1 + numKeys) * m_vertexWorkPerKey <= m_options.limits.maxVertexWork) {
                std::vector<PosedInstances> grid, middles;
                for (int k = 0; k <= pieces; ++k) grid.push_back(poseAt(keyTime(k, pieces + 1), grid.empty() ? nullptr : &grid.back()));
                for (int k = 0; k < pieces; ++k) middles.push_back(poseAt(keyTime(2 * k + 1, 2 * pieces + 1), &grid[std::size_t(k)]));
                const KeyDeviation gridDeviation = keyDeviation(grid, middles);
                if (gridDeviation.worst() <= m_options.keyTolerancePixels) {
                    keys = std::move(grid), deviation = gridDeviation;
                    holdsKeys = false;
                    if (m_stats) m_stats->setInfo("motion_keys_on", "keyframes");
                }
            }
        }
        if (!isMade) makeMeshes(keys);
        else if (!holdsKeys) writeKeys(keys);
        if (m_stats) {
            m_stats->setCounter("motion_keys", double(keys.size()));
            if (deviation) {
                m_stats->setCounter("motion_key_deviation_px", deviation->screen);
                m_stats->setCounter("motion_key_depth_deviation_px", deviation->depth);
                // What set the count: the screen paths, what depth does to visibility, or the cap.
                m_stats->setInfo("motion_keys_chosen_by", deviation->worst() > m_options.keyTolerancePixels ? "cap"
                                                          : deviation->depth > deviation->screen       ? "depth"
                                                                                                       : "screen");
            }
        }
    }

    // The fewest even pieces of the shutter (up to kMaxMotionKeys - 1) whose ends hold every
    // keyframe time of the animation strictly inside the shutter, or 0 where there is none or
    // no such grid (a keyframe off every grid by more than a thousandth of a piece).
    int keyframeGridPieces() const {
        if (!m_animation) return 0;
        const double t0 = m_options.frame / m_options.fps, t1 = (m_options.frame + m_options.shutter) / m_options.fps;
        std::vector<double> inside;  // as shares of the shutter
        for (const gltf::AnimationSampler& sampler : m_animation->samplers)
            for (const float time : sampler.times) {
                const double u = (double(time) - t0) / (t1 - t0);
                if (u > 1e-6 && u < 1.0 - 1e-6) inside.push_back(u);
            }
        if (inside.empty()) return 0;
        for (int pieces = 1; pieces < kMaxMotionKeys; ++pieces)
            if (std::all_of(inside.begin(), inside.end(), [&](double u) { return std::abs(u * pieces - std::round(u * pieces)) <= 1e-3; }))
                return pieces;
        return 0;
    }

    // --motion-curve bezier: the poses become the control points of the curve through them (or
    // of the least-squares fit to motionFitSamples poses), or of each chosen piece's curve
    // through its poses, once the camera has been placed from the poses (the control points
    // overshoot the motion).
    void curveKeys() {
        if (m_options.motionCurve != MotionInterpolation::Bezier) return;
        for (Mesh& mesh : m_scene.meshes) {
            mesh.interpolation = MotionInterpolation::Bezier;
            if (m_fitSamples == 0) {
                // Pieces share their end poses, which their curves keep: each piece converts
                // its own copy of its poses.
                const int order = m_options.motionKeys == 0 ? m_pieceOrder : mesh.numKeys - 1;
                mesh.bezierPieces = (mesh.numKeys - 1) / order;
                const std::size_t n = mesh.numVertices();
                for (std::vector<glm::vec3>* keys : {&mesh.positions, &mesh.normals}) {
                    if (keys->empty()) continue;
                    const std::vector<glm::vec3> poses = *keys;
                    for (int p = 0; p < mesh.bezierPieces; ++p) {
                        const std::size_t first = std::size_t(p * order) * n, count = std::size_t(order + 1) * n;
                        std::vector<glm::vec3> piece(poses.begin() + std::ptrdiff_t(first), poses.begin() + std::ptrdiff_t(first + count));
                        bezierControlPointsThroughSamples(piece, order + 1);
                        std::copy(piece.begin() + std::ptrdiff_t(n), piece.end() - std::ptrdiff_t(n), keys->begin() + std::ptrdiff_t(first + n));
                    }
                }
                continue;
            }
            const int order = m_options.motionKeys - 1;
            mesh.positions = bezierControlPointsFittingSamples(mesh.positions, mesh.numKeys, order);
            if (mesh.hasNormals()) mesh.normals = bezierControlPointsFittingSamples(mesh.normals, mesh.numKeys, order);
            mesh.numKeys = m_options.motionKeys;
        }
        if (m_stats && m_fitSamples != 0) {
            m_stats->setCounter("motion_keys", double(m_options.motionKeys));
            m_stats->setCounter("motion_fit_samples", double(m_fitSamples));
        }
        if (m_stats && !m_scene.meshes.empty()) {
            m_stats->setCounter("motion_bezier_pieces", double(m_scene.meshes.front().bezierPieces));
            m_stats->setCounter("motion_bezier_order", double(m_scene.meshes.front().bezierOrder()));
        }
    }

    // One streak Mesh per instance: what the keys do not change (name, triangles, uvs, colours,
    // material, winding), then the keys (writeKeys). A primitive only one instance uses hands its
    // mesh its uvs and colours rather than a copy, and its triangles unless a point cache moves
    // the instance: cachedPose makes every later pose's normals from them (the keys the chooser
    // adds after this). Nothing else reads them from the primitive afterwards, and on the
    // million-triangle spheres (102 primitives, each placed once) the triangles alone are 12 MB
    // of fresh pages.
    void makeMeshes(const std::vector<PosedInstances>& keys) {
        m_scene.meshes.assign(m_instances.size(), Mesh{});
        std::map<const PrimitiveData*, int> uses;
        for (const Instance& instance : m_instances) ++uses[instance.data];
        // glTF 3.7.4: a mirroring transform (negative determinant) turns the winding clockwise;
        // flip it back so that front faces stay counter-clockwise. Judged at mid-shutter.
        const gltf::NodePoses middle = gltf::poseNodes(m_nodes, m_animation ? &*m_animation : nullptr, keyTime(1, 3));
        for (std::size_t i = 0; i < m_instances.size(); ++i) {
            const Instance& instance = m_instances[i];
            PrimitiveData& data = *instance.data;
            Mesh& mesh = m_scene.meshes[i];
            mesh.name = instance.name;
            mesh.interpolation = MotionInterpolation::PiecewiseLinear;
            const bool isOnlyUse = uses[instance.data] == 1;
            mesh.uvs = isOnlyUse ? std::move(data.uvs) : data.uvs;
            mesh.colors = isOnlyUse ? std::move(data.colors) : data.colors;
            mesh.triangles = isOnlyUse && !instance.cacheFirst ? std::move(data.triangles) : data.triangles;
            mesh.material = data.material;
            if (isMirrored(instance, middle.worldFromNode[instance.node]))
                for (glm::uvec3& tri : mesh.triangles) std::swap(tri.y, tri.z);
        }
        writeKeys(keys);
    }

    // The meshes' keys (positions and normals, key after key) from the key poses.
    void writeKeys(const std::vector<PosedInstances>& keys) {
        const int numKeys = int(keys.size());
        for (std::size_t i = 0; i < m_instances.size(); ++i) {
            const std::size_t n = m_instances[i].data->geometry.numVertices();
            const bool hasNormals = !m_instances[i].data->geometry.normals.empty();
            Mesh& mesh = m_scene.meshes[i];
            mesh.numKeys = numKeys;
            mesh.positions.clear();
            mesh.normals.clear();
            mesh.positions.reserve(n * std::size_t(numKeys));
            if (hasNormals) mesh.normals.reserve(n * std::size_t(numKeys));
            for (const PosedInstances& key : keys) {
                mesh.positions.insert(mesh.positions.end(), key.positions[i]->begin(), key.positions[i]->end());
                if (hasNormals) mesh.normals.insert(mesh.normals.end(), key.normals[i]->begin(), key.normals[i]->end());
            }
        }
    }

    // World-space bounds of every key pose, to frame the scene or scale the near plane.
    void sceneBounds(glm::vec3& lo, glm::vec3& hi) const {
        lo = glm::vec3(std::numeric_limits<float>::max());
        hi = glm::vec3(-std::numeric_limits<float>::max());
        for (const Mesh& mesh : m_scene.meshes)
            for (const glm::vec3& p : mesh.positions)
                if (isFinite(p)) lo = glm::min(lo, p), hi = glm::max(hi, p);
        if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);
    }

    void placeCamera() {
        Camera& camera = m_scene.camera;
        glm::vec3 lo, hi;
        sceneBounds(lo, hi);
        const glm::vec3 centre = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
        const float diagonal = 2.0f * glm::length(half);

        if (m_options.lookAt) {
            const GltfLookAt& look = *m_options.lookAt;
            const glm::vec3 positionEnd = look.positionEnd.value_or(look.position), targetEnd = look.targetEnd.value_or(look.target);
            for (const auto& [from, to] : {std::pair{look.position, look.target}, std::pair{positionEnd, targetEnd}}) {
                if (!isFinite(from) || !isFinite(to) || !isFinite(look.up)) throw Error("camera position, target and up must be finite");
                const glm::vec3 forward = to - from;
                if (!(glm::length(forward) > 0.0f)) throw Error("camera position and target must differ");
                if (!(glm::length(glm::cross(forward, look.up)) > 1e-6f * glm::length(forward) * glm::length(look.up)))
                    throw Error("camera up must not be parallel to the view direction");
            }
            if (!(look.verticalFovDegrees > 0.0f && look.verticalFovDegrees < 180.0f)) throw Error("--fov must be in (0, 180) degrees");
            camera.open = CameraPose::lookAt(look.position, look.target, look.up);
            camera.close = CameraPose::lookAt(positionEnd, targetEnd, look.up);
            camera.verticalFov = glm::radians(look.verticalFovDegrees);
            const float distance = std::max(glm::length(look.position - centre), glm::length(positionEnd - centre));
            camera.zNear = std::max(1e-4f * (diagonal + distance), 1e-8f);
            if (m_stats) m_stats->setInfo("camera_source", "look-at");
            return;
        }

        int cameraNode = -1;
        if (m_options.camera) {
            const int index = *m_options.camera;
            if (index < 0 || std::size_t(index) >= m_model.cameras.size())
                throw Error("camera " + str(index) + " does not exist (the file has " + str(m_model.cameras.size()) + ")");
            if (m_model.cameras[std::size_t(index)].type != "perspective")
                throw Error("camera " + str(index) + " is not a perspective camera");
            for (std::size_t i = 0; i < m_nodes.size() && cameraNode < 0; ++i)
                if (m_isInScene[i] && m_model.nodes[i].camera == index) cameraNode = int(i);
            if (cameraNode < 0) throw Error("camera " + str(index) + " is not placed by any node of the scene");
        } else {
            for (std::size_t i = 0; i < m_nodes.size() && cameraNode < 0; ++i) {
                const int c = m_model.nodes[i].camera;
                if (m_isInScene[i] && c >= 0 && std::size_t(c) < m_model.cameras.size() && m_model.cameras[std::size_t(c)].type == "perspective")
                    cameraNode = int(i);
            }
        }
        if (cameraNode >= 0) {
            const int index = m_model.nodes[std::size_t(cameraNode)].camera;
            const std::string what = "camera " + str(index);
            const tinygltf::PerspectiveCamera& perspective = m_model.cameras[std::size_t(index)].perspective;
            if (!(perspective.yfov > 0.0 && perspective.yfov < std::numbers::pi)) throw Error(what + ": yfov is not in (0, pi)");
            if (!(perspective.znear > 0.0) || !std::isfinite(perspective.znear)) throw Error(what + ": znear is not positive");
            camera.open = poseFromMatrix(m_openPoses.worldFromNode[std::size_t(cameraNode)], what);
            camera.close = poseFromMatrix(m_closePoses.worldFromNode[std::size_t(cameraNode)], what);
            camera.verticalFov = float(perspective.yfov);
            camera.zNear = float(perspective.znear);
            if (m_stats) m_stats->setInfo("camera_source", "gltf camera " + str(index));
            return;
        }

        // No camera: look down -z at the bounds from far enough on +z to see all of them.
        camera.verticalFov = glm::radians(45.0f);
        const float tanHalf = std::tan(0.5f * camera.verticalFov);
        const float reach = std::max(half.y, half.x / m_options.aspect) / tanHalf;
        const float distance = half.z + std::max(1.1f * reach, 1e-6f);
        camera.open = camera.close = CameraPose::lookAt(centre + glm::vec3(0.0f, 0.0f, distance), centre);
        camera.zNear = std::max(0.01f * (distance - half.z), 1e-9f);
        if (m_stats) m_stats->setInfo("camera_source", "framed");
    }

    const gltf::Document& m_document;
    const tinygltf::Model& m_model;
    const GltfOptions& m_options;
    RenderStats* m_stats;
    AccessorReader m_reader;
    gltf::DocumentLimits m_documentLimits;
    Scene m_scene;
    int m_numKeys = 2;                                               ///< keys sampled first (options.motionKeys, or 2 to refine)
    int m_fitSamples = 0;                                            ///< Bezier keys: poses fitted by least squares (0: through the keys)
    int m_pieceOrder = 1;                                            ///< chosen keys: the degree of their pieces (1: linear keys)
    std::size_t m_vertexWorkPerKey = 0;                              ///< GltfLimits::maxVertexWork's measure of one key
    std::vector<gltf::Node> m_nodes;
    std::vector<bool> m_isInScene;                                   ///< per node: reachable from the scene's roots
    std::optional<gltf::Animation> m_animation;
    std::map<int, gltf::Skin> m_skins;                               ///< by glTF skin index
    std::map<std::pair<int, int>, PrimitiveData> m_primitives;       ///< by (mesh, primitive)
    std::map<int, MaterialInfo> m_materials;                         ///< by glTF material index (-1: default)
    std::map<std::tuple<int, WrapMode, WrapMode>, std::uint32_t> m_textures;  ///< by (image, wraps)
    std::vector<Instance> m_instances;
    std::optional<PointCache> m_pointCache;
    gltf::NodePoses m_openPoses, m_closePoses;
    std::size_t m_numSkipped = 0;                                    ///< primitives that are not triangles
};

}  // namespace

Scene loadGltfFromMemory(std::span<const std::uint8_t> bytes, const std::string& name, const std::string& baseDir,
                         const GltfOptions& options, RenderStats* stats) {
    try {
        const gltf::DocumentLimits limits{options.allowExternalFiles, options.limits.maxFileBytes, options.limits.maxTexels};
        const gltf::Document document = gltf::parseDocument(bytes, baseDir, limits);
        Scene scene = SceneBuilder(document, options, stats).build();
        scene.name = std::filesystem::path(name).stem().string();
        return scene;
    } catch (const Error& e) {
        throw Error(name + ": " + e.what());
    } catch (const std::bad_alloc&) {
        throw Error(name + ": out of memory");
    } catch (const std::length_error&) {
        throw Error(name + ": out of memory");
    }
}

Scene loadGltf(const std::string& path, const GltfOptions& options, RenderStats* stats) {
    const std::vector<std::uint8_t> bytes = gltf::readFileBytes(path, options.limits.maxFileBytes);
    return loadGltfFromMemory(bytes, path, std::filesystem::path(path).parent_path().string(), options, stats);
}

}  // namespace streak
