#include "scene/camera.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace warplab::scene {

glm::vec3 forwardDirection(float yaw, float pitch) {
    const float cp = std::cos(pitch);
    return {std::sin(yaw) * cp, std::sin(pitch), -std::cos(yaw) * cp};
}

glm::mat4 viewMatrix(const CameraState& camera) {
    const glm::vec3 f = forwardDirection(camera.yaw, camera.pitch);
    // Up stays world-up; pitch is clamped by the callers well inside +-90 degrees.
    return glm::lookAt(camera.eye, camera.eye + f, glm::vec3(0.0f, 1.0f, 0.0f));
}

glm::mat4 projectionMatrix(const CameraState& camera, float aspect) {
    return glm::perspective(glm::radians(camera.verticalFovDeg), aspect, camera.nearPlane,
                            camera.farPlane);
}

CameraState widenedByRows(const CameraState& camera, int height, int marginY) {
    CameraState wide = camera;
    const double tanHalf = std::tan(camera.verticalFovDeg * M_PI / 360.0) * (height + 2.0 * marginY) / height;
    wide.verticalFovDeg = static_cast<float>(std::atan(tanHalf) * 360.0 / M_PI);
    return wide;
}

glm::vec3 rayDirection(const CameraState& camera, float aspect, glm::vec2 ndc) {
    const glm::mat4 invView = glm::inverse(viewMatrix(camera));
    const float tanHalf = std::tan(glm::radians(camera.verticalFovDeg) * 0.5f);
    const glm::vec4 dirView(ndc.x * tanHalf * aspect, ndc.y * tanHalf, -1.0f, 0.0f);
    return glm::normalize(glm::vec3(invView * dirView));
}

}  // namespace warplab::scene
