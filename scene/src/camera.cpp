#include "scene/camera.h"

#include <cmath>
#include <limits>

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
    return glm::perspective(glm::radians(camera.verticalFovDeg), aspect, camera.nearPlane, camera.farPlane);
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

float projectedSphereRadiusPixels(const CameraState& camera, int height, glm::vec3 centre, float radius) {
    const double infinity = std::numeric_limits<float>::infinity();
    const glm::dvec3 toCentre = glm::dvec3(centre) - glm::dvec3(camera.eye);
    const double distance = glm::length(toCentre);
    if (distance <= radius) return static_cast<float>(infinity);
    // The sphere subtends the cone of half-angle alpha around the direction theta off the axis;
    // in the image plane at focal length f its long axis runs from tan(theta - alpha) to
    // tan(theta + alpha).
    const double alpha = std::asin(radius / distance);
    const glm::dvec3 forward = glm::dvec3(forwardDirection(camera.yaw, camera.pitch));
    const double theta = std::acos(glm::clamp(glm::dot(forward, toCentre) / distance, -1.0, 1.0));
    const double quarter = M_PI / 2.0;
    if (theta - alpha >= quarter) return 0.0f;
    if (theta + alpha >= quarter) return static_cast<float>(infinity);
    const double focal = 0.5 * height / std::tan(camera.verticalFovDeg * M_PI / 360.0);
    return static_cast<float>(0.5 * focal * (std::tan(theta + alpha) - std::tan(theta - alpha)));
}

}  // namespace warplab::scene
