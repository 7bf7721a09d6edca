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

std::optional<renderer::HudPhotonMarker> hudPhotonMarker(protocol::PhotonMarker corner) {
    using Corner = renderer::HudPhotonMarker::Corner;
    switch (corner) {
        case protocol::PhotonMarker::Off: return std::nullopt;
        case protocol::PhotonMarker::TopLeft: return renderer::HudPhotonMarker{Corner::TopLeft, false};
        case protocol::PhotonMarker::TopRight: return renderer::HudPhotonMarker{Corner::TopRight, false};
        case protocol::PhotonMarker::BottomLeft: return renderer::HudPhotonMarker{Corner::BottomLeft, false};
        case protocol::PhotonMarker::BottomRight: return renderer::HudPhotonMarker{Corner::BottomRight, false};
    }
    return std::nullopt;
}

}  // namespace warplab::live
