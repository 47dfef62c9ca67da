#pragma once

// A scene streak renders: meshes moving over the shutter t in [0, 1] as key poses, their
// materials and textures, the camera at shutter open and close, and how the shutter is exposed.
// Made from the user's arrays, or loaded from a built-in scene or a glTF 2.0 file.

#include "streak/error.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
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
    std::string name;  ///< the Cryptomatte material name; empty: "material I"
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
    std::string name;  ///< the Cryptomatte object name; empty: "mesh I"
};

// How the shutter is exposed (README, "The shutter"): the curve's name (box, triangle,
// trapezoid:A or T0:W0,T1:W1,...) and the rolling duration D in (0, 1] (1: global).
struct Shutter {
    std::string curve = "box";
    float rollingDuration = 1.0f;
};

// The stretch of animation a trail method (blur-shell) shows instead of a shutter:
// lengthSeconds ending at the frame, sampled at `keys` evenly spaced poses (Renderer::trail()).
struct Trail {
    double lengthSeconds = 0.2;
    int keys = 11;
};

// An explicit camera for a glTF scene, posed by look-at at shutter open and (optionally
// elsewhere) at close.
struct LookAt {
    std::array<float, 3> position{0.0f, 0.0f, 1.0f};
    std::array<float, 3> target{0.0f, 0.0f, 0.0f};
    std::array<float, 3> up{0.0f, 1.0f, 0.0f};
    std::optional<std::array<float, 3>> positionEnd;  ///< at shutter close; default: position
    std::optional<std::array<float, 3>> targetEnd;    ///< at shutter close; default: target
    float verticalFovDegrees = 45.0f;
};

// How a scene is loaded. The glTF fields (time in animation frames, motion sampling, camera)
// are those of the command line's flags of the same names, and are ignored for built-in scenes.
struct LoadOptions {
    double frame = 0.0;                     ///< --frame: the frame the shutter sits at
    double shutterFrames = 0.5;             ///< --shutter: frames it stays open
    double fps = 24.0;                      ///< --fps
    std::string animation;                  ///< --animation: name or index; empty: the first
    std::string shutterPosition = "start";  ///< --shutter-position: start, center or end
    int motionKeys = 0;                     ///< --motion-keys: 2 to 256; 0: as many as --key-tolerance needs
    std::string motionCurve = "linear";     ///< --motion-curve: linear or bezier (3 or 4 keys, or pieces chosen)
    int motionCurveOrder = 2;               ///< --motion-curve-order: the degree of chosen Bezier pieces, 2 or 3
    int motionFitSamples = -1;              ///< --motion-fit-samples: -1: 4 (K - 1) + 1; 0: the curve through the keys
    double keyTolerancePixels = 0.125;      ///< --key-tolerance
    std::optional<int> camera;              ///< --camera: a glTF camera by index
    std::optional<LookAt> lookAt;           ///< --camera-pos etc.: an explicit camera instead
    int width = 1024, height = 768;         ///< the image the scene is framed for (aspect, key tolerance)
    // --point-cache: a PC2 or MDD file (Blender's Mesh Cache formats) that moves one mesh of a
    // glTF scene: the vertices of its triangle primitives, in order, take the cache's points in
    // place of its skin and morph targets; PC2's frames count at fps from its start frame, MDD's
    // times are seconds. The mesh is named by its node's or its own name (--point-cache-mesh;
    // empty: the scene's only mesh); the points lie in its node's space ("object": the node's
    // animated transform places them) or in world space ("world"). They follow the glTF's
    // vertex order, its primitives' POSITION arrays one after another.
    std::string pointCache;
    std::string pointCacheMesh;
    std::string pointCacheSpace = "object";
    // --velocity-unit: velocity attributes (glTF _VELOCITY, PLY vx vy vz) move their vertices from
    // where they are at the frame, in metres per "second" or per "frame".
    std::string velocityUnit = "second";
    // --sequence-interpolate: an OBJ/PLY sequence's files are interpolated even where their
    // triangles differ, and files of differing vertex counts are an Error rather than held.
    bool sequenceInterpolate = false;
    // Every scene: how the shutter is exposed (Scene::withShutter changes it later), and the
    // background colour (linear RGB) instead of the scene's own.
    Shutter shutter;
    std::optional<std::array<float, 3>> background;
    // A trail method's trail (Renderer::trail()): a glTF scene is loaded over [T - length, T],
    // T = frame / fps, with its keys (shutterFrames, shutterPosition and motionKeys do not
    // apply); a built-in scene's shutter is its trail.
    std::optional<Trail> trail;
};

// A built-in scene: `builtin:NAME[?key=value&...]`.
struct SceneInfo {
    std::string name;
    std::string description;
};
std::vector<SceneInfo> builtinScenes();

// Whether a scene spec names a glTF file (.gltf, .glb) rather than a built-in scene.
bool isGltfFile(const std::string& spec);
// Whether a scene spec names a scene file with a clock, which takes the glTF load options: glTF,
// or an OBJ or PLY mesh or numbered sequence (`fluid_%04d.ply`: frame N is file N).
bool isSceneFile(const std::string& spec);

// A frame pattern's path for one frame: its %d or %0Nd (`out_%04d.png`, `fluid_%04d.ply`)
// replaced by the frame number, %% by a %. hasNumber says whether it has one; without, the
// pattern is the one path. Throws Error for another conversion or more than one number.
std::string framePatternPath(const std::string& pattern, long frame, bool& hasNumber);

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

    // A scene made from arrays, with what the vector pass (RenderSettings::passes "vector")
    // needs, which a file's scene loads itself: each mesh given to fromArrays standing still at
    // the frame before the shutter's, at it and after it (framePositions[i]: 3 x V x 3 floats,
    // the frames in that order, V its vertices), and the camera at each (`open` is used).
    // Throws Error for a scene not made from arrays or arrays of the wrong size.
    Scene withFrames(const std::vector<std::vector<float>>& framePositions, const std::array<Camera, 3>& frameCameras) const;

    // Writes the scene as glTF 2.0: binary (.glb) or text with its buffer inlined (.gltf). Key
    // poses become morph targets under a LINEAR weights animation one-hot at k/(K-1) seconds, so
    // --frame 0 --shutter 24 --fps 24 renders it as streak does.
    void writeGltf(const std::string& path) const;

    std::size_t numTriangles() const;
    std::size_t skippedTriangles() const;

    struct Impl;
    const Impl& impl() const { return *m_impl; }

private:
    explicit Scene(std::shared_ptr<const Impl> impl) : m_impl(std::move(impl)) {}
    std::shared_ptr<const Impl> m_impl;
};

}  // namespace streak::api
