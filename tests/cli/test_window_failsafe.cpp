// A live session's window fails safe: without a display to show it on, a run says so at once,
// before any window, rather than waiting at a start screen nobody sees.
#include <chrono>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "cli/cli_support.h"

namespace {

namespace fs = std::filesystem;

using warplab::testing::contains;
using warplab::testing::runCommand;
using warplab::testing::sessionIn;

std::string scratch(const std::string& name) { return warplab::testing::scratch("window-failsafe", name); }

// The shooter in a few seconds, warning (not refusing) of a refresh other than its own.
std::string tinyProtocol(const std::string& dir) {
    std::ofstream(dir + "/tiny.json") << R"({"format_version":2,"name":"shooter-tiny","game":"shooter",
 "display":{"refresh_mismatch":"warn"},
 "acclimation":{"duration_s":1.0,"level":0,"mode":"conv120"},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.5},
 "test":{"targets_per_condition":1,"timeout_s":0.5,"pause_s":0.25,"supervisor_starts":true}})";
    return dir + "/tiny.json";
}

std::string warplabBinary() { return WARPLAB_BINARY; }

TEST(LiveWindow, WithoutADisplayARunSaysSoAtOnceBeforeAnyWindow) {
    const std::string dir = scratch("no-display");
    // Bounded: SDL's fallback waited at an invisible start screen for ever.
    const std::string run = "timeout 10 " + warplabBinary() + " run --seed 1 --protocol " + tinyProtocol(dir) +
        " --participant N --out " + dir + " --width 160 --height 90";
    const auto started = std::chrono::steady_clock::now();
    auto r = runCommand("env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER " + run);
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5));
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.output,
              "warplab run: no window can be shown: DISPLAY is not set (start warplab from the desktop, or set "
              "DISPLAY=:0 for the machine's own screen)\n");
    // A display no X server answers on, and SDL's drivers that draw into no screen: refused,
    // never a start screen nobody sees.
    r = runCommand("env -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER DISPLAY=:1999 " + run);
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.output, "warplab run: no window can be shown: the display ':1999' cannot be reached"))
        << r.output;
    for (const std::string driver : {"offscreen", "dummy"}) {
        r = runCommand("SDL_VIDEODRIVER=" + driver + " " + run);
        EXPECT_EQ(r.status, 1);
        EXPECT_TRUE(contains(
            r.output, "warplab run: no window can be shown: SDL_VIDEODRIVER=" + driver + " draws into no screen"))
            << r.output;
    }
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(10));
    EXPECT_TRUE(sessionIn(dir).empty());
}

}  // namespace
