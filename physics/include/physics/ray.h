// Ray queries for analytic scoring: did the aim ray hit the target, and by how much did it
// miss. Double precision throughout: the target is a few pixels wide at ~7 m.
#pragma once

#include <optional>

#include <glm/glm.hpp>

namespace warplab::physics {

// Distance (in metres, i.e. along the normalised dir) from origin to the first point where
// the ray meets the sphere, counting t >= 0 only: from inside the sphere that is the exit
// point, from its surface 0; a tangent ray hits. std::nullopt if the ray misses or the
// sphere is behind. dir need not be unit length. Throws std::invalid_argument for a zero or
// non-finite dir or a negative radius.
std::optional<double> raySphereHit(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 centre, double radius);

// Angle in radians, [0, pi], between the ray's direction and the direction from origin to
// point. Accurate for tiny angles (near misses). Throws std::invalid_argument for a zero dir
// or point == origin.
double angleBetweenRayAndPoint(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 point);

}  // namespace warplab::physics
