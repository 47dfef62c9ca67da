#pragma once

#include "scene/scene.h"
#include "util/stats.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace streak {

// An explicit camera for a glTF scene: it looks from position at target (vertical field of
// view, y up) and moves linearly to positionEnd / targetEnd over the shutter.
struct GltfLookAt {
    glm::vec3 position{0.0f, 0.0f, 1.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    std::optional<glm::vec3> positionEnd;  ///< at shutter close; default: position
    std::optional<glm::vec3> targetEnd;    ///< at shutter close; default: target
    float verticalFovDegrees = 45.0f;
};

// Caps that keep a broken or hostile file from taking unbounded memory or time; going over one
// is an Error, checked before the work it bounds.
struct GltfLimits {
    std::uint64_t maxFileBytes = 1ull << 31;        ///< the file and each external buffer or image
    std::size_t maxTexels = std::size_t(1) << 26;     ///< per decoded image
    std::size_t maxTriangles = std::size_t(1) << 26;  ///< over all instanced primitives
    // Vertices over all instanced primitives, times motion keys, times (1 + morph targets +
    // skin influence sets): the work and memory of sampling the key poses.
    std::size_t maxVertexWork = std::size_t(1) << 30;
};

// A point cache (PC2 or MDD, scene/point_cache.h) that moves one mesh of a glTF scene: its
// triangle primitives' vertices, in order, take the cache's points, in place of the mesh's skin
// and morph targets (Blender's Mesh Cache modifier). The points are in the mesh node's space,
// which the node's animated transform then places, or already in world space.
struct GltfPointCache {
    std::string path;
    std::string mesh;           ///< a node's or a mesh's name; empty: the scene's one mesh
    bool isWorldSpace = false;
};

// How to turn a glTF file into one streak scene: which stretch of which animation the shutter
// covers, how finely to sample it, and where the camera is.
struct GltfOptions {
    double frame = 0.0;         ///< the shutter opens at frame / fps seconds of animation time
    double shutter = 0.5;       ///< frames it stays open (0: no motion)
    double fps = 24.0;          ///< frames per second
    std::string animation;      ///< a name, or an index; empty: the first animation, if any
    int motionKeys = 0;         ///< key poses sampled evenly over the shutter, 2 to 256; 0: chosen
                                ///< per scene (2, 3, 5, 9...) to follow the animation on screen
    // Bezier with motionKeys 3 or 4: the keys become the control points of one curve through (or
    // fitted to) the poses; with motionKeys 0: Bezier pieces of degree bezierOrder through evenly
    // spaced poses, as many as the animation needs (1, 2, 4, 8...), chosen as linear keys are.
    MotionInterpolation motionCurve = MotionInterpolation::PiecewiseLinear;
    int bezierOrder = 2;        ///< chosen Bezier pieces: their degree, 2 or 3
    int motionFitSamples = -1;  ///< Bezier: the least-squares fit to N > motionKeys evenly spaced poses;
                                ///< -1: N = 4 (motionKeys - 1) + 1 (bench/higher_order_bench.py: closer
                                ///< to the animation than the curve through motionKeys poses); 0: that curve
    double keyTolerancePixels = 0.125;  ///< chosen keys or pieces: the screen deviation they may leave
    int maxMotionKeys = 33;             ///< chosen keys: at most this many
    int imageHeight = 768;              ///< pixels, the unit of keyTolerancePixels
    std::optional<int> camera;  ///< a glTF camera (index into cameras); default: the first
                                ///< perspective camera instanced by a node, in node order
    std::optional<GltfLookAt> lookAt;  ///< an explicit camera instead of a glTF one
    float aspect = 4.0f / 3.0f;        ///< image width / height, to frame a scene without a camera
    bool allowExternalFiles = true;    ///< whether uris may name files (memory loads can say no)
    std::optional<GltfPointCache> pointCache;
    // _VELOCITY vertex attributes move their vertices from where they are at velocityFrame
    // (default: frame, where the shutter opens), in metres per second, or per frame.
    std::optional<double> velocityFrame;
    bool isVelocityPerFrame = false;
    // A mesh sequence (scene/mesh_sequence.h) interpolates its files even where their triangles
    // differ (vertices of one count in one order); files of other vertex counts are an Error.
    bool isSequenceInterpolated = false;
    GltfLimits limits;
};

// Loads a .gltf or .glb file into a Scene: one streak Mesh per (node, triangle primitive) of
// the file's default scene, with world-space key poses (piecewise linear; options.motionKeys
// of them, or as many as the animation needs, reported as motion_keys in stats) sampled from
// the animation over [frame, frame + shutter] / fps seconds: node hierarchies,
// skinning and morph targets included. Materials keep base colour, texture, vertex colours,
// alpha mode and double-sidedness. Points and lines are skipped (counted in stats). The
// camera is options.lookAt, else a glTF camera (posed at shutter open and close), else one
// that frames the scene's bounding box over the shutter from +z. Any problem with the file
// throws one Error that starts with its path.
Scene loadGltf(const std::string& path, const GltfOptions& options, RenderStats* stats = nullptr);

// The same from bytes in memory; `name` starts error messages, and relative uris resolve
// against baseDir when options.allowExternalFiles.
Scene loadGltfFromMemory(std::span<const std::uint8_t> bytes, const std::string& name, const std::string& baseDir,
                         const GltfOptions& options, RenderStats* stats = nullptr);

}  // namespace streak
