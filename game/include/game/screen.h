// The display's pixels and the world, in double precision, for scoring a pointer that is not
// at the centre (the click game's cursor): the ray through a pixel and the pixel a point
// projects to. Same convention as scene::viewMatrix / projectionMatrix (world-up lookAt,
// vertical field of view), so what scoring computes is what the renderer draws.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "game/game.h"
#include "scene/scene.h"

namespace warplab::game {

class ScreenMapping {
public:
    ScreenMapping(const scene::CameraState& camera, const DisplaySize& display);
    const glm::dvec3& eye() const { return eye_; }
    // Unit direction of the ray through display pixel coordinates (x right, y down).
    glm::dvec3 ray(glm::dvec2 pixel) const;
    // Where a world point lands in display pixels; nullopt behind the eye.
    std::optional<glm::dvec2> project(const glm::dvec3& point) const;
    // Radians one display pixel spans at the centre of the view.
    double radiansPerPixel() const;

private:
    glm::dvec3 eye_, forward_, right_, up_;
    double tanHalfY_, aspect_;
    DisplaySize display_;
};

}  // namespace warplab::game
