#include "game/shooter_scene.h"

#include "scene/hangar_layout.h"

namespace warplab::game {

ShooterScene::ShooterScene(const ShooterSceneConfig& config) : config_(config) {
    plane_ = physics::fitTargetPlane(restingCamera(), config.aspect, config.targetRadius);
    motion_ = physics::spawnTarget(plane_, config.targetSpeed, config.seed);
}

scene::CameraState ShooterScene::restingCamera() const {
    using L = scene::HangarLayout;
    scene::CameraState camera;
    camera.eye = {L::kEyeX, L::kEyeY, L::kEyeZ};
    camera.verticalFovDeg = config_.verticalFovDeg;
    return camera;
}

scene::SceneSnapshot ShooterScene::snapshot(double time) const {
    scene::SceneSnapshot snap;
    snap.time = time;
    snap.objects.push_back(physics::targetObject(plane_, motion_, time, config_.targetRadius));
    return snap;
}

}  // namespace warplab::game
