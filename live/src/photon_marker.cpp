#include "photon_marker.h"

namespace warplab::live {

PhotonMarkerTiming::Answer PhotonMarkerTiming::step(const game::ShownFrame& shown, const game::FrameInput& input,
                                                    bool onScreen) {
    // A press is the button going down, as the games count one.
    const bool pressed = (input.buttons & game::kButtonLeft) && !(previousButtons_ & game::kButtonLeft);
    previousButtons_ = input.buttons;
    if (pressed) pending_.push_back(shown.frame);
    Answer answer;
    if (!onScreen) return answer;
    while (!pending_.empty() && pending_.front() <= shown.inputFrame) {
        if (!answer.lit) answer.press = pending_.front();
        answer.lit = true;
        pending_.pop_front();
    }
    return answer;
}

}  // namespace warplab::live
