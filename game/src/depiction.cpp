#include "game/depiction.h"

namespace warplab::game {

session::FrameRecord frameRecordOf(const ShownFrame& shown) {
    session::FrameRecord r;
    r.frame = shown.frame;
    r.condition = shown.condition.name;
    r.kind = shown.blank ? "screen" : (shown.frozen ? "frozen" : condition::frameKindName(shown.schedule.kind));
    r.cameraYaw = shown.camera.yaw;
    r.cameraPitch = shown.camera.pitch;
    return r;
}

ShownFrame scheduledShownFrame(std::int64_t frame, const condition::Condition& condition,
                               const condition::ScheduledFrame& f, const SchedulePlacement& placement) {
    ShownFrame shown;
    shown.frame = frame;
    shown.time = static_cast<double>(frame) / placement.refreshHz;
    shown.condition = condition;
    shown.schedule = f;
    shown.sourceFrame = placement.start + f.sourceIndex;
    shown.nextSourceFrame = f.nextSourceIndex < 0 ? -1 : placement.start + f.nextSourceIndex;
    shown.scene.time = placement.timeAt(f.sceneTime);
    shown.rendersNow = f.rendersNow;
    shown.inputFrame = cameraFrame(f, placement);
    return shown;
}

ShownFrame screenShownFrame(std::int64_t frame, double time, const scene::CameraState& camera, PointerKind pointer,
                            glm::dvec2 cursor) {
    ShownFrame shown;
    shown.frame = frame;
    shown.time = time;
    shown.inputFrame = frame;
    shown.camera = camera;
    shown.blank = true;
    shown.pointer = pointer;
    shown.cursor = cursor;
    return shown;
}

std::int64_t cameraFrame(const condition::ScheduledFrame& f, const SchedulePlacement& placement) {
    return placement.frameAt(f.cameraTime);
}

WorldDepiction depictWorld(const condition::Condition& condition, const condition::ScheduledFrame& f,
                           const SchedulePlacement& placement, WorldClock clock) {
    const double refresh = placement.refreshHz;
    auto sessionTime = [&](std::int64_t frame) { return static_cast<double>(frame) / refresh; };
    WorldDepiction d;
    d.depictedFrame = placement.frameAt(f.sceneTime);
    d.frame = d.depictedFrame;
    if (condition.movesWorld()) {
        // The source's world moved on by its velocities, as the warp moves its pixels (a warp
        // fill, or a depth late warp to the display instant).
        d.how = Depicted::Extrapolated;
        d.frame = placement.frameAt(f.worldSampleTime);
        d.dt = clock == WorldClock::Session ? sessionTime(d.depictedFrame) - sessionTime(d.frame)
                                            : f.sceneTime - f.worldSampleTime;
        return d;
    }
    switch (condition.fillKind()) {
        case condition::Fill::Hold:
        case condition::Fill::Warp: break;
        case condition::Fill::Blend:
            // A cross-fade moves nothing: what it shows under a pixel is the nearer render's.
            d.frame = placement.frameAt(f.worldSampleTime);
            break;
        case condition::Fill::Bireproj:
            // B-frames move what the I-frames before and after show linearly between them.
            if (f.nextSourceIndex < 0) break;
            d.how = Depicted::Interpolated;
            d.frame = placement.start + f.sourceIndex;
            d.nextFrame = placement.start + f.nextSourceIndex;
            if (clock == WorldClock::Session) {
                const double t0 = sessionTime(d.frame), t1 = sessionTime(d.nextFrame);
                d.weight = (sessionTime(d.depictedFrame) - t0) / (t1 - t0);
                d.spanS = t1 - t0;
            } else {
                d.weight = static_cast<double>(d.depictedFrame - d.frame) / static_cast<double>(d.nextFrame - d.frame);
                d.spanS = static_cast<double>(d.nextFrame - d.frame) / refresh;
            }
            break;
    }
    return d;
}

}  // namespace warplab::game
