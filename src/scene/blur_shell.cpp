#include "scene/blur_shell.h"

#include "util/error.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace streak {

BlurShellOptions BlurShellOptions::read(OptionMap& options) {
    BlurShellOptions o;
    o.lengthSeconds = options.getDouble("length", o.lengthSeconds, 0.0, 1e6);
    if (!(o.lengthSeconds > 0.0)) throw Error(options.owner() + ": length must be more than 0 seconds");
    o.subdivisions = options.getInt("subdivisions", o.subdivisions, 1, kMaxSubdivisions);
    o.alpha = float(options.getDouble("alpha", o.alpha, 0.0, 1.0));
    o.fade = options.getInt("fade", o.fade, 1, 64);
    const std::string facing = options.getString("facing", "welded");
    if (facing != "welded" && facing != "mesh") throw Error(options.owner() + ": facing must be welded or mesh, got '" + facing + "'");
    o.isFacingWelded = facing == "welded";
    return o;
}

bool BlurShellOptions::readIsSorted(OptionMap& options) {
    const std::string blend = options.getString("blend", "ordered");
    if (blend != "ordered" && blend != "sorted") throw Error(options.owner() + ": blend must be ordered or sorted, got '" + blend + "'");
    return blend == "sorted";
}

std::size_t ShellScene::firstShellTriangle() const {
    std::size_t count = 0;
    for (std::size_t m = 0; m < firstShellMesh; ++m) count += scene.meshes[m].triangles.size();
    return count;
}

std::size_t ShellScene::numShellTriangles() const { return scene.numTriangles() - firstShellTriangle(); }

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// A mesh's vertices at update i of s (shutter time i / s): its keys themselves when there is one
// per update, so a trail loaded over [T - length, T] is used as sampled. `facing` is what the
// SoM classifies by, `normals` what shades.
struct Pose {
    std::vector<glm::vec3> positions, normals, facing;
};

// Vertices at one position share an id (runs of equal positions, by sorting): the welded mesh.
std::vector<std::uint32_t> weldedVertices(std::span<const glm::vec3> positions) {
    std::vector<std::uint32_t> order(positions.size());
    for (std::uint32_t v = 0; v < order.size(); ++v) order[v] = v;
    auto less = [&](std::uint32_t a, std::uint32_t b) {
        const glm::vec3 &p = positions[a], &q = positions[b];
        return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : p.z < q.z;
    };
    std::sort(order.begin(), order.end(), less);
    std::vector<std::uint32_t> weld(positions.size());
    std::uint32_t id = 0;
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (i > 0 && positions[order[i]] != positions[order[i - 1]]) ++id;
        weld[order[i]] = id;
    }
    return weld;
}

// Area-weighted mean polygon normals per weld id (identity ids: per vertex), normalized.
void meanPolygonNormals(const Mesh& mesh, std::span<const glm::vec3> positions, std::span<const std::uint32_t> weld,
                        std::vector<glm::vec3>& normals) {
    std::vector<glm::vec3> sum(positions.size(), glm::vec3(0.0f));
    for (const glm::uvec3& tri : mesh.triangles) {
        const glm::vec3 n = glm::cross(positions[tri.y] - positions[tri.x], positions[tri.z] - positions[tri.x]);
        for (int c = 0; c < 3; ++c) sum[weld.empty() ? tri[c] : weld[tri[c]]] += n;
    }
    normals.resize(positions.size());
    for (std::size_t v = 0; v < positions.size(); ++v) normals[v] = sum[weld.empty() ? v : weld[v]];
}

void normalize(std::vector<glm::vec3>& normals) {
    for (glm::vec3& normal : normals) {
        const float length = glm::length(normal);
        if (length > 0.0f && std::isfinite(length)) normal /= length;
    }
}

void poseAt(const Mesh& mesh, int i, int s, Pose& pose, std::span<const std::uint32_t> weld = {}) {
    const std::size_t n = mesh.numVertices();
    pose.positions.resize(n);
    pose.normals.assign(n, glm::vec3(0.0f));
    if (mesh.numKeys == s + 1 && mesh.interpolation == MotionInterpolation::PiecewiseLinear) {
        const std::span<const glm::vec3> key = mesh.keyPositions(i);
        std::copy(key.begin(), key.end(), pose.positions.begin());
        if (mesh.hasNormals())
            std::copy(mesh.normals.begin() + std::ptrdiff_t(std::size_t(i) * n),
                      mesh.normals.begin() + std::ptrdiff_t(std::size_t(i + 1) * n), pose.normals.begin());
    } else {
        const MotionWeights w = mesh.weightsAt(float(i) / float(s));
        for (std::uint32_t v = 0; v < n; ++v) {
            pose.positions[v] = mesh.positionAt(v, w);
            if (mesh.hasNormals()) pose.normals[v] = mesh.normalAt(v, w);
        }
    }
    // Without normals, each vertex takes the area-weighted mean of its polygons' (the thesis'
    // choice: a polygon whose vertex normals agree can make no SoM).
    if (!mesh.hasNormals()) meanPolygonNormals(mesh, pose.positions, {}, pose.normals);
    normalize(pose.normals);
    if (weld.empty()) {
        pose.facing = pose.normals;
    } else {
        meanPolygonNormals(mesh, pose.positions, weld, pose.facing);
        normalize(pose.facing);
    }
}

// A mesh that stands at one pose (two equal keys).
Mesh standingMesh(const Mesh& mesh, const Pose& pose) {
    Mesh out = mesh;
    out.numKeys = 2;
    out.interpolation = MotionInterpolation::PiecewiseLinear;
    out.positions = pose.positions;
    out.positions.insert(out.positions.end(), pose.positions.begin(), pose.positions.end());
    if (mesh.hasNormals()) {
        out.normals = pose.normals;
        out.normals.insert(out.normals.end(), pose.normals.begin(), pose.normals.end());
    }
    return out;
}

bool isSameEdge(const ShellEdge& a, const ShellEdge& b) { return a.positions == b.positions; }

// One mesh's strips as a mesh of quads (two triangles each, wound to face along the recorded
// normals), or an empty mesh.
Mesh shellMesh(const Mesh& source, const std::vector<ShellStrip>& strips, std::uint32_t material) {
    Mesh mesh;
    mesh.name = source.name + " shell";
    mesh.material = material;
    mesh.numKeys = 2;
    std::vector<glm::vec3> positions, normals;
    for (const ShellStrip& strip : strips) {
        const auto base = std::uint32_t(positions.size());
        for (std::size_t e = 0; e < strip.edges.size(); ++e) {
            const ShellEdge& edge = strip.edges[e];
            for (int k = 0; k < 2; ++k) {
                positions.push_back(edge.positions[k]);
                normals.push_back(edge.normals[k]);
                if (source.hasUvs()) mesh.uvs.push_back(source.uvs[edge.vertices[k]]);
                mesh.colors.push_back(source.color(edge.vertices[k]) * glm::vec4(1.0f, 1.0f, 1.0f, strip.alphas[e]));
            }
        }
        for (std::uint32_t e = 0; e + 1 < strip.edges.size(); ++e) {
            if (isSameEdge(strip.edges[e], strip.edges[e + 1])) continue;  // no area: the mesh edge at its last update
            const std::uint32_t a0 = base + 2 * e, a1 = a0 + 1, b0 = a0 + 2, b1 = a0 + 3;
            const glm::vec3 faceNormal = glm::cross(positions[a1] - positions[a0], positions[b1] - positions[a0]);
            const glm::vec3 recorded = normals[a0] + normals[a1] + normals[b0] + normals[b1];
            if (glm::dot(faceNormal, recorded) >= 0.0f) {
                mesh.triangles.push_back({a0, a1, b1});
                mesh.triangles.push_back({a0, b1, b0});
            } else {
                mesh.triangles.push_back({a0, b1, a1});
                mesh.triangles.push_back({a0, b0, b1});
            }
        }
    }
    mesh.positions = positions;
    mesh.positions.insert(mesh.positions.end(), positions.begin(), positions.end());
    mesh.normals = normals;
    mesh.normals.insert(mesh.normals.end(), normals.begin(), normals.end());
    return mesh;
}

}  // namespace

BlurShell buildBlurShell(const Scene& scene, const BlurShellOptions& options) {
    const int s = options.subdivisions;
    BlurShell shell;
    shell.strips.resize(scene.meshes.size());
    double edgesOverUpdates = 0.0;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (mesh.isStatic()) continue;  // no SoM
        auto start = Clock::now();
        SilhouetteOfMotion som(mesh.triangles, s);
        Pose previous, current;
        poseAt(mesh, 0, s, previous);
        const std::vector<std::uint32_t> weld = options.isFacingWelded ? weldedVertices(previous.positions) : std::vector<std::uint32_t>{};
        for (int i = 1; i <= s; ++i) {
            poseAt(mesh, i, s, current, weld);
            const std::size_t edges = som.update(previous.positions, current.positions, current.facing, current.normals);
            edgesOverUpdates += double(edges);
            if (i == s) shell.silhouetteEdges += edges;
            std::swap(previous, current);
        }
        shell.silhouetteSeconds += secondsSince(start);
        start = Clock::now();
        // `previous` now holds the last update's pose: shutter close.
        som.appendStrips(previous.positions, previous.normals, options.alpha, options.fade, shell.strips[m]);
        for (const ShellStrip& strip : shell.strips[m])
            for (std::size_t e = 0; e + 1 < strip.edges.size(); ++e)
                if (!isSameEdge(strip.edges[e], strip.edges[e + 1])) shell.numTriangles += 2;
        shell.numStrips += shell.strips[m].size();
        shell.buildSeconds += secondsSince(start);
    }
    shell.meanSilhouetteEdges = edgesOverUpdates / double(s);
    return shell;
}

ShellScene makeShellScene(const Scene& scene, const BlurShell& shell) {
    if (shell.strips.size() != scene.meshes.size()) throw Error("blur shell: built for another scene");
    ShellScene out;
    Scene& at = out.scene;
    at.name = scene.name + " blur shell";
    at.materials = scene.materials;
    at.textures = scene.textures;
    at.light = scene.light;
    at.background = scene.background;
    at.camera = scene.camera;
    at.camera.open = scene.camera.close;
    Pose pose;
    for (const Mesh& mesh : scene.meshes) {
        poseAt(mesh, 1, 1, pose);  // shutter close
        at.meshes.push_back(standingMesh(mesh, pose));
    }
    validateScene(at);  // the close pose may leave triangles of no area
    out.firstShellMesh = at.meshes.size();
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        if (shell.strips[m].empty()) continue;
        Material material = scene.materials[scene.meshes[m].material];
        material.name += " shell";
        material.alphaMode = AlphaMode::Blend;
        material.doubleSided = true;
        at.materials.push_back(material);
        at.meshes.push_back(shellMesh(scene.meshes[m], shell.strips[m], std::uint32_t(at.materials.size() - 1)));
    }
    validateScene(at);
    return out;
}

}  // namespace streak

namespace streak {

ShellScene buildShellScene(const Scene& scene, const BlurShellOptions& options, RenderStats& stats) {
    if (!scene.shutter.isBox())
        throw Error("blur-shell draws a trail, not a shutter average: a shutter curve or rolling shutter does not apply to it");
    const BlurShell shell = buildBlurShell(scene, options);
    stats.addTime("silhouette", shell.silhouetteSeconds);
    stats.addTime("shell build", shell.buildSeconds);
    ShellScene out;
    {
        PhaseTimer timer(stats, "shell scene");
        out = makeShellScene(scene, shell);
    }
    stats.setCounter("subdivisions", options.subdivisions);
    stats.setCounter("silhouette_edges", double(shell.silhouetteEdges));
    stats.setCounter("silhouette_edges_per_update", shell.meanSilhouetteEdges);
    stats.setCounter("shell_strips", double(shell.numStrips));
    stats.setCounter("shell_triangles", double(out.numShellTriangles()));
    return out;
}

}  // namespace streak
