// A condition as a frame schedule on the display clock (DESIGN.md "Time, conditions and
// determinism"). It says, for every displayed frame: is it rendered, held, warped or
// interpolated; is the mouse read for it; which instant's camera and which instant's world it
// depicts. Everything else -- the game loop, scoring, the frame maker, replay, the latency
// tables of the README and `warplab conditions` -- reads these schedules, so a condition's
// timing is written down once, whatever its parts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "condition/condition.h"
#include "condition/pacing.h"

namespace warplab::condition {

enum class FrameKind : std::uint8_t { Rendered, Held, Warped, Interpolated };
const char* frameKindName(FrameKind kind);

// What one displayed frame depicts. Times are seconds since the schedule started (a condition
// switch starts a new schedule); they may be negative for lag and bidirectional conditions, whose
// first frames show what the queue held before the switch.
struct ScheduledFrame {
    std::int64_t index = 0;  // display frame since the schedule started
    double displayTime = 0.0;  // when it is shown
    // What the frame is, as the frame log names it: a new render, a new frame of the fill
    // (warped, interpolated), or held: the frame before it shown again, no new image -- the
    // hold fill between renders, and a fill slower than the refresh between the frames it makes.
    FrameKind kind = FrameKind::Rendered;
    // How its image is made: the render of sourceIndex copied (Rendered or Held), or by the
    // fill's method (Warped, Interpolated). A frame the fill repeats is `kind` Held and made
    // again as the frame it repeats, so a repeated B-frame shows that B-frame, not its I-frame.
    FrameKind made = FrameKind::Rendered;
    double cameraTime = 0.0;  // the instant whose camera (mouse) it shows
    double sceneTime = 0.0;  // the instant whose world it shows (warp: by extrapolation)
    // The latest instant at which the world was sampled for it: a change in the world's motion
    // (not just its continuation) shows from here on. Warp extrapolates the source's motion,
    // so a target that changes course shows only in the next source frame.
    double worldSampleTime = 0.0;
    bool rendersNow = false;  // a conventional frame is rendered at this display frame
    bool samplesInput = false;  // the mouse is read for this frame
    std::int64_t sourceIndex = 0;  // display frame whose conventional render it is made from
    std::int64_t nextSourceIndex = -1;  // bidirectional: the later source frame
};

class ConditionSchedule {
public:
    // Throws std::invalid_argument with condition::problem's reason when the condition cannot
    // run at this refresh (a render rate above it, a lag that is not whole frames). A jittered
    // or hitching condition draws its render intervals from pacingSeed: the same seed, the
    // same cadence (games derive it from the session's seed and where the schedule starts).
    ConditionSchedule(const Condition& condition, double refreshHz, std::uint64_t pacingSeed = 0);

    const Condition& condition() const { return condition_; }
    double refreshHz() const { return refreshHz_; }
    ScheduledFrame frame(std::int64_t index) const;

    // Latency of a step at instant tau: time from tau to the first displayed frame whose
    // camera was read at or after tau (view), or whose world was sampled at or after tau
    // (scene: a change in the world's motion).
    double viewLatency(double tau) const;
    double sceneLatency(double tau) const;

    // The shortest and longest of those over where a step falls in the cycle (seconds). The
    // longest is a supremum: a step just after an instant that was read waits for the next.
    struct Range {
        double min = 0.0, max = 0.0;
    };
    Range viewLatencyRange() const;
    Range sceneLatencyRange() const;
    // Where a step falling in (from, to] is first shown: `from` and `to` are consecutive distinct
    // instants that frames depict, so its latency falls linearly from shownAt - from to shownAt - to.
    struct LatencySpan {
        double from = 0.0, to = 0.0, shownAt = 0.0;
    };
    // The spans of the instants display frames first..last depict, but the first of them.
    std::vector<LatencySpan> viewLatencySpans(std::int64_t first, std::int64_t last) const;
    std::vector<LatencySpan> sceneLatencySpans(std::int64_t first, std::int64_t last) const;
    // The first display frame the latency ranges (and condition::pacingStats) look at: once the
    // lag and four cycles have passed, so nothing the queue held before the schedule started shows.
    std::int64_t settledFrame() const;
    std::int64_t lagFrames() const { return lagFrames_; }
    const RenderCadence& cadence() const { return cadence_; }

private:
    template <typename Depicted>
    double firstShowing(double tau, Depicted depicted) const;
    template <typename Depicted>
    Range latencyRange(Depicted depicted) const;
    template <typename Depicted>
    std::vector<LatencySpan> latencySpans(std::int64_t first, std::int64_t last, Depicted depicted) const;
    std::int64_t cycle() const { return cadence_.cycleFrames() * cycleFactor_; }
    // The frame the fill makes at production frame j, before the queue and any late warp.
    ScheduledFrame produced(std::int64_t j) const;
    // A bidirectional fill at production frame j: the render interval it plays and the
    // instant (display frame) it depicts.
    struct Between {
        std::int64_t from = 0, to = 0, depicted = 0;
    };
    Between between(std::int64_t j) const;
    static const Condition& checked(const Condition& condition, double refreshHz);
    Condition condition_;
    double refreshHz_;
    RenderCadence cadence_;
    // The display frames the fill makes a frame at: every one, or fill_hz's steady cadence,
    // uneven when the refresh is not a whole multiple of it (120 Hz on 144: 1, 1, 1, 1, 2).
    RenderCadence fillCadence_;
    Fill fill_;
    std::int64_t lagFrames_;  // display frames a rendered frame waits in the queue
    // cycle() is the render cadence's cycle times this: the fill's cycle, or for hold the render
    // period (a steady cadence's cycle squared, as the latency ranges have always scanned it).
    std::int64_t cycleFactor_;
};

// A condition at one refresh, as `warplab conditions` and export's conditions.csv list it.
struct ConditionSummary {
    Condition condition;
    double refreshHz = 0.0;
    std::int64_t lagFrames = 0;
    ConditionSchedule::Range viewS, sceneS;  // latencies, seconds
};
// Throws std::invalid_argument as ConditionSchedule does.
ConditionSummary summarize(const Condition& condition, double refreshHz);

}  // namespace warplab::condition
