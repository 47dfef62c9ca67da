#pragma once

// streak's public API: analytic motion blur of moving and deforming triangle meshes.
//
//   streak::api::Scene scene = streak::api::Scene::load("builtin:cubes");
//   streak::api::RenderSettings settings;
//   settings.method = "analytic";
//   streak::api::Image image = streak::api::render(scene, settings).image;
//   streak::api::writeImage(image, "cubes.png");
//
// Everything is in linear light; the shutter interval is t in [0, 1]. Every function throws
// streak::Error (one line naming the problem) for bad input and never exits.

#include "streak/error.h"

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace streak::api {

// A camera pose: where it is, what it looks at, which way is up (world space).
struct CameraPose {
    std::array<float, 3> position{0.0f, 0.0f, 5.0f};
    std::array<float, 3> target{0.0f, 0.0f, 0.0f};
    std::array<float, 3> up{0.0f, 1.0f, 0.0f};
};

// A pinhole camera posed at shutter open and close; it moves between them (position linearly,
// rotation by slerp).
struct Camera {
    CameraPose open;
    CameraPose close = open;
    float verticalFovDegrees = 45.0f;
    float zNear = 0.05f;
};

// A texture: width x height texels, row-major, top row first, RGBA. Either 8-bit sRGB colour
// (rgba8, alpha linear) or linear float (rgbaFloat); exactly one is filled. Repeat wrapping.
struct Texture {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba8;
    std::vector<float> rgbaFloat;
};

// A material: base colour (times the texture), opacity (below 1: blended), double-sidedness
// (false: back faces culled) and Phong's specular weight and exponent.
struct Material {
    std::array<float, 3> baseColor{1.0f, 1.0f, 1.0f};
    int texture = -1;  ///< index into the scene's textures, or -1
    float opacity = 1.0f;
    bool doubleSided = false;
    float specular = 0.2f;
    float shininess = 32.0f;
};

// A triangle mesh moving over the shutter as `keys` key poses (keys >= 2, evenly spaced in
// t, vertices moving linearly between them). positions: keys x vertices x 3 floats, key-major;
// normals: empty (faceted) or the same size; uvs: empty or vertices x 2; indices: 3 per
// triangle, counter-clockwise seen from the front.
struct Mesh {
    int keys = 2;
    std::vector<float> positions;
    std::vector<float> normals;
    std::vector<float> uvs;
    std::vector<std::uint32_t> indices;
    int material = 0;  ///< index into the scene's materials
};

// How the shutter is exposed (README, "The shutter"): the curve's name (box, triangle,
// trapezoid:A or T0:W0,T1:W1,...) and the rolling duration D in (0, 1] (1: global).
struct Shutter {
    std::string curve = "box";
    float rollingDuration = 1.0f;
};

// How a glTF file's animation becomes the shutter (ignored for built-in scenes): frames, as on
// the command line (--frame, --shutter, --fps, --animation, --shutter-position).
struct LoadOptions {
    double frame = 0.0;
    double shutterFrames = 0.5;
    double fps = 24.0;
    std::string animation;               ///< name or index; empty: the first
    std::string shutterPosition = "start";  ///< start, center or end
    int width = 1024, height = 768;      ///< the image the scene is framed for (aspect, key tolerance)
};

// Scene is a validated scene, shared cheaply between copies (immutable once made).
class Scene {
public:
    // "builtin:NAME[?key=value&...]" or a .gltf / .glb file.
    static Scene load(const std::string& spec, const LoadOptions& options = {});
    // The user's own meshes. Arrays are checked (sizes, indices in range, finite numbers);
    // degenerate triangles are skipped and counted (skippedTriangles()).
    static Scene fromArrays(const std::vector<Mesh>& meshes, const std::vector<Material>& materials, const Camera& camera,
                            const std::vector<Texture>& textures = {}, std::array<float, 3> background = {0.0f, 0.0f, 0.0f});

    // The same scene under another shutter.
    Scene withShutter(const Shutter& shutter) const;

    std::size_t numTriangles() const;
    std::size_t skippedTriangles() const;

    struct Impl;
    const Impl& impl() const { return *m_impl; }

private:
    explicit Scene(std::shared_ptr<const Impl> impl) : m_impl(std::move(impl)) {}
    std::shared_ptr<const Impl> m_impl;
};

// A method streak renders with (`streak methods`).
struct Method {
    std::string name;
    std::string description;
};
std::vector<Method> methods();

// How to render: the method by name and its options (as --option KEY=VALUE: samples,
// max-intervals, ...), the image size, N x N anti-aliasing, Phong or unlit shading, the seed.
struct RenderSettings {
    std::string method = "motion-path";
    std::map<std::string, std::string> options;
    int width = 1024, height = 768;
    int aa = 1;
    bool unlit = false;
    std::uint64_t seed = 0;
};

// A linear-light RGB float image: width x height x 3 floats, row-major, top row first.
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;
    float at(int x, int y, int channel) const { return rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3 + std::size_t(channel)]; }
};

// The image and the render's figures: {"info": {...}, "time_ms": {...}, "counters": {...}},
// the JSON the command line's --stats writes.
struct RenderResult {
    Image image;
    std::string statsJson;
};

RenderResult render(const Scene& scene, const RenderSettings& settings);

// PNG (sRGB 8-bit) or EXR (linear float) by the extension; a failed write leaves nothing.
void writeImage(const Image& image, const std::string& path);
Image readImage(const std::string& path);

// PSNR (dB) and SSIM of two images of one size, in display space (as `streak compare`).
struct Comparison {
    double psnr = 0.0;
    double ssim = 0.0;
};
Comparison compare(const Image& a, const Image& b);

}  // namespace streak::api
