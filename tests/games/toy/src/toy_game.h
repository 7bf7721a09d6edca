// The toy's state machine and its scripted bot.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "game/depiction.h"
#include "game/frame_history.h"
#include "game/game.h"
#include "toy_protocol.h"

namespace warplab::toy {

inline constexpr double kRadius = 0.3;  // metres; the sphere is 5 m straight ahead
inline constexpr double kDistance = 5.0;

// The world: the sphere's sideways offset from the reticle swings, so a warp's straight-line
// continuation and a B-frame's blend each show something other than the world.
struct Dot {
    double x = 0.0, v = 0.0;
};

// Plays the protocol's conditions one after another (in the seed's order where it shuffles),
// each for its seconds; in free play, one condition without end.
class ToyGame final : public game::FreePlayGame {
public:
    ToyGame(const ToyProtocol& p, std::uint64_t seed);

    game::ShownFrame step(const game::FrameInput& input) override;
    bool finished() const override { return done_; }
    std::string phase() const override { return done_ ? "done" : "play"; }
    std::vector<session::EventRecord> takeEvents() override { return events_.take(); }
    bool atCommitPoint() const override { return commitPoint_; }
    session::FrameRecord frameRecord(const game::ShownFrame& shown) const override;
    bool isOutcome(const session::EventRecord& e) const override { return e.type == "click"; }
    game::PointerProbe probePointer(const game::ShownFrame& shown) const override;
    std::optional<std::uint32_t> displayedObject(const session::EventRecord& e) const override;
    void switchTo(const std::string& condition, int difficulty) override;

private:
    void startCondition(std::size_t index, std::int64_t atFrame);
    void emit(const char* type, session::EventRecord e);
    void emit(session::EventRecord e);

    ToyProtocol protocol_;
    std::vector<std::string> order_;  // the conditions in the order played
    std::size_t current_ = 0;
    std::int64_t framesPerCondition_ = 0;
    condition::ConditionSchedule schedule_;
    std::int64_t scheduleStart_ = 0;
    game::ClickGate clickGate_;
    game::EventQueue events_;
    game::FrameHistory<Dot> history_;
    scene::CameraState camera_;
    std::int64_t frame_ = -1;
    std::uint32_t previousButtons_ = 0;
    std::string typed_;
    int clicks_ = 0;
    bool done_ = false, freePlay_ = false, commitPoint_ = false;
};

// Clicks, one frame at a time, whenever the dot it sees is near the reticle, and once early on
// when it is far from it (a miss); then waits half a second. Types now and then meanwhile:
// letters, multi-byte UTF-8 and Backspaces.
class ToyBot final : public game::Player {
public:
    game::FrameInput next(const game::ShownFrame& shown) override;

private:
    scene::CameraState camera_;
    double quietUntil_ = 0.0;
};

}  // namespace warplab::toy
