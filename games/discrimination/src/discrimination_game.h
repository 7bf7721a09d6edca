// The discrimination task as a deterministic state machine on the display clock: one step() per
// displayed frame with that frame's input. A trial is two intervals -- the procedure's reference
// condition and its test condition, in an order drawn from the seed -- with a blank between,
// then the question; the answer goes to the block of adaptive procedures (adaptive/block.h),
// which chooses the next trial's procedure and level from the seed and the answers so far. So a
// session is a pure function of protocol, seed and input record: replay is exact, and a resumed
// session, whose recorded input is played up to where it stopped, continues every procedure
// where it was.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "adaptive/block.h"
#include "condition/schedule.h"
#include "discrimination/discrimination_protocol.h"
#include "game/depiction.h"
#include "game/frame_history.h"
#include "game/game.h"
#include "game/questionnaire.h"
#include "physics/bouncing_target.h"
#include "scene/scene.h"

namespace warplab::discrimination {

// On the question screen the mouse moves a cursor: this many display pixels per mouse count.
inline constexpr double kQuestionCursorPixelsPerCount = 1.0;
// The HUD's words for an interval, "Interval 1 of 2": the participant and the simulated one
// read them.
std::string intervalText(int interval);

enum class Stage : std::uint8_t { Reading, Interval, Blank, Question, Done };

class DiscriminationGame final : public game::FreePlayGame {
public:
    DiscriminationGame(const DiscriminationProtocol& protocol, std::uint64_t seed, const game::DisplaySize& display);

    game::ShownFrame step(const game::FrameInput& input) override;
    bool finished() const override { return stage_ == Stage::Done; }
    std::string phase() const override;
    std::vector<session::EventRecord> takeEvents() override { return events_.take(); }
    bool atCommitPoint() const override { return commitPoint_; }
    // A participant who sat down again faces the targets, as at every interval's start.
    void resumeHere() override { recentre_ = true; }
    session::FrameRecord frameRecord(const game::ShownFrame& shown) const override;
    bool isOutcome(const session::EventRecord& event) const override { return event.type == "judgement"; }
    game::PointerProbe probePointer(const game::ShownFrame& shown) const override;
    std::optional<std::uint32_t> displayedObject(const session::EventRecord&) const override { return std::nullopt; }
    // Free play: the target bounces on in `condition` without trials; difficulty is not used.
    void switchTo(const std::string& condition, int difficulty) override;

    // The block of procedures as the answers so far have left it, for tests.
    const adaptive::Block& block() const { return block_; }
    Stage stage() const { return stage_; }

private:
    struct Trial {
        int index = 0;  // in the session
        std::size_t procedure = 0;  // in the protocol's list
        int procedureTrial = 0;  // in its procedure
        std::size_t level = 0;  // index into the procedure's levels
        condition::Condition test;
        int testInterval = 1;  // 1 or 2
        physics::TargetMotion motion;  // the same path in both intervals
    };

    void startTrial();
    void beginInterval(int interval);
    void beginBlank(bool afterAnswer);
    void advanceStage();  // the stage whose time is up gives way to the next, from this frame
    game::ShownFrame intervalFrame(const game::FrameInput& input);
    game::ShownFrame questionFrame(const game::FrameInput& input);
    void answer(const game::Answer& answer);
    std::optional<glm::dvec3> targetAt(std::int64_t frame) const;  // the world; nullopt between trials
    std::optional<glm::dvec3> displayedTarget(const condition::ScheduledFrame& f) const;
    double now() const { return static_cast<double>(frame_) / protocol_.refreshHz; }
    std::int64_t frames(double seconds) const;
    void emit(session::EventRecord event);

    DiscriminationProtocol protocol_;
    std::uint64_t seed_;
    game::DisplaySize display_;
    physics::TargetPlane plane_;
    scene::CameraState restingCamera_;
    adaptive::Block block_;

    std::int64_t frame_ = -1;
    scene::CameraState camera_;
    game::FrameHistory<scene::CameraState> cameraHistory_;
    bool recentre_ = false;
    std::uint32_t previousKeys_ = 0, previousButtons_ = 0;

    Stage stage_ = Stage::Reading;
    std::int64_t stageStart_ = 0;
    int interval_ = 0;  // the interval playing (1, 2), 0 between
    bool afterAnswer_ = false;  // the blank after an answer, which leads to the next trial
    std::optional<Trial> trial_;
    int trials_ = 0;
    std::int64_t spawnFrame_ = 0;  // the interval's target starts here
    std::optional<condition::ConditionSchedule> schedule_;
    std::int64_t scheduleStart_ = 0;
    game::Questionnaire question_;
    glm::dvec2 cursor_{0.0};

    bool freePlay_ = false;
    game::EventQueue events_;
    bool commitPoint_ = false;
};

}  // namespace warplab::discrimination
