// The window's input as the game and the supervisor read it, without a window: typed text
// reaches the game as typed, Backspace as the game's own; the keys keep their meanings.
#include <gtest/gtest.h>

#include "window_loop.h"

namespace warplab::live {
namespace {

TEST(WindowInput, TypedTextReachesTheGameWithItsBackspaces) {
    renderer::WindowInput in;
    in.text = std::string("lagy") + renderer::kTypedBackspace + "gy \xE2\x80\x94 ok";
    in.keysPressed = "q3\r";
    const Polled p = readInput(in, 1.0, false);
    EXPECT_EQ(p.input.text, std::string("lagy") + game::kTextBackspace + "gy \xE2\x80\x94 ok");
    // Letters are no game key and stop nothing; Enter and the digit are the game's.
    EXPECT_EQ(p.input.keys, game::kKeyEnter | game::digitKey(3));
    EXPECT_FALSE(p.escape);
    EXPECT_EQ(p.keys, "q3\r");
}

TEST(WindowInput, OnlyEscPauses) {
    renderer::WindowInput in;
    in.text = "sq ";
    in.keysPressed = "sq";
    EXPECT_FALSE(readInput(in, 1.0, false).escape);
    in.keysPressed = "s\x1b";
    EXPECT_TRUE(readInput(in, 1.0, false).escape);
}

TEST(WindowInput, MouseCountsAreScaledAndYInvertedWhenAsked) {
    renderer::WindowInput in;
    in.mouseDx = 4.0;
    in.mouseDy = -2.0;
    in.leftHeld = true;
    const Polled p = readInput(in, 0.5, true);
    EXPECT_EQ(p.input.mouseDx, 2.0);
    EXPECT_EQ(p.input.mouseDy, 1.0);
    EXPECT_EQ(p.input.buttons, game::kButtonLeft);
}

}  // namespace
}  // namespace warplab::live
