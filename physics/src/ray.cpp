#include "physics/ray.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace warplab::physics {
namespace {

glm::dvec3 requireDirection(glm::dvec3 dir) {
    const double length = glm::length(dir);
    if (!(length > 0.0) || !std::isfinite(length)) {
        throw std::invalid_argument("dir: must be non-zero and finite");
    }
    return dir / length;
}

}  // namespace

std::optional<double> raySphereHit(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 centre, double radius) {
    const glm::dvec3 unitDir = requireDirection(dir);
    if (!(radius >= 0.0)) {
        throw std::invalid_argument("radius: must be non-negative");
    }
    const glm::dvec3 toOrigin = origin - centre;
    const double along = glm::dot(toOrigin, unitDir);
    // The discriminant from the closest approach (Haines et al., Ray Tracing Gems ch. 7)
    // rather than along^2 - c: no cancellation between two large squares, which is what
    // decides grazing hits on a small, distant target.
    const glm::dvec3 perpendicular = toOrigin - along * unitDir;
    const double discriminant = radius * radius - glm::dot(perpendicular, perpendicular);
    if (discriminant < 0.0) {
        return std::nullopt;
    }
    // Roots of t^2 + 2 along t + c = 0; the stable pair avoids subtracting nearly equal
    // numbers when the origin is near the surface.
    const double c = glm::dot(toOrigin, toOrigin) - radius * radius;
    const double q = -along - std::copysign(std::sqrt(discriminant), along);
    if (q == 0.0) {
        return 0.0;  // along == 0 and tangent: the origin is the touching point
    }
    const double t0 = q;
    const double t1 = c / q;
    const double nearT = std::min(t0, t1);
    const double farT = std::max(t0, t1);
    if (nearT >= 0.0) return nearT;
    if (farT >= 0.0) return farT;
    return std::nullopt;
}

double angleBetweenRayAndPoint(glm::dvec3 origin, glm::dvec3 dir, glm::dvec3 point) {
    requireDirection(dir);
    const glm::dvec3 toPoint = point - origin;
    if (!(glm::length(toPoint) > 0.0)) {
        throw std::invalid_argument("point: must differ from origin");
    }
    // atan2 of |cross| and dot rather than acos of the cosine: acos loses half the digits
    // near 0, and near misses are the angles scoring cares about.
    return std::atan2(glm::length(glm::cross(dir, toPoint)), glm::dot(dir, toPoint));
}

}  // namespace warplab::physics
