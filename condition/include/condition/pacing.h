// When a condition's renders reach the screen (DESIGN.md "Render instants are data too"). A
// render happens at an instant its pacing gives -- a steady render_hz, intervals drawn with
// frame_time_jitter, stalls added by hitches -- and is shown at the first display refresh at or
// after it, as a vsync'd game shows it. The display clock stays the clock: a render depicts the
// instant of the refresh it is first shown at, so only which refreshes show a new render changes.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "condition/condition.h"

namespace warplab::condition {

// The render instants of one schedule, as the display frames that first show each. Before the
// schedule's frame 0 (what a lag or bidirectional queue held before it started) the renders are
// the steady cadence of render_hz; from frame 0 on they follow the pacing, drawn from `seed`.
class RenderCadence {
public:
    // The condition must be one problem() accepts at refreshHz.
    RenderCadence(const Condition& condition, double refreshHz, std::uint64_t seed);

    // The display frame that shows the latest render at or before display frame j.
    std::int64_t latestAtOrBefore(std::int64_t j) const;
    // The display frame that shows the first render after display frame j.
    std::int64_t firstAfter(std::int64_t j) const;
    // Display frames between renders when they are evenly spaced whole frames (render_hz
    // divides the refresh and nothing jitters or stalls): every published preset.
    std::optional<std::int64_t> wholePeriod() const { return wholePeriod_; }
    // Display frames after which the cadence repeats; for a drawn cadence, the horizon over
    // which its latencies are looked at (kDrawnHorizonS).
    std::int64_t cycleFrames() const { return cycleFrames_; }

private:
    struct Drawn;  // the renders drawn so far, shared by copies (the stream is a pure function of the seed)
    std::int64_t steadyFrame(std::int64_t i) const;  // the frame of render i of the steady cadence
    std::int64_t steadyIndex(std::int64_t j) const;  // the latest steady render at or before frame j
    double framesPerRender_;
    std::optional<std::int64_t> wholePeriod_;
    std::int64_t cycleFrames_ = 1;
    std::shared_ptr<Drawn> drawn_;  // null for a steady cadence
};

// How long a drawn (jittered or hitching) cadence is looked at for its latency ranges.
inline constexpr double kDrawnHorizonS = 10.0;

// The longest render interval a condition's pacing can give, in seconds: what a bidirectional
// fill may wait for the next render (condition::problem bounds it by what a game keeps).
double longestRenderIntervalS(const Condition& condition);

}  // namespace warplab::condition
