#include "scene/mesh_sequence.h"

#include "scene/frame_pattern.h"
#include "scene/mesh_file.h"
#include "util/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>

namespace streak {

namespace {

// A glTF binary of one mesh built up in memory: accessors over one buffer.
class GlbBuilder {
public:
    int addFloats(const float* values, std::size_t count, const std::string& type, bool withBounds = false) {
        const std::size_t components = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 0;
        const std::size_t offset = m_buffer.size();
        m_buffer.resize(offset + count * components * sizeof(float));
        std::memcpy(m_buffer.data() + offset, values, count * components * sizeof(float));
        nlohmann::json accessor = {{"bufferView", addView(offset)}, {"componentType", 5126}, {"count", count}, {"type", type}};
        if (withBounds) {
            std::vector<float> lo(components, std::numeric_limits<float>::max()), hi(components, -std::numeric_limits<float>::max());
            for (std::size_t i = 0; i < count * components; ++i) lo[i % components] = std::min(lo[i % components], values[i]), hi[i % components] = std::max(hi[i % components], values[i]);
            accessor["min"] = lo, accessor["max"] = hi;
        }
        m_json["accessors"].push_back(accessor);
        return int(m_json["accessors"].size()) - 1;
    }
    int addIndices(const std::vector<glm::uvec3>& triangles) {
        const std::size_t offset = m_buffer.size();
        m_buffer.resize(offset + triangles.size() * 12);
        for (std::size_t t = 0; t < triangles.size(); ++t)
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t v = triangles[t][c];
                std::memcpy(m_buffer.data() + offset + t * 12 + std::size_t(c) * 4, &v, 4);
            }
        m_json["accessors"].push_back({{"bufferView", addView(offset)}, {"componentType", 5125}, {"count", triangles.size() * 3}, {"type", "SCALAR"}});
        return int(m_json["accessors"].size()) - 1;
    }
    nlohmann::json& json() { return m_json; }

    std::vector<std::uint8_t> glb() {
        while (m_buffer.size() % 4) m_buffer.push_back(0);
        m_json["buffers"] = nlohmann::json::array({{{"byteLength", m_buffer.size()}}});
        std::string text = m_json.dump();
        while (text.size() % 4) text += ' ';
        std::vector<std::uint8_t> out;
        auto u32 = [&](std::uint32_t v) {
            for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
        };
        u32(0x46546C67), u32(2), u32(std::uint32_t(12 + 8 + text.size() + 8 + m_buffer.size()));
        u32(std::uint32_t(text.size())), u32(0x4E4F534A);
        out.insert(out.end(), text.begin(), text.end());
        u32(std::uint32_t(m_buffer.size())), u32(0x004E4942);
        out.insert(out.end(), m_buffer.begin(), m_buffer.end());
        return out;
    }

private:
    int addView(std::size_t offset) {
        m_json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", m_buffer.size() - offset}});
        while (m_buffer.size() % 4) m_buffer.push_back(0);
        return int(m_json["bufferViews"].size()) - 1;
    }

    nlohmann::json m_json = {{"asset", {{"version", "2.0"}, {"generator", "streak mesh sequence"}}}};
    std::vector<std::uint8_t> m_buffer;
};

}  // namespace

Scene loadMeshSequence(const std::string& spec, const GltfOptions& options, RenderStats* stats) {
    bool isSequence = false;
    framePatternPath(spec, 0, isSequence);
    if (!std::isfinite(options.frame) || !(options.shutter >= 0.0) || !std::isfinite(options.shutter) || !(options.fps > 0.0) || !std::isfinite(options.fps))
        throw Error("the shutter must be finite frames and --fps positive");
    // The files the shutter spans: frame N is file N. Past the sequence's ends the mesh holds its
    // end file, as an animation holds its end values; a file missing between two that exist is
    // a missing frame.
    const double open = options.frame, close = options.frame + options.shutter;
    const double reference = options.velocityFrame.value_or(open);  // the frame whose file a held mesh shows
    if (!std::isfinite(reference) || std::abs(open) > 1e9 || std::abs(close) > 1e9 || std::abs(reference) > 1e9)
        throw Error(spec + ": frames beyond a billion");
    long first = isSequence ? long(std::floor(std::min(open, reference) + 1e-9)) : 0;
    long last = isSequence ? std::max(first, long(std::ceil(std::max(close, reference) - 1e-9))) : 0;
    if (last - first > 4096) throw Error(spec + ": a shutter of more than 4096 frames");
    auto pathOf = [&](long frame) {
        bool unused = false;
        return framePatternPath(spec, frame, unused);
    };
    auto exists = [&](long frame) {
        std::error_code ec;
        return std::filesystem::is_regular_file(pathOf(frame), ec);
    };
    std::vector<long> present;
    for (long frame = first; frame <= last; ++frame)
        if (exists(frame)) present.push_back(frame);
    if (present.empty())
        throw Error(pathOf(first) + (isSequence ? ": the sequence has no file for frames " + std::to_string(first) + " to " + std::to_string(last) : ": no such file"));
    for (std::size_t k = 1; k < present.size(); ++k)
        if (present[k] != present[k - 1] + 1)
            throw Error(pathOf(present[k - 1] + 1) + ": frame " + std::to_string(present[k - 1] + 1) + " of the sequence is missing");
    // Outside the range, a sequence of files lying further on holds its nearer end.
    first = present.front(), last = present.back();
    std::vector<MeshFile> files;
    std::size_t vertexWork = 0;
    for (long frame = first; frame <= last; ++frame) {
        files.push_back(readMeshFile(pathOf(frame), options.limits.maxFileBytes, options.limits.maxTriangles));
        vertexWork += files.back().positions.size();
        if (vertexWork > options.limits.maxVertexWork) throw Error(spec + ": the files' vertices exceed the limit of " + std::to_string(options.limits.maxVertexWork));
    }
    if (options.isSequenceInterpolated)
        for (std::size_t k = 1; k < files.size(); ++k)
            if (files[k].positions.size() != files.front().positions.size())
                throw Error(spec + ": frame " + std::to_string(first + long(k)) + " has " + std::to_string(files[k].positions.size()) + " vertices and frame " +
                            std::to_string(first) + " " + std::to_string(files.front().positions.size()) +
                            ": only files of one vertex count interpolate (without --sequence-interpolate, the mesh is held or moved by its velocities)");
    const bool isSameTopology = std::all_of(files.begin(), files.end(), [&](const MeshFile& f) {
        return f.positions.size() == files.front().positions.size() && (options.isSequenceInterpolated || f.triangles == files.front().triangles);
    });
    const bool isHeld = !isSameTopology;
    // A held mesh is the file of the reference frame (--frame), moved by its velocities from there.
    const long heldFrame = std::clamp(long(std::floor(reference + 1e-9)), first, last);
    const MeshFile& base = isHeld ? files[std::size_t(heldFrame - first)] : files.front();
    const std::size_t n = base.positions.size();

    GlbBuilder b;
    nlohmann::json primitive;
    primitive["attributes"]["POSITION"] = b.addFloats(&base.positions[0].x, n, "VEC3", true);
    primitive["indices"] = b.addIndices(base.triangles);
    GltfOptions o = options;
    o.allowExternalFiles = false;
    if ((isHeld || files.size() == 1) && !base.velocities.empty()) {
        // The files cannot be interpolated (or there is one): the held one moves along its
        // velocities from its frame (a lone file's: the frame the user names).
        primitive["attributes"]["_VELOCITY"] = b.addFloats(&base.velocities[0].x, n, "VEC3");
        if (isSequence) o.velocityFrame = double(heldFrame);
    } else if (!isHeld && files.size() > 1) {
        // Each later file is a morph target; the weights animation is one-hot on file k's target
        // at its frame, so glTF's linear interpolation moves each vertex on the line between files.
        std::vector<float> times, weights;
        const std::size_t numTargets = files.size() - 1;
        for (std::size_t k = 0; k < files.size(); ++k) {
            times.push_back(float(double(first + long(k)) / options.fps));
            for (std::size_t t = 0; t < numTargets; ++t) weights.push_back(k > 0 && t == k - 1 ? 1.0f : 0.0f);
            if (k == 0) continue;
            std::vector<glm::vec3> offsets(n);
            for (std::size_t v = 0; v < n; ++v) offsets[v] = files[k].positions[v] - base.positions[v];
            primitive["targets"].push_back({{"POSITION", b.addFloats(&offsets[0].x, n, "VEC3", true)}});
        }
        const int input = b.addFloats(times.data(), times.size(), "SCALAR", true), output = b.addFloats(weights.data(), weights.size(), "SCALAR");
        b.json()["animations"] = nlohmann::json::array(
            {{{"samplers", {{{"input", input}, {"output", output}, {"interpolation", "LINEAR"}}}},
              {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}}}});
    }
    const std::string name = std::filesystem::path(spec).stem().string();
    b.json()["meshes"] = nlohmann::json::array({{{"name", name}, {"primitives", {primitive}}}});
    b.json()["nodes"] = nlohmann::json::array({{{"mesh", 0}, {"name", name}}});
    b.json()["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
    b.json()["scene"] = 0;
    if (stats) {
        stats->setCounter("sequence_files", double(files.size()));
        stats->setCounter("sequence_topology_changes", isHeld ? 1.0 : 0.0);
        stats->setCounter("sequence_held_still", isHeld && base.velocities.empty() ? 1.0 : 0.0);
    }
    const std::vector<std::uint8_t> glb = b.glb();
    return loadGltfFromMemory(glb, spec, "", o, stats);
}

}  // namespace streak
