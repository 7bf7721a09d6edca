// The shooter study's scene at any instant: the camera at the hallway's end and the target
// bouncing in its plane (seed 004 section 5.3.2). The shooter game drives the camera from
// the mouse; `warplab render` and the tests set it directly.
#pragma once

#include <cstdint>

#include "physics/bouncing_target.h"
#include "scene/scene.h"

namespace warplab::game {

struct ShooterSceneConfig {
    float verticalFovDeg = 60.0f;
    double aspect = 16.0 / 9.0;
    double targetRadius = 0.35;  // metres
    double targetSpeed = 2.0;  // metres per second
    std::uint64_t seed = 1;  // spawn point and direction
};

class ShooterScene {
public:
    explicit ShooterScene(const ShooterSceneConfig& config);

    // The camera at rest (looking down the hallway) with the configured field of view.
    scene::CameraState restingCamera() const;
    scene::SceneSnapshot snapshot(double time) const;
    const physics::TargetPlane& plane() const { return plane_; }
    const physics::TargetMotion& motion() const { return motion_; }

private:
    ShooterSceneConfig config_;
    physics::TargetPlane plane_;
    physics::TargetMotion motion_;
};

}  // namespace warplab::game
