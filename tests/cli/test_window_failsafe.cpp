// A live session's window fails safe: without a display to show it on, a run says so at once,
// before any window, rather than waiting at a start screen nobody sees; a window destroyed or
// cut off by another program ends in one sentence with the session file intact. Real X events
// on Xvfb: xdotool destroys the window.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

#include "cli/cli_support.h"
#include "session/session_store.h"

namespace {

namespace fs = std::filesystem;

using warplab::testing::contains;
using warplab::testing::Result;
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

// A participant's session in the background on a fresh virtual X display, its output in
// DIR/out.txt, and `scene` (sh) acting on its window ($id) meanwhile; `waitfor TEXT [N]` waits
// until the output holds TEXT N times. Prints "exit STATUS" and the session's output.
Result sessionWith(const std::string& dir, const std::string& scene) {
    std::ofstream(dir + "/script.txt") << "start key enter\n";
    std::ofstream(dir + "/scene.sh")
        << "x=" << WARPLAB_XDOTOOL << "; out=" << dir << "/out.txt\n"
        << "waitfor() { i=0; until [ \"$(grep -c \"$1\" $out)\" -ge \"${2:-1}\" ]; do i=$((i+1));"
           " if [ $i -gt 600 ]; then echo \"never saw '$1'\"; kill $pid; cat $out; exit 99; fi; sleep 0.05; done; }\n"
        << "started=$(date +%s.%N)\n"
        << warplabBinary() << " run --seed 1 --protocol " << tinyProtocol(dir) << " --participant F --out " << dir
        << " --width 160 --height 90 --input-script " << dir << "/script.txt > $out 2>&1 &\n"
        << "pid=$!\n"
        << "id=$($x search --sync --name '^warplab: ' | head -1)\n"
        << "waitfor '^session '\n"
        << scene << "\n"
        << "wait $pid; echo \"exit $?\"\n"
        << "echo \"wall $(echo \"$(date +%s.%N) - $started\" | bc)\"\n"
        << "cat $out\n";
    return runCommand("SDL_AUDIODRIVER=dummy " + warplab::testing::onXvfb() + "sh " + dir + "/scene.sh");
}

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

// Another program destroys the window (xdotool windowclose) or kills its connection (xkill,
// xdotool windowkill): one sentence saying so, exit 1, and the session file as a kill leaves
// it, replaying every committed trial. Xlib alone printed "X Error of failed request:
// BadDrawable" with the request's opcodes and serial numbers.
TEST(LiveWindow, AWindowDestroyedUnderTheSessionEndsInOneSentence) {
    for (const std::string how : {"windowclose", "windowkill"}) {
        const std::string dir = scratch(how);
        const auto r = sessionWith(dir, "sleep 1; $x " + how + " $id");
        EXPECT_TRUE(contains(r.output, "exit 1")) << r.output;
        EXPECT_FALSE(contains(r.output, "X Error")) << r.output;
        EXPECT_FALSE(contains(r.output, "XIO")) << r.output;
        if (how == "windowclose")
            EXPECT_TRUE(std::regex_search(r.output,
                                          std::regex("\nwarplab run: the window was destroyed by another "
                                                     "program \\(the X server answered Bad(Drawable|Window) "
                                                     "to a request on it\\)\n")))
                << r.output;
        else
            EXPECT_TRUE(std::regex_search(r.output,
                                          std::regex("\nwarplab: the connection to the X display ':[0-9]+' "
                                                     "was lost \\(the X server ended, or another program "
                                                     "killed the window\\); a session keeps every trial "
                                                     "committed before it\n")))
                << r.output;
        const std::string session = sessionIn(dir);
        ASSERT_FALSE(session.empty()) << r.output;
        const auto replay = warplab::testing::warplab("replay " + session);
        EXPECT_EQ(replay.status, 3) << "incomplete, not damaged: " << replay.output;
        EXPECT_TRUE(contains(replay.output, "outcomes reproduced (")) << replay.output;
    }
}

}  // namespace
