// The bouncing target's scene at any instant, as seed 004 (section 5.3.2) sets it up: the
// camera at rest at the hallway's end and the target bouncing in its plane. `warplab render`,
// the bench's sequences and the tests draw it without a game; the shooter game drives the
// camera from the mouse.
#pragma once

#include <cstdint>

#include "physics/bouncing_target.h"
#include "scene/scene.h"

namespace warplab::physics {

struct TargetSceneConfig {
    float verticalFovDeg = 60.0f;
    double aspect = 16.0 / 9.0;
    double targetRadius = 0.35;  // metres
    double targetSpeed = 2.0;  // metres per second
    std::uint64_t seed = 1;  // spawn point and direction
};

class TargetScene {
public:
    explicit TargetScene(const TargetSceneConfig& config);

    // The camera at rest (looking down the hallway) with the configured field of view.
    scene::CameraState restingCamera() const;
    scene::SceneSnapshot snapshot(double time) const;
    const TargetPlane& plane() const { return plane_; }
    const TargetMotion& motion() const { return motion_; }

private:
    TargetSceneConfig config_;
    TargetPlane plane_;
    TargetMotion motion_;
};

}  // namespace warplab::physics
