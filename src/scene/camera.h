#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cmath>

namespace streak {

// CameraPose places a camera in the world: it looks down its local -z with +y up (the OpenGL
// and glTF convention).
struct CameraPose {
    glm::vec3 position{0.0f};
    glm::quat worldFromCamera{1.0f, 0.0f, 0.0f, 0.0f};  ///< rotation, camera axes to world

    static CameraPose lookAt(const glm::vec3& eye, const glm::vec3& target,
                             const glm::vec3& up = glm::vec3(0.0f, 1.0f, 0.0f));
};

// Camera is a pinhole perspective camera that may move over the shutter: its pose goes from
// `open` (t = 0) to `close` (t = 1), position linearly and orientation by slerp. There is no far
// plane (infinite projection); clip-space w is the view depth, so depth tests compare w.
struct Camera {
    CameraPose open;
    CameraPose close;
    float verticalFov = 0.785398f;  ///< radians (45 degrees by default)
    float zNear = 0.05f;            ///< world units

    bool isStatic() const;
    // The orientation changes over the shutter: its axes move by more than kTurnTolerance. A
    // camera that only moves (without turning; its projection is fixed) keeps clip-space motion
    // linear: clipFromView * viewFromWorld(t) * x is R (x - c(t)) projected, affine in t for a
    // point x moving linearly, so a screen path needs no more linear pieces than the scene's own
    // keys. (Two look-at poses with one view direction can differ in their last float bits.)
    static constexpr float kTurnTolerance = 1e-6f;  ///< radians, about: below float precision
    bool isTurning() const;
    CameraPose poseAt(float t) const;
    glm::vec3 positionAt(float t) const;
    glm::mat4 viewFromWorld(float t) const;
    // aspect = width / height of the image.
    glm::mat4 clipFromView(float aspect) const;
    glm::mat4 clipFromWorld(float t, float aspect) const { return clipFromView(aspect) * viewFromWorld(t); }
    // The length in pixels of an NDC displacement on an image imageHeight pixels tall and aspect
    // times as wide: NDC spans the image's height and width in 2 units each. How far apart two
    // projections of a point are (the key and curve choosers' deviations).
    static double pixelsOfNdc(const glm::dvec2& ndcDelta, double aspect, double imageHeight) {
        const glm::dvec2 d = ndcDelta * (0.5 * imageHeight);
        return std::hypot(d.x * aspect, d.y);
    }
};

}  // namespace streak
