// The photodiode marker's timing without a window: which shown frame answers a press, as the
// frames' inputFrame says, and that a skipped display frame answers none.
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "photon_marker.h"

namespace warplab::live {
namespace {

game::ShownFrame frame(std::int64_t number, std::int64_t inputFrame) {
    game::ShownFrame shown;
    shown.frame = number;
    shown.inputFrame = inputFrame;
    return shown;
}

const game::FrameInput kPressed{0.0, 0.0, game::kButtonLeft, 0};

// A condition that shows each frame's input 3 frames late (lag50 at 60 Hz): a press at 10 lights 13
// alone, however long the button is held.
TEST(PhotonMarker, LightsOnceOnTheFirstFrameThatShowsThePress) {
    PhotonMarkerTiming timing;
    for (std::int64_t k = 0; k < 30; ++k) {
        const game::FrameInput input = k >= 10 && k < 20 ? kPressed : game::FrameInput{};
        const PhotonMarkerTiming::Answer a = timing.step(frame(k, k - 3), input, true);
        EXPECT_EQ(a.lit, k == 13) << "frame " << k;
        if (a.lit) {
            EXPECT_EQ(a.press, 10);
        }
    }
}

// A display frame the clock skipped is never on screen: the next frame shown answers the press,
// though the skipped one already depicted it.
TEST(PhotonMarker, ASkippedFrameLightsNothingAndTheNextShownDoes) {
    PhotonMarkerTiming timing;
    EXPECT_FALSE(timing.step(frame(5, 5), kPressed, false).lit);
    EXPECT_FALSE(timing.step(frame(6, 6), {}, false).lit);
    const PhotonMarkerTiming::Answer a = timing.step(frame(7, 7), {}, true);
    EXPECT_TRUE(a.lit);
    EXPECT_EQ(a.press, 5);
    EXPECT_FALSE(timing.step(frame(8, 8), {}, true).lit);
}

// Presses closer together than the latency: each lights the frame that shows it; two shown by
// the same frame light it once, named by the earlier.
TEST(PhotonMarker, EachPressIsAnsweredByTheFrameThatShowsIt) {
    PhotonMarkerTiming timing;
    std::vector<std::pair<std::int64_t, std::int64_t>> lit;  // frame, press
    for (std::int64_t k = 0; k < 40; ++k) {
        const bool down = k == 1 || k == 3 || k == 6 || k == 20 || k == 21;  // 20 and 21: one held press
        const game::FrameInput input = down ? kPressed : game::FrameInput{};
        // A condition that renders every 4th frame and shows each render 4 frames late.
        const std::int64_t shows = k < 4 ? -4 : (k - 4) / 4 * 4;
        const PhotonMarkerTiming::Answer a = timing.step(frame(k, shows), input, true);
        if (a.lit) lit.emplace_back(k, a.press);
    }
    using Lit = std::vector<std::pair<std::int64_t, std::int64_t>>;
    EXPECT_EQ(lit, (Lit{{8, 1}, {12, 6}, {24, 20}}));
}

}  // namespace
}  // namespace warplab::live
