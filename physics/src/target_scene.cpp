#include "physics/target_scene.h"

#include "scene/hangar_layout.h"

namespace warplab::physics {

TargetScene::TargetScene(const TargetSceneConfig& config) : config_(config) {
    plane_ = fitTargetPlane(restingCamera(), config.aspect, config.targetRadius);
    motion_ = spawnTarget(plane_, config.targetSpeed, config.seed);
}

scene::CameraState TargetScene::restingCamera() const {
    using L = scene::HangarLayout;
    scene::CameraState camera;
    camera.eye = {L::kEyeX, L::kEyeY, L::kEyeZ};
    camera.verticalFovDeg = config_.verticalFovDeg;
    return camera;
}

scene::SceneSnapshot TargetScene::snapshot(double time) const {
    scene::SceneSnapshot snap;
    snap.time = time;
    snap.objects.push_back(targetObject(plane_, motion_, time, config_.targetRadius));
    return snap;
}

}  // namespace warplab::physics
