// The shooter target of seed 004 section 5.3.2: a sphere moving without gravity in a plane
// across the hallway, bouncing perfectly elastically off walls, floor and ceiling. Its state
// is a closed-form function of time (the straight line folded back into the box), so the
// world has no integrator, no drift and the same answer for any sampling of time.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace warplab::physics {

// Where the sphere's centre may go: the rectangle [minX, maxX] x [minY, maxY] in the plane
// z = const. Already shrunk by the target radius, so the sphere touches a wall exactly when
// its centre reaches an edge.
struct TargetPlane {
    double z = 0.0;
    double minX = 0.0, maxX = 0.0;
    double minY = 0.0, maxY = 0.0;
};

// Fits the plane to the hangar's clear cross-section (scene::HangarLayout) at the distance
// where the view volume at the initial gaze (yaw = pitch = 0) meets the walls, so the whole
// cross-section, and with it every position of the centre, is on screen before the player
// turns. aspect = width / height. Throws std::invalid_argument (naming the parameter) for
// aspect <= 0, a vertical FOV outside (0, 180) degrees, or a radius <= 0 or not smaller than
// half the cross-section.
TargetPlane fitTargetPlane(const scene::CameraState& camera, double aspect, double radius);

// The unfolded straight line: where the centre would be at t = 0 and its velocity (m/s),
// both in the plane's (x, y).
struct TargetMotion {
    glm::dvec2 start{0.0};
    glm::dvec2 velocity{0.0};
};

// Centre at time t (seconds, any sign, any magnitude): start + velocity * t folded back into
// the rectangle per axis. Always inside the rectangle. Bitwise the same on every IEEE-754
// machine (no transcendental functions, explicit fma).
glm::dvec2 positionAt(const TargetPlane& plane, const TargetMotion& motion, double t);

// Velocity at time t: each component is +-velocity (so speed is conserved exactly).
// At the exact instant the centre is on a wall the velocity is the one *after* the bounce
// (velocity is continuous from the right in t); a corner hit flips both components at once.
// An axis of zero length (min == max) pins the centre there, with that component 0.
glm::dvec2 velocityAt(const TargetPlane& plane, const TargetMotion& motion, double t);

// A deterministic start for a seed: the start point uniform in the middle 80% of each axis,
// the direction uniform in angle but at least 10 degrees from either axis (so it does not
// bounce back and forth on one line), at the given speed. The same seed gives bitwise the
// same motion on every machine. Throws std::invalid_argument for a negative or non-finite
// speed or an inverted plane.
TargetMotion spawnTarget(const TargetPlane& plane, double speed, std::uint64_t seed);

// The target as the renderer and the id buffer see it at time t.
scene::ObjectState targetObject(const TargetPlane& plane, const TargetMotion& motion, double t, double radius);

}  // namespace warplab::physics
