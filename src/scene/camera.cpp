#include "scene/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace streak {

CameraPose CameraPose::lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up) {
    // glm::lookAt gives viewFromWorld; its rotation part inverted is worldFromCamera.
    const glm::mat4 view = glm::lookAt(eye, target, up);
    CameraPose pose;
    pose.position = eye;
    pose.worldFromCamera = glm::normalize(glm::quat_cast(glm::transpose(glm::mat3(view))));
    return pose;
}

bool Camera::isStatic() const {
    return open.position == close.position && open.worldFromCamera == close.worldFromCamera;
}

bool Camera::isTurning() const {
    const glm::mat3 a = glm::mat3_cast(open.worldFromCamera), b = glm::mat3_cast(close.worldFromCamera);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (!(std::abs(a[c][r] - b[c][r]) <= kTurnTolerance)) return true;
    return false;
}

CameraPose Camera::poseAt(float t) const {
    if (isStatic()) return open;
    CameraPose pose;
    pose.position = glm::mix(open.position, close.position, t);
    pose.worldFromCamera = glm::slerp(open.worldFromCamera, close.worldFromCamera, t);
    return pose;
}

glm::vec3 Camera::positionAt(float t) const { return glm::mix(open.position, close.position, t); }

glm::mat4 Camera::viewFromWorld(float t) const {
    const CameraPose pose = poseAt(t);
    const glm::mat3 cameraFromWorldRotation = glm::transpose(glm::mat3_cast(pose.worldFromCamera));
    glm::mat4 view(cameraFromWorldRotation);
    view[3] = glm::vec4(-(cameraFromWorldRotation * pose.position), 1.0f);
    return view;
}

glm::mat4 Camera::clipFromView(float aspect) const {
    // Infinite perspective: x and y as usual, w = -z_view (the view depth), z unused by streak
    // but kept finite for GL: z_clip = -z_view - 2 near (maps near to -1, infinity to +1).
    const float f = 1.0f / std::tan(verticalFov * 0.5f);
    glm::mat4 m(0.0f);
    m[0][0] = f / aspect;
    m[1][1] = f;
    m[2][2] = -1.0f;
    m[2][3] = -1.0f;
    m[3][2] = -2.0f * zNear;
    return m;
}

}  // namespace streak
