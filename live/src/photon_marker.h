// The photodiode marker's timing (display.photon_marker, docs/live-sessions.md "Measuring
// click-to-photon latency with a photodiode"): which shown frame answers a left-button press.
// No GL: the window loop draws what this decides.
#pragma once

#include <cstdint>
#include <deque>

#include "game/game.h"

namespace warplab::live {

// Presses wait until a frame is shown whose picture shows their input (ShownFrame::inputFrame,
// which the condition's schedule decides); that frame lights the marker, and the next is black again
// unless it answers a later press. A display frame the clock skipped is never seen, so it
// answers nothing: the next frame shown does.
class PhotonMarkerTiming {
public:
    struct Answer {
        bool lit = false;
        std::int64_t press = -1;  // lit: the frame of the earliest press it answers
    };
    // The game stepped to `shown` with `input`; `onScreen` false for a skipped display frame.
    Answer step(const game::ShownFrame& shown, const game::FrameInput& input, bool onScreen);

private:
    std::uint32_t previousButtons_ = 0;
    std::deque<std::int64_t> pending_;  // frames of the presses not yet shown, in order
};

}  // namespace warplab::live
