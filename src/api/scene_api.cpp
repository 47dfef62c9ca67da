// Scenes through the public API: loaded (built-in or glTF, with every loading option the command
// line has), built from the user's arrays, re-exposed, written as glTF.

#include "api/api_internal.h"

#include "scene/builtin_scenes.h"
#include "scene/gltf_writer.h"
#include "scene/frame_pattern.h"
#include "scene/scene_loader.h"
#include "scene/shutter.h"
#include "util/file_io.h"

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>

namespace streak::api {

namespace {

streak::CameraPose poseOf(const CameraPose& p, const std::string& which) {
    for (const auto* v : {&p.position, &p.target, &p.up})
        for (float x : *v)
            if (!std::isfinite(x)) throw Error("camera " + which + ": a position, target or up is not finite");
    if (vec3(p.position) == vec3(p.target)) throw Error("camera " + which + ": position and target are the same point");
    return streak::CameraPose::lookAt(vec3(p.position), vec3(p.target), vec3(p.up));
}

bool allFinite(const std::vector<float>& values) {
    return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

// The scene camera of an API camera (`where` names it in errors): moving from its open to its
// close pose, or held at its open pose.
streak::Camera cameraOf(const Camera& in, const std::string& where, bool isMoving) {
    if (!(in.verticalFovDegrees > 0.0f && in.verticalFovDegrees < 180.0f) || !(in.zNear > 0.0f))
        throw Error(where + ": the field of view must be in (0, 180) degrees and zNear positive");
    streak::Camera out;
    out.open = poseOf(in.open, "open");
    out.close = isMoving ? poseOf(in.close, "close") : out.open;
    out.verticalFov = glm::radians(in.verticalFovDegrees);
    out.zNear = in.zNear;
    return out;
}

streak::Mesh meshOf(const Mesh& in, std::size_t index, std::size_t numMaterials) {
    const std::string where = "mesh " + std::to_string(index);
    if (in.keys < 2) throw Error(where + ": needs at least 2 key poses, got " + std::to_string(in.keys));
    if (in.positions.empty() || in.positions.size() % (3 * std::size_t(in.keys)) != 0)
        throw Error(where + ": positions must be keys x vertices x 3 floats, got " + std::to_string(in.positions.size()) + " for " +
                    std::to_string(in.keys) + " keys");
    const std::size_t n = in.positions.size() / (3 * std::size_t(in.keys));
    if (!in.normals.empty() && in.normals.size() != in.positions.size()) throw Error(where + ": normals must be empty or match positions");
    if (!in.uvs.empty() && in.uvs.size() != 2 * n) throw Error(where + ": uvs must be empty or vertices x 2 floats");
    if (in.indices.empty() || in.indices.size() % 3 != 0) throw Error(where + ": indices must be 3 per triangle, got " + std::to_string(in.indices.size()));
    if (!allFinite(in.positions) || !allFinite(in.normals) || !allFinite(in.uvs))
        throw Error(where + ": positions, normals and uvs must be finite (a NaN or Inf is in them)");
    for (std::uint32_t i : in.indices)
        if (i >= n) throw Error(where + ": index " + std::to_string(i) + " is out of range (" + std::to_string(n) + " vertices)");
    if (in.material < 0 || std::size_t(in.material) >= numMaterials)
        throw Error(where + ": material " + std::to_string(in.material) + " does not exist");
    streak::Mesh mesh;
    mesh.name = in.name.empty() ? where : in.name;
    mesh.numKeys = in.keys;
    mesh.material = std::uint32_t(in.material);
    for (std::size_t i = 0; i < in.positions.size(); i += 3) mesh.positions.emplace_back(in.positions[i], in.positions[i + 1], in.positions[i + 2]);
    for (std::size_t i = 0; i < in.normals.size(); i += 3) mesh.normals.emplace_back(in.normals[i], in.normals[i + 1], in.normals[i + 2]);
    for (std::size_t i = 0; i < in.uvs.size(); i += 2) mesh.uvs.emplace_back(in.uvs[i], in.uvs[i + 1]);
    for (std::size_t i = 0; i < in.indices.size(); i += 3) mesh.triangles.emplace_back(in.indices[i], in.indices[i + 1], in.indices[i + 2]);
    return mesh;
}

streak::Texture textureOf(const Texture& in, std::size_t index) {
    const std::string where = "texture " + std::to_string(index);
    if (in.width <= 0 || in.height <= 0) throw Error(where + ": width and height must be positive");
    const std::size_t texels = std::size_t(in.width) * std::size_t(in.height);
    if (in.rgba8.empty() == in.rgbaFloat.empty()) throw Error(where + ": give exactly one of rgba8 and rgbaFloat");
    if (!in.rgba8.empty()) {
        if (in.rgba8.size() != 4 * texels) throw Error(where + ": rgba8 must be width x height x 4 bytes");
        return streak::Texture::fromSrgb8(in.width, in.height, in.rgba8);
    }
    if (in.rgbaFloat.size() != 4 * texels) throw Error(where + ": rgbaFloat must be width x height x 4 floats");
    if (!allFinite(in.rgbaFloat)) throw Error(where + ": rgbaFloat must be finite");
    std::vector<glm::vec4> linear(texels);
    for (std::size_t i = 0; i < texels; ++i) linear[i] = {in.rgbaFloat[4 * i], in.rgbaFloat[4 * i + 1], in.rgbaFloat[4 * i + 2], in.rgbaFloat[4 * i + 3]};
    return streak::Texture::fromLinear(in.width, in.height, std::move(linear));
}

streak::Shutter shutterOf(const Shutter& in) {
    streak::Shutter shutter;
    shutter.curve = ShutterCurve::parse(in.curve);
    shutter.rollingDuration = checkRollingDuration(in.rollingDuration);
    return shutter;
}

glm::vec3 backgroundOf(const std::array<float, 3>& c) {
    for (float x : c)
        if (!(std::isfinite(x) && x >= 0.0f)) throw Error("background must be three non-negative finite numbers r,g,b");
    return vec3(c);
}

// The glTF loader's options from the public ones (everything but the frame, which depends on the
// shutter position or the trail).
GltfOptions gltfOptionsOf(const LoadOptions& o) {
    GltfOptions gltf;
    gltf.shutter = o.shutterFrames;
    gltf.fps = o.fps;
    gltf.animation = o.animation;
    gltf.motionKeys = o.motionKeys;
    if (o.motionCurve == "bezier") gltf.motionCurve = MotionInterpolation::Bezier;
    else if (o.motionCurve != "linear") throw Error("motion curve must be linear or bezier, got '" + o.motionCurve + "'");
    if (o.motionFitSamples < -1) throw Error("motion fit samples must be 0 or more (-1: the default), got " + std::to_string(o.motionFitSamples));
    gltf.motionFitSamples = o.motionFitSamples;
    if (o.motionCurveOrder != LoadOptions().motionCurveOrder && (gltf.motionCurve != MotionInterpolation::Bezier || o.motionKeys != 0))
        throw Error("motion curve order applies to Bezier pieces chosen without motion keys (motion curve bezier, motion keys 0)");
    gltf.bezierOrder = o.motionCurveOrder;
    gltf.keyTolerancePixels = o.keyTolerancePixels;
    gltf.imageHeight = o.height;
    gltf.aspect = float(o.width) / float(o.height);
    gltf.camera = o.camera;
    if (o.pointCacheSpace != "object" && o.pointCacheSpace != "world")
        throw Error("point cache space must be object or world, got '" + o.pointCacheSpace + "'");
    if (o.velocityUnit != "second" && o.velocityUnit != "frame") throw Error("velocity unit must be second or frame, got '" + o.velocityUnit + "'");
    gltf.isVelocityPerFrame = o.velocityUnit == "frame";
    gltf.isSequenceInterpolated = o.sequenceInterpolate;
    if (!o.pointCache.empty()) gltf.pointCache = GltfPointCache{o.pointCache, o.pointCacheMesh, o.pointCacheSpace == "world"};
    else if (!o.pointCacheMesh.empty() || o.pointCacheSpace != "object") throw Error("point cache mesh and space need a point cache");
    if (o.lookAt) {
        GltfLookAt look;
        look.position = vec3(o.lookAt->position);
        look.target = vec3(o.lookAt->target);
        look.up = vec3(o.lookAt->up);
        if (o.lookAt->positionEnd) look.positionEnd = vec3(*o.lookAt->positionEnd);
        if (o.lookAt->targetEnd) look.targetEnd = vec3(*o.lookAt->targetEnd);
        look.verticalFovDegrees = o.lookAt->verticalFovDegrees;
        gltf.lookAt = look;
    }
    return gltf;
}

// A trail over [T - length, T], T = frame / fps, with one key pose per trail key. The animation
// holds its first pose before it starts, so a trail reaching back past 0 s moves only from there
// (trail_before_start_seconds).
void applyTrail(const Trail& trail, GltfOptions& gltf, double frame, RenderStats& stats) {
    if (!(trail.lengthSeconds > 0.0 && std::isfinite(trail.lengthSeconds)) || trail.keys < 2)
        throw Error("a trail needs a positive length and at least 2 keys");
    const double end = frame / gltf.fps;
    gltf.frame = frame - trail.lengthSeconds * gltf.fps;
    gltf.shutter = trail.lengthSeconds * gltf.fps;
    gltf.motionKeys = trail.keys;
    gltf.velocityFrame = frame;  // velocities move vertices from where they are at T
    stats.setInfo("trail", numberList({end - trail.lengthSeconds, end}) + " s");
    stats.setCounter("trail_before_start_seconds", std::max(0.0, trail.lengthSeconds - end));
}

}  // namespace

std::vector<SceneInfo> builtinScenes() {
    std::vector<SceneInfo> out;
    for (const BuiltinSceneInfo& info : streak::builtinScenes()) out.push_back({std::string(info.name), std::string(info.description)});
    return out;
}

bool isGltfFile(const std::string& spec) { return isGltfSpec(spec); }
bool isSceneFile(const std::string& spec) { return isSceneFileSpec(spec); }
std::string framePatternPath(const std::string& pattern, long frame, bool& hasNumber) { return streak::framePatternPath(pattern, frame, hasNumber); }

Scene Scene::load(const std::string& spec, const LoadOptions& options) {
    if (options.width <= 0 || options.height <= 0) throw Error("load options: width and height must be positive");
    auto impl = std::make_shared<Impl>();
    impl->spec = spec;
    impl->isGltf = isSceneFileSpec(spec);  // glTF, or a mesh or sequence loaded as one
    if (!options.pointCache.empty() && !impl->isGltf) throw Error("a point cache applies to scene files (glTF, OBJ, PLY) only");
    GltfOptions gltf = gltfOptionsOf(options);
    const ShutterPosition position = parseShutterPosition(options.shutterPosition);
    impl->shutterPosition = shutterPositionName(position);
    const streak::Shutter shutter = shutterOf(options.shutter);
    RenderStats& stats = impl->loadStats;
    if (options.trail && impl->isGltf) {
        applyTrail(*options.trail, gltf, options.frame, stats);
        impl->trail = options.trail;
    } else {
        if (options.trail) stats.setInfo("trail", "the built-in scene's shutter");
        gltf.frame = shutterOpenFrame(position, options.frame, options.shutterFrames);
        gltf.velocityFrame = options.frame;  // velocities move vertices from where they are at the frame
    }
    if (impl->isGltf) impl->loadOptions = options;
    {
        PhaseTimer timer(stats, "load");
        impl->scene = loadScene(spec, gltf, &stats);
        if (options.background) impl->scene.background = backgroundOf(*options.background);
        impl->scene.shutter = shutter;
        impl->cleanup = validateScene(impl->scene);
    }
    return Impl::wrap(std::move(impl));
}

Scene Scene::fromArrays(const std::vector<Mesh>& meshes, const std::vector<Material>& materials, const Camera& camera,
                        const std::vector<Texture>& textures, std::array<float, 3> background) {
    auto impl = std::make_shared<Impl>();
    streak::Scene& scene = impl->scene;
    scene.name = "arrays";
    if (meshes.empty()) throw Error("scene: needs at least one mesh");
    for (std::size_t i = 0; i < textures.size(); ++i) scene.textures.push_back(textureOf(textures[i], i));
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const Material& in = materials[i];
        if (in.texture >= int(textures.size())) throw Error("material " + std::to_string(i) + ": texture " + std::to_string(in.texture) + " does not exist");
        streak::Material m;
        m.baseColor = vec3(in.baseColor);
        m.baseColorTexture = in.texture < 0 ? -1 : in.texture;
        m.opacity = in.opacity;
        m.doubleSided = in.doubleSided;
        m.specular = in.specular;
        m.shininess = in.shininess;
        m.name = in.name.empty() ? "material " + std::to_string(i) : in.name;
        scene.materials.push_back(m);
    }
    for (std::size_t i = 0; i < meshes.size(); ++i) scene.meshes.push_back(meshOf(meshes[i], i, materials.size()));
    scene.camera = cameraOf(camera, "camera", /*isMoving=*/true);
    scene.background = backgroundOf(background);
    impl->cleanup = validateScene(scene);
    impl->numArrayMeshes = meshes.size();
    return Impl::wrap(std::move(impl));
}

Scene Scene::withFrames(const std::vector<std::vector<float>>& framePositions, const std::array<Camera, 3>& frameCameras) const {
    if (m_impl->numArrayMeshes == 0) throw Error("withFrames: the scene is not made from arrays (" + m_impl->spec + " loads its own frames)");
    if (framePositions.size() != m_impl->numArrayMeshes)
        throw Error("withFrames: " + std::to_string(framePositions.size()) + " meshes' frames for a scene of " +
                    std::to_string(m_impl->numArrayMeshes) + " meshes");
    auto impl = std::make_shared<Impl>(*m_impl);
    Impl::ArrayFrames frames;
    const std::vector<std::size_t>& kept = m_impl->cleanup.keptMeshes;
    for (std::size_t m = 0; m < kept.size(); ++m) {
        const std::vector<float>& in = framePositions[kept[m]];
        const std::size_t n = m_impl->scene.meshes[m].numVertices();
        if (in.size() != 3 * n * 3)
            throw Error("withFrames: mesh " + std::to_string(kept[m]) + " needs 3 x " + std::to_string(n) + " x 3 floats (its vertices at 3 frames), got " +
                        std::to_string(in.size()));
        if (!allFinite(in))
            throw Error("withFrames: mesh " + std::to_string(kept[m]) + " has a position that is not finite");
        std::array<std::vector<glm::vec3>, 3>& out = frames.positions.emplace_back();
        for (std::size_t k = 0; k < 3; ++k)
            for (std::size_t v = 0; v < n; ++v) out[k].emplace_back(in[(k * n + v) * 3], in[(k * n + v) * 3 + 1], in[(k * n + v) * 3 + 2]);
    }
    for (std::size_t k = 0; k < 3; ++k) {
        frames.cameras[k] = cameraOf(frameCameras[k], "withFrames: camera " + std::to_string(k), /*isMoving=*/false);
    }
    impl->arrayFrames = std::move(frames);
    return Impl::wrap(std::move(impl));
}

streak::Scene Scene::Impl::withFrameMotion(float aspect) const {
    if (arrayFrames) {
        streak::Scene out = scene;
        FrameMotion motion;
        for (std::size_t m = 0; m < out.meshes.size(); ++m)
            for (std::size_t k = 0; k < 3; ++k) out.meshes[m].framePositions[k] = arrayFrames->positions[m][k];
        for (std::size_t k = 0; k < 3; ++k) motion.clipFromWorld[k] = arrayFrames->cameras[k].clipFromWorld(0.0f, aspect);
        out.frameMotion = motion;
        return out;
    }
    if (!loadOptions || trail)
        throw Error("the vector pass needs a scene with frames: a glTF, OBJ or PLY file loaded over a shutter, or arrays given theirs (Scene::withFrames; " +
                    spec + " has none)");
    const LoadOptions& main = *loadOptions;
    const double open = shutterOpenFrame(parseShutterPosition(main.shutterPosition), main.frame, main.shutterFrames);
    const bool isFramed = loadStats.info().count("camera_source") && loadStats.info().at("camera_source") == "framed";
    streak::Scene out = scene;
    FrameMotion motion;
    for (int k = 0; k < 3; ++k) {
        // The scene standing still at frame F - 1, F or F + 1, from the main load's options but
        // for the shutter and motion ones; velocities move vertices from where they are at F,
        // as the main load's do (a held file of a sequence keeps its vertices).
        LoadOptions o = main;
        o.shutterFrames = 0.0, o.motionKeys = 2, o.motionCurve = "linear";
        o.motionCurveOrder = LoadOptions().motionCurveOrder, o.motionFitSamples = LoadOptions().motionFitSamples;
        const double frame = main.frame + double(k - 1);
        if (main.lookAt && (main.lookAt->positionEnd || main.lookAt->targetEnd)) {
            // An explicit camera moving over the shutter keeps moving at its pace past it.
            const double u = main.shutterFrames > 0.0 ? (frame - open) / main.shutterFrames : 0.0;
            const LookAt& from = *main.lookAt;
            LookAt& look = *o.lookAt;
            for (int c = 0; c < 3; ++c) {
                look.position[c] += float(u) * (from.positionEnd.value_or(from.position)[c] - from.position[c]);
                look.target[c] += float(u) * (from.targetEnd.value_or(from.target)[c] - from.target[c]);
            }
            look.positionEnd.reset(), look.targetEnd.reset();
        }
        GltfOptions gltf = gltfOptionsOf(o);
        gltf.frame = frame;
        gltf.velocityFrame = main.frame;
        const streak::Scene still = loadScene(spec, gltf);
        // validateScene dropped the main scene's empty meshes (and kept the others in order, with
        // their vertices): each main mesh is the next still one of its name and vertex count. A
        // still mesh is not validated, so one scaled to nothing at F - 1 still matches.
        std::size_t next = 0;
        for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
            const streak::Mesh& mesh = scene.meshes[m];
            while (next < still.meshes.size() && (still.meshes[next].name != mesh.name || still.meshes[next].numVertices() != mesh.numVertices())) ++next;
            if (next == still.meshes.size())
                throw Error("the vector pass: mesh '" + mesh.name + "' has other vertices at frame " + numberList({frame}) + " (its topology changes)");
            const std::span<const glm::vec3> positions = still.meshes[next++].keyPositions(0);
            out.meshes[m].framePositions[std::size_t(k)].assign(positions.begin(), positions.end());
        }
        // A framed scene (no camera given) keeps the frame's framing; a camera of the file's
        // is where its animation has it at that frame.
        motion.clipFromWorld[std::size_t(k)] = (isFramed ? scene.camera : still.camera).clipFromWorld(0.0f, aspect);
    }
    out.frameMotion = motion;
    return out;
}

Scene Scene::withShutter(const Shutter& shutter) const {
    auto impl = std::make_shared<Impl>(*m_impl);
    impl->scene.shutter = shutterOf(shutter);
    return Impl::wrap(std::move(impl));
}

void Scene::writeGltf(const std::string& path) const {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".glb" && extension != ".gltf") throw Error("cannot write " + path + ": a glTF file ends in .glb or .gltf");
    std::vector<char> bytes;
    if (extension == ".gltf") {
        const std::string text = writeGltfText(m_impl->scene);
        bytes.assign(text.begin(), text.end());
    } else {
        const std::vector<std::uint8_t> binary = writeGltfBinary(m_impl->scene);
        bytes.assign(binary.begin(), binary.end());
    }
    try {
        writeFileAtomically(path, bytes);
    } catch (const std::exception& e) {
        throw Error("cannot write " + path + ": " + e.what());
    }
}

std::size_t Scene::numTriangles() const { return m_impl->scene.numTriangles(); }
std::size_t Scene::skippedTriangles() const { return m_impl->cleanup.numSkipped(); }

}  // namespace streak::api
