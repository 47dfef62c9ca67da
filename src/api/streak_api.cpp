// The public API (include/streak/streak.h) over the layers: scene loading and building, the
// method registry, rendering, image files. Inside namespace streak::api the public types
// shadow the layers' own of the same name; the layers' are written streak::X.

#include "streak/streak.h"

#include "image/image_io.h"
#include "image/metrics.h"
#include "methods/registry.h"
#include "scene/scene_loader.h"
#include "scene/shutter.h"

#include <glm/trigonometric.hpp>

#include <cmath>
#include <string>

namespace streak::api {

struct Scene::Impl {
    streak::Scene scene;
    SceneCleanup cleanup;
};

namespace {

glm::vec3 vec3(const std::array<float, 3>& v) { return {v[0], v[1], v[2]}; }

streak::CameraPose poseOf(const CameraPose& p, const std::string& which) {
    for (const auto* v : {&p.position, &p.target, &p.up})
        for (float x : *v)
            if (!std::isfinite(x)) throw Error("camera " + which + ": a position, target or up is not finite");
    if (vec3(p.position) == vec3(p.target)) throw Error("camera " + which + ": position and target are the same point");
    return streak::CameraPose::lookAt(vec3(p.position), vec3(p.target), vec3(p.up));
}

bool allFinite(const std::vector<float>& values) {
    for (float v : values)
        if (!std::isfinite(v)) return false;
    return true;
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
    mesh.name = where;
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

Image imageOf(const streak::Image& in) {
    Image out;
    out.width = in.width(), out.height = in.height();
    out.rgb.reserve(std::size_t(in.width()) * std::size_t(in.height()) * 3);
    for (const glm::vec3& p : in.pixels()) out.rgb.insert(out.rgb.end(), {p.x, p.y, p.z});
    return out;
}

streak::Image imageOf(const Image& in) {
    if (in.width <= 0 || in.height <= 0 || in.rgb.size() != std::size_t(in.width) * std::size_t(in.height) * 3)
        throw Error("image: rgb must be width x height x 3 floats");
    streak::Image out(in.width, in.height);
    for (std::size_t i = 0; i < out.pixels().size(); ++i) out.pixels()[i] = {in.rgb[3 * i], in.rgb[3 * i + 1], in.rgb[3 * i + 2]};
    return out;
}

}  // namespace

Scene Scene::load(const std::string& spec, const LoadOptions& options) {
    if (options.width <= 0 || options.height <= 0) throw Error("load options: width and height must be positive");
    GltfOptions gltf;
    gltf.shutter = options.shutterFrames;
    gltf.frame = shutterOpenFrame(parseShutterPosition(options.shutterPosition), options.frame, options.shutterFrames);
    gltf.fps = options.fps;
    gltf.animation = options.animation;
    gltf.imageHeight = options.height;
    gltf.aspect = float(options.width) / float(options.height);
    auto impl = std::make_shared<Impl>();
    impl->scene = loadScene(spec, gltf);
    impl->cleanup = validateScene(impl->scene);
    return Scene(std::move(impl));
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
        scene.materials.push_back(m);
    }
    for (std::size_t i = 0; i < meshes.size(); ++i) scene.meshes.push_back(meshOf(meshes[i], i, materials.size()));
    if (!(camera.verticalFovDegrees > 0.0f && camera.verticalFovDegrees < 180.0f) || !(camera.zNear > 0.0f))
        throw Error("camera: the field of view must be in (0, 180) degrees and zNear positive");
    scene.camera.open = poseOf(camera.open, "open");
    scene.camera.close = poseOf(camera.close, "close");
    scene.camera.verticalFov = glm::radians(camera.verticalFovDegrees);
    scene.camera.zNear = camera.zNear;
    scene.background = vec3(background);
    impl->cleanup = validateScene(scene);
    return Scene(std::move(impl));
}

Scene Scene::withShutter(const Shutter& shutter) const {
    auto impl = std::make_shared<Impl>(*m_impl);
    impl->scene.shutter.curve = ShutterCurve::parse(shutter.curve);
    impl->scene.shutter.rollingDuration = checkRollingDuration(shutter.rollingDuration);
    return Scene(std::move(impl));
}

std::size_t Scene::numTriangles() const { return m_impl->scene.numTriangles(); }
std::size_t Scene::skippedTriangles() const { return m_impl->cleanup.numSkipped(); }

std::vector<Method> methods() {
    std::vector<Method> out;
    for (const MethodInfo& info : registeredMethods()) out.push_back({std::string(info.name), std::string(info.description)});
    return out;
}

RenderResult render(const Scene& scene, const RenderSettings& settings) {
    if (settings.width <= 0 || settings.height <= 0) throw Error("render: width and height must be positive");
    if (settings.aa < 1 || settings.aa > 16) throw Error("render: aa must be in [1, 16], got " + std::to_string(settings.aa));
    OptionMap options;
    for (const auto& [key, value] : settings.options) options.set(key, value);
    std::unique_ptr<Renderer> renderer = createRenderer(settings.method, options);
    if (renderer->animationTrail()) throw Error("method " + settings.method + " draws a trail: render it with the command line, which loads the trail");
    streak::RenderSettings s;
    s.width = settings.width, s.height = settings.height, s.aa = settings.aa;
    s.shading = settings.unlit ? ShadingMode::Unlit : ShadingMode::Phong;
    s.seed = settings.seed;
    RenderStats stats;
    RenderContext context{stats};
    RenderResult result;
    {
        PhaseTimer timer(stats, "render");
        result.image = imageOf(renderer->render(scene.impl().scene, s, context));
    }
    stats.setInfo("method", settings.method);
    stats.setCounter("triangles", double(scene.numTriangles()));
    stats.setCounter("skipped_triangles", double(scene.skippedTriangles()));
    result.statsJson = stats.toJson();
    return result;
}

void writeImage(const Image& image, const std::string& path) { streak::writeImage(imageOf(image), path); }
Image readImage(const std::string& path) { return imageOf(streak::readImage(path)); }

Comparison compare(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) throw Error("compare: the images' sizes differ");
    const streak::Image x = imageOf(a), y = imageOf(b);
    return {psnr(x, y), ssim(x, y)};
}

}  // namespace streak::api
