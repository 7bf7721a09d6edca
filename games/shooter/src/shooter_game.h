// The bouncing-target shooter study (seed 004 sections 5.1, 5.3, Appendix B) as a
// deterministic state machine on the display clock: one step() per displayed frame, with
// that frame's input. It owns the phases (acclimation; the supervisor's Enter, which begins
// the recorded experiment as in seed 004 Appendix B; the training staircase; the test), the
// trials, the conditions' schedules and the scoring; it never touches GL.
// A session is a pure function of protocol, seed and the per-frame input record, which is
// what makes replay exact.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "game/depiction.h"
#include "game/frame_history.h"
#include "game/game.h"
#include "game/questionnaire.h"
#include "condition/schedule.h"
#include "physics/bouncing_target.h"
#include "session/rows.h"
#include "shooter/shooter_protocol.h"
#include "scene/scene.h"

namespace warplab::game {

enum class Phase : std::uint8_t { Acclimation, Training, AwaitingSupervisor, Test, Done };
const char* phaseName(Phase phase);

// On the question screens after a block the mouse moves a cursor instead of the view: this
// many display pixels per mouse count.
inline constexpr double kQuestionCursorPixelsPerCount = 1.0;

enum class Outcome : std::uint8_t { None, Hit, Miss, Timeout };
const char* outcomeName(Outcome outcome);

class ShooterGame final : public FreePlayGame {
public:
    // The display's aspect fits the target's plane to the view; its pixels lay out the question
    // screens.
    ShooterGame(const protocol::ShooterProtocol& protocol, std::uint64_t seed, const DisplaySize& display);

    ShownFrame step(const FrameInput& input) override;
    bool finished() const override { return phase_ == Phase::Done; }
    std::string phase() const override { return phaseName(phase_); }
    std::vector<session::EventRecord> takeEvents() override;
    bool atCommitPoint() const override { return commitPoint_; }
    // From format 7 a participant who sat down again faces the targets, as at a phase's start.
    void resumeHere() override;
    session::FrameRecord frameRecord(const ShownFrame& shown) const override;
    bool isOutcome(const session::EventRecord& event) const override;
    PointerProbe probePointer(const ShownFrame& shown) const override;
    std::optional<std::uint32_t> displayedObject(const session::EventRecord& event) const override;
    // Free play: endless targets at `difficulty` (the staircase's level) in `mode`.
    void switchTo(const std::string& condition, int difficulty) override;

    Phase currentPhase() const { return phase_; }
    int testLevel() const { return testLevel_; }
    std::int64_t frameIndex() const { return frame_; }
    const scene::CameraState& trueCamera() const { return camera_; }
    const physics::TargetPlane& targetPlane() const { return plane_; }

    // The trial in progress, for tests and tools that need the world's exact motion.
    struct TrialView {
        double spawnTime = 0.0;
        physics::TargetMotion motion;
        std::string condition;
    };
    std::optional<TrialView> currentTrial() const;

private:
    struct Trial {
        int index = 0;  // within its phase
        std::string condition;
        int level = 0;
        double speed = 0.0;
        std::int64_t spawnFrame = 0;
        physics::TargetMotion motion;
    };

    void beginPhase(Phase phase);
    // The phase's first trial, or first the screen of its instructions where it has some.
    void openPhase(const std::string& instructions);
    void finishReading();
    ShownFrame readingFrame() const;
    void startTrial(const std::string& condition, int level);
    void scheduleNextTrial();
    void finishTrial(Outcome world, Outcome displayed, double shotTime, double angularErrorDeg);
    // A frame of the questions after a block of the test: the mouse moves a cursor, not the view.
    ShownFrame questionFrame(const FrameInput& input);
    // The parts of step(), in the order it takes them.
    void openQuestionsIfDue();  // a block's last pause over: its questions, from this frame
    void turnCamera(const FrameInput& input);  // the mouse turns the view; recorded per frame
    ShownFrame frozenShownFrame() const;  // the frame of the last shot, held with its banner
    ShownFrame scheduledFrame(const condition::ScheduledFrame& f) const;  // the condition's frame and the target in it
    void describePhase(ShownFrame& shown) const;  // the status line for the participant and supervisor
    void judgeTrial(bool click, ShownFrame& shown);  // a shot or a timeout ends the trial
    void finishTrainingLevel();
    bool timedOut(const Trial& trial) const;
    std::optional<glm::dvec3> targetAt(double time) const;  // the world; nullopt when no target
    std::optional<glm::dvec3> displayedTarget(const condition::ScheduledFrame& f) const;  // as frame f depicts it
    double now() const { return static_cast<double>(frame_) / protocol_.refreshHz; }
    double speedFor(int level) const;
    std::uint64_t trialSeed(int phaseTag, int index) const;
    void emit(session::EventRecord event);

    protocol::ShooterProtocol protocol_;
    std::uint64_t seed_;
    physics::TargetPlane plane_;
    scene::CameraState restingCamera_;

    std::int64_t frame_ = -1;  // the frame being stepped
    scene::CameraState camera_;  // where the mouse points now
    FrameHistory<scene::CameraState> cameraHistory_;  // the true camera at recent frames
    std::uint32_t previousButtons_ = 0, previousKeys_ = 0;
    ClickGate clickGate_;

    Phase phase_ = Phase::Acclimation;
    std::int64_t phaseStartFrame_ = 0;  // its time runs from here (from the end of its instructions)
    bool reading_ = false;  // the phase's instructions are on screen
    bool recentre_ = false;  // the next frame's view starts from the resting one (a phase begins)
    std::string condition_;
    std::optional<condition::ConditionSchedule> schedule_;
    std::int64_t scheduleStart_ = 0;

    std::optional<Trial> trial_;
    int trialsInPhase_ = 0;
    std::int64_t pauseUntil_ = -1;  // frames before this are the post-shot pause
    std::optional<ShownFrame> frozenFrame_;
    std::string banner_;

    // Training staircase.
    int level_ = 0;
    int shotsPerCondition_ = 0;
    std::vector<std::string> levelQueue_;  // conditions of the remaining trials of this level
    std::size_t levelTrials_ = 0;  // ... and of all its trials
    int levelHits_[2] = {0, 0}, levelShots_[2] = {0, 0};
    bool missedYet_ = false;
    int testLevel_ = 0;

    // Test.
    std::vector<std::string> testQueue_;
    std::size_t testNext_ = 0;
    // The protocol's questions after each block of the test (a condition's trials, or the whole
    // test where conditions are interleaved): due once the block's last pause ends.
    Questionnaire questions_;
    bool questionsDue_ = false, asking_ = false;
    int block_ = 0;  // blocks of the test whose questions are answered
    std::string blockCondition_;  // the condition of the block being asked about; "" for a mixed one
    glm::dvec2 questionCursor_{0.0};
    DisplaySize display_;

    bool freePlay_ = false;
    std::string freeCondition_;
    int freeLevel_ = 0;

    EventQueue events_;
    bool commitPoint_ = false;
};

}  // namespace warplab::game
