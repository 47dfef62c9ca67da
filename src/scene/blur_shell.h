#pragma once

#include "scene/scene.h"
#include "scene/silhouette_of_motion.h"
#include "util/options.h"
#include "util/stats.h"

#include <cstddef>
#include <vector>

namespace streak {

// The settings of Jones' blur shell (2004, section 3.2.1), read from method options.
struct BlurShellOptions {
    double lengthSeconds = 0.2;  ///< the trail: glTF scenes are loaded over [T - length, T]
    int subdivisions = 10;       ///< SoM updates over the trail, length / subdivisions apart
    float alpha = 0.5f;          ///< the alpha of a strip at the mesh
    int fade = 3;                ///< updates a strip survives after its polygon leaves the SoM
    // How vertices face: welded (the area-weighted mean normal of every polygon around the
    // vertex's position, so a flat-shaded mesh whose polygons have their own vertices still has
    // a silhouette of motion: the thesis' advice) or the mesh's own normals. Shell vertices
    // keep the mesh's normals either way, for shading.
    bool isFacingWelded = true;

    static constexpr int kMaxSubdivisions = 128;
    // length (seconds, > 0), subdivisions (1 to 128), alpha ([0, 1]), fade (1 to 64),
    // facing (welded or mesh).
    static BlurShellOptions read(OptionMap& options);
    // The renderers' blend option: ordered (false; the thesis: submission order, no depth
    // writes) or sorted (true: order independent, with the scene's translucent surfaces).
    static bool readIsSorted(OptionMap& options);
};

// The blur shell of a scene at shutter close: the state that `subdivisions` SoM updates at the
// shutter times i / subdivisions (i = 1..subdivisions) leave, run in order from a cleared
// state, and each mesh's strips built from it. The shutter is the trail: a scene loaded over
// [T - length, T] with one key per update time has its keys at exactly those times, and any
// other scene is sampled there (MotionWeights). Camera motion makes no shell: the SoM is found
// in world space. Meshes that do not move have none.
struct BlurShell {
    std::vector<std::vector<ShellStrip>> strips;  ///< per mesh of the scene
    std::size_t silhouetteEdges = 0;              ///< polygons on the SoM at the last update
    double meanSilhouetteEdges = 0.0;             ///< per update, over all updates
    std::size_t numStrips = 0;
    std::size_t numTriangles = 0;                 ///< two per quad of non-zero area
    double silhouetteSeconds = 0.0;               ///< the SoM updates (Jones' Tables 1-2: "SoM detection")
    double buildSeconds = 0.0;                    ///< building the strips
};

BlurShell buildBlurShell(const Scene& scene, const BlurShellOptions& options);

// The scene the shell is drawn in and exported as: every mesh at its shutter-close pose (not
// moving), followed by one mesh of quads per mesh with strips (the meshes from firstShellMesh
// on): double-sided, with the source mesh's uvs and vertex colours, its alpha in the vertex
// colours, the normals recorded with each edge, and a Blend copy of the source material. The
// camera stands at its close pose. Validated.
struct ShellScene {
    Scene scene;
    std::size_t firstShellMesh = 0;

    std::size_t firstShellTriangle() const;  ///< in scene order (FlatGeometry's)
    std::size_t numShellTriangles() const;
};

ShellScene makeShellScene(const Scene& scene, const BlurShell& shell);

// buildBlurShell and makeShellScene, as a renderer reports them: phases "silhouette" (the SoM
// updates), "shell build" and "shell scene"; counters subdivisions, silhouette_edges (at the
// last update), silhouette_edges_per_update, shell_strips and shell_triangles (drawn).
ShellScene buildShellScene(const Scene& scene, const BlurShellOptions& options, RenderStats& stats);

}  // namespace streak
