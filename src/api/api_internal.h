#pragma once

// What the public API's files share: the scene behind the opaque handle and the conversions
// between the public plain structs and the layers' types. Inside namespace streak::api the
// public types shadow the layers' own of the same name; the layers' are written streak::X.

#include "streak/render.h"
#include "streak/scene.h"

#include "image/deep_image.h"
#include "image/image.h"
#include "scene/scene.h"
#include "util/stats.h"

#include <glm/vec3.hpp>

#include <array>
#include <initializer_list>
#include <optional>
#include <string>

namespace streak::api {

struct Scene::Impl {
    streak::Scene scene;
    SceneCleanup cleanup;
    std::string spec = "arrays";           ///< what it was loaded from (--stats "scene")
    std::string shutterPosition = "start";
    bool isGltf = false;
    std::optional<Trail> trail;            ///< the trail a glTF scene was loaded over
    RenderStats loadStats;                 ///< the load's time and the loader's figures
    std::optional<LoadOptions> loadOptions;  ///< how a scene with a clock was loaded (the vector pass loads its frames)
    std::size_t numArrayMeshes = 0;          ///< a scene from arrays: the meshes given (cleanup.keptMeshes: those kept)
    // A scene from arrays with its frames (Scene::withFrames): per kept mesh, its vertices at the
    // frames F - 1, F and F + 1, and the camera at each.
    struct ArrayFrames {
        std::vector<std::array<std::vector<glm::vec3>, 3>> positions;
        std::array<streak::Camera, 3> cameras;
    };
    std::optional<ArrayFrames> arrayFrames;

    // The scene with its surfaces' motion across the frames around the shutter's (Mesh::
    // framePositions, Scene::frameMotion) for an image of `aspect`: the vector pass's. Throws
    // Error for a scene without a clock, or one whose meshes change between those frames.
    streak::Scene withFrameMotion(float aspect) const;

    // Whether a trail method may draw this scene with `needed`: a glTF scene must have been
    // loaded over that trail; a built-in or arrays scene's shutter is its trail.
    bool canShowTrail(const Trail& needed) const {
        return !isGltf || (trail && trail->lengthSeconds == needed.lengthSeconds && trail->keys == needed.keys);
    }

    // The handle over a finished Impl (Scene's constructor is private to it and its members).
    static Scene wrap(std::shared_ptr<const Impl> impl) { return Scene(std::move(impl)); }
};

inline glm::vec3 vec3(const std::array<float, 3>& v) { return {v[0], v[1], v[2]}; }

// "x,y,z,..." with every digit a float holds, so another renderer can rebuild what it describes.
std::string numberList(std::initializer_list<double> values);

Image imageOf(const streak::Image& in);
streak::Image imageOf(const Image& in);
DeepImage deepImageOf(const streak::DeepImage& in);

}  // namespace streak::api
