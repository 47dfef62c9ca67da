#include "scene/camera.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace streak {

TEST(Camera, ClipWIsViewDepthAndCentreProjectsToCentre) {
    Camera camera;
    camera.open = CameraPose::lookAt(glm::vec3(1.0f, 2.0f, 3.0f), glm::vec3(1.0f, 2.0f, -7.0f));
    camera.close = camera.open;
    const glm::vec4 clip = camera.clipFromWorld(0.0f, 2.0f) * glm::vec4(1.0f, 2.0f, -2.0f, 1.0f);
    EXPECT_NEAR(clip.w, 5.0f, 1e-5f);
    EXPECT_NEAR(clip.x, 0.0f, 1e-5f);
    EXPECT_NEAR(clip.y, 0.0f, 1e-5f);
}

TEST(Camera, FieldOfViewMapsEdgesToNdcOne) {
    Camera camera;
    camera.verticalFov = 1.5707963f;  // tan(45 deg) = 1: at depth d the view spans y in [-d, d]
    camera.open = CameraPose::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    camera.close = camera.open;
    const glm::vec4 top = camera.clipFromWorld(0.0f, 2.0f) * glm::vec4(0.0f, 3.0f, -3.0f, 1.0f);
    EXPECT_NEAR(top.y / top.w, 1.0f, 1e-5f);
    const glm::vec4 right = camera.clipFromWorld(0.0f, 2.0f) * glm::vec4(6.0f, 0.0f, -3.0f, 1.0f);
    EXPECT_NEAR(right.x / right.w, 1.0f, 1e-5f);
}

TEST(Camera, PoseInterpolatesBetweenOpenAndClose) {
    Camera camera;
    camera.open = CameraPose::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    camera.close = CameraPose::lookAt(glm::vec3(2.0f, 0.0f, 0.0f), glm::vec3(2.0f + 1.0f, 0.0f, -1.0f));  // turned 45 deg right
    EXPECT_FALSE(camera.isStatic());
    EXPECT_NEAR(glm::length(camera.positionAt(0.5f) - glm::vec3(1.0f, 0.0f, 0.0f)), 0.0f, 1e-6f);
    // Halfway through, the camera has turned 22.5 degrees: a point on that bearing is centred.
    const float angle = 0.3926991f;
    const glm::vec3 ahead = glm::vec3(1.0f, 0.0f, 0.0f) + 4.0f * glm::vec3(std::sin(angle), 0.0f, -std::cos(angle));
    const glm::vec4 clip = camera.clipFromWorld(0.5f, 1.0f) * glm::vec4(ahead, 1.0f);
    EXPECT_NEAR(clip.x / clip.w, 0.0f, 1e-5f);
    EXPECT_NEAR(clip.w, 4.0f, 1e-4f);
}

}  // namespace streak
