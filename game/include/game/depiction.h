// What a condition shows, decided once (DESIGN.md "Time, modes and determinism"). A condition's
// ScheduledFrame says which instants a displayed frame depicts; from it this decides, for every
// game alike, which of the game's recorded states the frame shows and how: as sampled
// (rendered, held, lagged), moved on by its velocity (warp extrapolation) or blended between
// the I-frames before and after (bidirectional reprojection). A game only says how its objects
// move and blend. The rest that every game's frame loop shares is here too: the ShownFrame's
// timing, the click gate of click_timing "input_reads", and the queue of events.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "game/game.h"
#include "condition/schedule.h"
#include "session/rows.h"

namespace warplab::game {

// A condition's schedule laid on the session's display frames: its frame 0 is shown at session
// frame `start` (a condition switch, a trial or a match starts a schedule afresh).
struct SchedulePlacement {
    std::int64_t start = 0;
    double refreshHz = 60.0;
    // The session frame of a schedule-local instant; the schedule's instants are display frames.
    std::int64_t frameAt(double localTime) const { return start + std::llround(localTime * refreshHz); }
    double timeAt(double localTime) const { return static_cast<double>(frameAt(localTime)) / refreshHz; }
};

// The ShownFrame of session frame `frame` as far as the schedule says: its display time, condition,
// schedule, sources, depicted scene time, the input it shows (cameraFrame) and whether it
// renders now. The game adds the camera
// or pointer (at cameraFrame), what the scene holds, the render and its texts.
ShownFrame scheduledShownFrame(std::int64_t frame, const condition::Condition& condition,
                               const condition::ScheduledFrame& f, const SchedulePlacement& placement);

// The columns of a frame's record that every game fills alike from what the frame shows: its
// frame, condition, kind ("screen" for a blank frame, "frozen" for a held shot, else the schedule's)
// and camera. The game adds its own detail_json.
session::FrameRecord frameRecordOf(const ShownFrame& shown);
// A screen's ShownFrame (ready, instructions, questions, done): no scene, the camera at rest
// where the game has it, the pointer as given; it answers this frame's input at once.
ShownFrame screenShownFrame(std::int64_t frame, double time, const scene::CameraState& camera, PointerKind pointer,
                            glm::dvec2 cursor = glm::dvec2(0.0));
// The session frame whose camera (mouse, cursor) frame `f` shows.
std::int64_t cameraFrame(const condition::ScheduledFrame& f, const SchedulePlacement& placement);

// The clock a game's world is timed on: what an extrapolation's dt and a blend's weight are
// measured in. Each game's displayed positions were fixed with one of these roundings; the two
// agree to the last bit or two, and keeping each lets every bot run and frame log stay
// bit-identical.
enum class WorldClock : std::uint8_t {
    // A function of session time (the shooter's closed-form target): instants are session
    // frames over the refresh, and a B-frame weighs its I-frames by those seconds.
    Session,
    // Recorded frame by frame from the schedule's start (the click game's match): instants are
    // the schedule's own times, and a B-frame weighs its I-frames by whole display frames.
    Schedule,
};

enum class Depicted : std::uint8_t { AsSampled, Extrapolated, Interpolated };

// Which states a displayed frame shows of the world, and how.
struct WorldDepiction {
    Depicted how = Depicted::AsSampled;
    // AsSampled: the session frame whose world is shown. Extrapolated: the source frame.
    // Interpolated: the I-frame before.
    std::int64_t frame = 0;
    std::int64_t nextFrame = -1;  // Interpolated: the I-frame after
    std::int64_t depictedFrame = 0;  // the session frame whose instant is depicted
    double dt = 0.0;  // Extrapolated: seconds the source's world moves on
    double weight = 0.0;  // Interpolated: the share of the I-frame after
    double spanS = 0.0;  // Interpolated: seconds from one I-frame to the other
};

WorldDepiction depictWorld(const condition::Condition& condition, const condition::ScheduledFrame& f,
                           const SchedulePlacement& placement, WorldClock clock);

// What `d` shows of a world, through the game's hooks:
//   at(frame)                         -> std::optional<State>: the world at a session frame,
//                                        nullopt where there was nothing to show;
//   move(State, dt)                   -> State: moved on dt seconds by its own velocities;
//   blend(before, after, weight, spanS) -> State: between two I-frames spanS seconds apart.
// A B-frame whose I-frames do not both have a world shows the world at the instant it depicts.
template <typename State, typename At, typename Move, typename Blend>
std::optional<State> depictedState(const WorldDepiction& d, At&& at, Move&& move, Blend&& blend) {
    switch (d.how) {
        case Depicted::AsSampled: return at(d.frame);
        case Depicted::Extrapolated: {
            std::optional<State> source = at(d.frame);
            if (!source) return std::nullopt;
            return move(std::move(*source), d.dt);
        }
        case Depicted::Interpolated: {
            const std::optional<State> before = at(d.frame), after = at(d.nextFrame);
            if (!before || !after) return at(d.depictedFrame);
            return blend(*before, *after, d.weight, d.spanS);
        }
    }
    return std::nullopt;
}

// click_timing "input_reads": a press waits for the next frame at which the condition reads its
// input (conv15/30/60 read it only at their renders), as a game polling input at its frame
// rate would. With click_timing "display" a press counts at the frame it comes with.
class ClickGate {
public:
    explicit ClickGate(bool waitsForInputReads) : waits_(waitsForInputReads) {}
    // Whether a click counts at frame `f`. `armed`: whether a press may wait (false drops it,
    // e.g. while there is nothing to shoot at).
    bool pass(bool pressed, const condition::ScheduledFrame& f, bool armed = true) {
        if (!waits_) return pressed;
        pending_ = (pending_ || pressed) && armed;
        const bool click = pending_ && f.samplesInput;
        if (click) pending_ = false;
        return click;
    }
    void clear() { pending_ = false; }

private:
    bool waits_;
    bool pending_ = false;  // pressed, not yet read
};

// The events a game produced since the runner last took them (Game::takeEvents), in order.
class EventQueue {
public:
    void push(session::EventRecord event) { events_.push_back(std::move(event)); }
    std::vector<session::EventRecord> take() {
        std::vector<session::EventRecord> out;
        out.swap(events_);
        return out;
    }

private:
    std::vector<session::EventRecord> events_;
};

}  // namespace warplab::game
