#include "physics/bouncing_target.h"

#include "physics/splitmix.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scene/hangar_layout.h"

namespace warplab::physics {
namespace {

constexpr double kPi = 3.14159265358979323846;

void require(bool ok, const char* parameter, const char* what) {
    if (!ok) {
        throw std::invalid_argument(std::string(parameter) + ": " + what);
    }
}

struct AxisState {
    double position;
    double velocity;
};

// One axis of the fold. A bounce off [min, max] is the unfolded line seen in a mirror, so
// the state repeats with period 2L in the unfolded coordinate: the first half of a period
// is the outward leg (moving as the line does), the second half the return leg (mirrored).
// std::fmod is exact, so the only roundings are the fma and the final add: no error grows
// with t, and the same inputs give the same bits everywhere.
AxisState foldAxis(double min, double max, double start, double velocity, double t) {
    const double length = max - min;
    if (!(length > 0.0)) {
        // A slot of zero width: the centre cannot move along it at all.
        return {min, 0.0};
    }
    const double period = 2.0 * length;
    const double unfolded = std::fma(velocity, t, start - min);
    require(std::isfinite(unfolded), "t", "must be finite (start + velocity * t overflows)");

    double phase = std::fmod(unfolded, period);  // exact, in (-period, period)
    // Which leg owns a phase exactly on a wall (0, L or 2L) decides the convention at the
    // wall instant: we want the leg the centre is on just *after* that instant. With the
    // line moving forwards that is [0, L) outward, [L, 2L) return; moving backwards the
    // phase runs down, so (0, L] outward, (L, 2L] return.
    bool returnLeg;
    if (velocity < 0.0) {
        if (phase <= 0.0) phase += period;  // (0, period]
        returnLeg = phase > length;
    } else {
        // phase + period may round up to exactly period when phase is a tiny negative: the
        // exact phase is then just short of the min wall on the return leg, which is what
        // returnLeg = true and offset 0 below say.
        if (phase < 0.0) phase += period;  // [0, period]
        returnLeg = phase >= length;
    }
    // period - phase is exact here (Sterbenz: phase lies in [L, 2L]).
    const double offset = returnLeg ? period - phase : phase;
    return {std::clamp(min + offset, min, max), returnLeg ? -velocity : velocity};
}

void requireValidPlane(const TargetPlane& plane) {
    require(std::isfinite(plane.z) && std::isfinite(plane.minX) && std::isfinite(plane.maxX) &&
                std::isfinite(plane.minY) && std::isfinite(plane.maxY),
            "plane", "must be finite");
    require(plane.minX <= plane.maxX && plane.minY <= plane.maxY, "plane", "min must not exceed max");
}

// Draws from the one splitmix64 (physics/splitmix.h).
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    double uniform01() { return physics::uniform01(state_); }

private:
    std::uint64_t state_;
};

}  // namespace

TargetPlane fitTargetPlane(const scene::CameraState& camera, double aspect, double radius) {
    using Layout = scene::HangarLayout;
    const double fovDeg = camera.verticalFovDeg;
    require(std::isfinite(aspect) && aspect > 0.0, "aspect", "must be positive and finite");
    require(fovDeg > 0.0 && fovDeg < 180.0, "camera.verticalFovDeg", "must lie in (0, 180) degrees");
    const double minX = Layout::kClearMinX, maxX = Layout::kClearMaxX;
    const double minY = Layout::kClearMinY, maxY = Layout::kClearMaxY;
    require(std::isfinite(radius) && radius > 0.0 && 2.0 * radius < maxX - minX && 2.0 * radius < maxY - minY, "radius",
            "must be positive and smaller than half the clear cross-section");
    const glm::dvec3 eye(camera.eye);
    require(std::isfinite(eye.x) && std::isfinite(eye.y) && std::isfinite(eye.z), "camera.eye", "must be finite");

    // The farther wall from the eye on each axis must fit in the half angle on that axis;
    // the tighter axis sets the distance, the other then shows a little beyond its walls.
    const double tanHalfV = std::tan(fovDeg * (kPi / 180.0) * 0.5);
    const double tanHalfH = tanHalfV * aspect;
    const double halfX = std::max(eye.x - minX, maxX - eye.x);
    const double halfY = std::max(eye.y - minY, maxY - eye.y);
    const double distance = std::max(halfX / tanHalfH, halfY / tanHalfV);

    TargetPlane plane;
    plane.z = eye.z - distance;
    plane.minX = minX + radius;
    plane.maxX = maxX - radius;
    plane.minY = minY + radius;
    plane.maxY = maxY - radius;
    return plane;
}

glm::dvec2 positionAt(const TargetPlane& plane, const TargetMotion& motion, double t) {
    return {foldAxis(plane.minX, plane.maxX, motion.start.x, motion.velocity.x, t).position,
            foldAxis(plane.minY, plane.maxY, motion.start.y, motion.velocity.y, t).position};
}

glm::dvec2 velocityAt(const TargetPlane& plane, const TargetMotion& motion, double t) {
    return {foldAxis(plane.minX, plane.maxX, motion.start.x, motion.velocity.x, t).velocity,
            foldAxis(plane.minY, plane.maxY, motion.start.y, motion.velocity.y, t).velocity};
}

TargetMotion spawnTarget(const TargetPlane& plane, double speed, std::uint64_t seed) {
    requireValidPlane(plane);
    require(std::isfinite(speed) && speed >= 0.0, "speed", "must be non-negative and finite");
    SplitMix64 rng(seed);

    // Away from the walls so the first bounce is not immediate.
    constexpr double kMargin = 0.1;
    const auto spawnCoordinate = [&rng](double min, double max) {
        const double fraction = std::fma(1.0 - 2.0 * kMargin, rng.uniform01(), kMargin);
        return std::clamp(std::fma(fraction, max - min, min), min, max);
    };
    TargetMotion motion;
    motion.start.x = spawnCoordinate(plane.minX, plane.maxX);
    motion.start.y = spawnCoordinate(plane.minY, plane.maxY);

    // Direction by rejection in the unit disc rather than cos/sin of a random angle: the
    // libm trigonometry may differ by an ulp between machines, sqrt and division may not.
    // Rejecting points within 10 degrees of an axis keeps the angle uniform on what is left.
    constexpr double kTan10Deg = 0.17632698070846498;
    // Acceptance is ~61% per try, so the fallback is never reached in practice; it only
    // bounds the loop.
    glm::dvec2 direction(0.70710678118654752, 0.70710678118654752);
    for (int attempt = 0; attempt < 256; ++attempt) {
        const double a = 2.0 * rng.uniform01() - 1.0;
        const double b = 2.0 * rng.uniform01() - 1.0;
        const double lengthSquared = std::fma(a, a, b * b);
        if (lengthSquared > 1.0 || lengthSquared < 1e-6) continue;
        const double ax = std::fabs(a), ay = std::fabs(b);
        if (std::min(ax, ay) < kTan10Deg * std::max(ax, ay)) continue;
        const double length = std::sqrt(lengthSquared);
        direction = {a / length, b / length};
        break;
    }
    motion.velocity = direction * speed;
    return motion;
}

scene::ObjectState targetObject(const TargetPlane& plane, const TargetMotion& motion, double t, double radius) {
    require(std::isfinite(radius) && radius > 0.0, "radius", "must be positive and finite");
    const glm::dvec2 position = positionAt(plane, motion, t);
    const glm::dvec2 velocity = velocityAt(plane, motion, t);
    scene::ObjectState object;
    object.id = scene::kIdTarget;
    object.shape = scene::Shape::Sphere;
    object.position = glm::vec3(glm::dvec3(position, plane.z));
    object.velocity = glm::vec3(glm::dvec3(velocity, 0.0));
    object.halfExtents = glm::vec3(static_cast<float>(radius));
    object.angularVelocity = glm::vec3(0.0f);
    return object;
}

}  // namespace warplab::physics
