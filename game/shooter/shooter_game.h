// The bouncing-target shooter study (seed 004 sections 5.1, 5.3, Appendix B) as a
// deterministic state machine on the display clock: one step() per displayed frame, with
// that frame's input. It owns the phases (acclimation; the supervisor's Enter, which begins
// the recorded experiment as in seed 004 Appendix B; the training staircase; the test), the trials, the modes' schedules and the scoring; it never touches GL.
// A session is a pure function of protocol, seed and the per-frame input record, which is
// what makes replay exact.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "game/modes.h"
#include "physics/bouncing_target.h"
#include "protocol/session_store.h"
#include "protocol/shooter_protocol.h"
#include "scene/scene.h"

namespace warplab::game {

inline constexpr std::uint32_t kButtonLeft = 1u;  // FrameInput::buttons
inline constexpr std::uint32_t kKeyEnter = 1u;    // FrameInput::keys: the supervisor begins the experiment

struct FrameInput {
    double mouseDx = 0.0;  // mouse counts since the previous frame; +x turns right
    double mouseDy = 0.0;  // +y moves down, so looks down
    std::uint32_t buttons = 0;
    std::uint32_t keys = 0;
};

enum class Phase : std::uint8_t { Acclimation, Training, AwaitingSupervisor, Test, Done };
const char* phaseName(Phase phase);

enum class Outcome : std::uint8_t { None, Hit, Miss, Timeout };
const char* outcomeName(Outcome outcome);

// What one displayed frame shows, for the renderer and for a player looking at the screen.
struct ShownFrame {
    std::int64_t frame = 0;             // display frame since the session started
    double time = 0.0;                  // its display time, seconds
    std::string mode;
    ScheduledFrame schedule;            // the mode's account of this frame (schedule-local)
    scene::CameraState camera;          // the camera the frame depicts (the reticle is its centre)
    scene::SceneSnapshot scene;         // the world as the frame depicts it (extrapolated for warp)
    bool rendersNow = false;            // render `render` conventionally at this frame
    scene::FrameDescription render;     // ... the source of this and the following frames
    std::int64_t sourceFrame = 0;       // session frame whose render this frame is made from
    std::int64_t nextSourceFrame = -1;  // bidirectional: the later source
    bool frozen = false;                // the pause after a shot: the last frame stays on screen
    std::string banner;                 // "HIT", "MISS", "TIMEOUT" during the pause, else ""
    std::string phaseText;              // e.g. "Training: level 4", "Press Enter to begin"
};

class ShooterGame {
public:
    // aspect = width / height of the display; it fits the target's plane to the view.
    ShooterGame(const protocol::ShooterProtocol& protocol, std::uint64_t seed, double aspect);

    ShownFrame step(const FrameInput& input);
    bool finished() const { return phase_ == Phase::Done; }
    Phase phase() const { return phase_; }
    int testLevel() const { return testLevel_; }
    std::int64_t frameIndex() const { return frame_; }
    const scene::CameraState& trueCamera() const { return camera_; }
    const physics::TargetPlane& targetPlane() const { return plane_; }

    // The trial in progress, for tests and tools that need the world's exact motion.
    struct TrialView {
        double spawnTime = 0.0;
        physics::TargetMotion motion;
        std::string mode;
    };
    std::optional<TrialView> currentTrial() const;

    // Events produced since the last call, in order.
    std::vector<protocol::EventRecord> takeEvents();
    // True when the last step completed a trial or changed phase: the session store commits.
    bool atCommitPoint() const { return commitPoint_; }
    // The frame log row for a shown frame.
    protocol::FrameRecord frameRecord(const ShownFrame& shown) const;

private:
    struct Trial {
        int index = 0;              // within its phase
        std::string mode;
        int level = 0;
        double speed = 0.0;
        std::int64_t spawnFrame = 0;
        physics::TargetMotion motion;
    };

    void beginPhase(Phase phase);
    void startTrial(const std::string& mode, int level);
    void scheduleNextTrial();
    void finishTrial(Outcome world, Outcome displayed, double shotTime, double angularErrorDeg);
    void finishTrainingLevel();
    std::optional<glm::dvec3> targetAt(double time) const;  // the world; nullopt when no target
    std::optional<glm::dvec3> displayedTarget(const ScheduledFrame& f) const;  // as frame f depicts it
    scene::CameraState cameraAt(std::int64_t frame) const;
    double now() const { return static_cast<double>(frame_) / protocol_.refreshHz; }
    double speedFor(int level) const;
    std::uint64_t trialSeed(int phaseTag, int index) const;
    void emit(protocol::EventRecord event);

    protocol::ShooterProtocol protocol_;
    std::uint64_t seed_;
    double aspect_;
    physics::TargetPlane plane_;
    scene::CameraState restingCamera_;

    std::int64_t frame_ = -1;               // the frame being stepped
    scene::CameraState camera_;             // where the mouse points now
    std::deque<scene::CameraState> cameraHistory_;  // the true camera at recent frames
    std::int64_t historyStart_ = 0;
    std::uint32_t previousButtons_ = 0, previousKeys_ = 0;

    Phase phase_ = Phase::Acclimation;
    std::int64_t phaseStartFrame_ = 0;
    std::string mode_;
    std::optional<ModeSchedule> schedule_;
    std::int64_t scheduleStart_ = 0;

    std::optional<Trial> trial_;
    int trialsInPhase_ = 0;
    std::int64_t pauseUntil_ = -1;          // frames before this are the post-shot pause
    std::optional<ShownFrame> frozenFrame_;
    std::string banner_;

    // Training staircase.
    int level_ = 0;
    int shotsPerMode_ = 0;
    std::vector<std::string> levelQueue_;   // modes of the remaining trials of this level
    int levelHits_[2] = {0, 0}, levelShots_[2] = {0, 0};
    bool missedYet_ = false;
    int testLevel_ = 0;

    // Test.
    std::vector<std::string> testQueue_;
    std::size_t testNext_ = 0;

    std::vector<protocol::EventRecord> events_;
    bool commitPoint_ = false;
};

}  // namespace warplab::game
