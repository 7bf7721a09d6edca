#include "game/screen.h"

#include <cmath>

namespace warplab::game {

ScreenMapping::ScreenMapping(const scene::CameraState& camera, const DisplaySize& display)
    : eye_(camera.eye), display_(display) {
    const double yaw = camera.yaw, pitch = camera.pitch;
    forward_ = {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
    right_ = glm::normalize(glm::cross(forward_, glm::dvec3(0.0, 1.0, 0.0)));
    up_ = glm::cross(right_, forward_);
    tanHalfY_ = std::tan(glm::radians(static_cast<double>(camera.verticalFovDeg)) * 0.5);
    aspect_ = display.aspect();
}

glm::dvec3 ScreenMapping::ray(glm::dvec2 pixel) const {
    const double x = 2.0 * pixel.x / display_.width - 1.0;
    const double y = 1.0 - 2.0 * pixel.y / display_.height;
    return glm::normalize(forward_ + right_ * (x * tanHalfY_ * aspect_) + up_ * (y * tanHalfY_));
}

std::optional<glm::dvec2> ScreenMapping::project(const glm::dvec3& point) const {
    const glm::dvec3 d = point - eye_;
    const double depth = glm::dot(d, forward_);
    if (!(depth > 0.0)) return std::nullopt;
    const double x = glm::dot(d, right_) / (depth * tanHalfY_ * aspect_);
    const double y = glm::dot(d, up_) / (depth * tanHalfY_);
    return glm::dvec2((x + 1.0) * 0.5 * display_.width, (1.0 - y) * 0.5 * display_.height);
}

double ScreenMapping::radiansPerPixel() const { return 2.0 * std::atan(tanHalfY_) / display_.height; }

}  // namespace warplab::game
