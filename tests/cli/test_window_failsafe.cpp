// A live session's window fails safe: no display is said at once, before any window; what a
// session needs is checked before its start screen; the window manager's close asks first;
// a window that leaves the participant pauses the session; a window destroyed or cut off by
// another program ends in one sentence with the session file intact. Real X events on Xvfb:
// xdotool unmaps, focuses, types into and destroys the window, and wm_close sends the close
// button's message as a window manager would.
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

using warplab::testing::tinyProtocol;

std::string warplabBinary() { return WARPLAB_BINARY; }

// A participant's session in the background on a fresh virtual X display, its output in
// DIR/out.txt, and `scene` (sh) acting on its window ($id) meanwhile; `waitfor TEXT [N]` waits
// until the output holds TEXT N times. Prints "exit STATUS" and the session's output.
Result sessionWith(const std::string& dir, const std::string& scene) {
    std::ofstream(dir + "/script.txt") << "start key enter\n";
    std::ofstream(dir + "/scene.sh")
        << "x=" << WARPLAB_XDOTOOL << "; wm_close=" << WARPLAB_WM_CLOSE << "; out=" << dir << "/out.txt\n"
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

long long numberAfter(const std::string& text, const std::string& prefix, std::size_t from = 0) {
    const std::size_t at = text.find(prefix, from);
    return at == std::string::npos ? -1 : std::stoll(text.substr(at + prefix.size()));
}

std::string replayOf(const std::string& session) { return warplab::testing::warplab("replay " + session).output; }

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

// What a session needs is checked before its start screen: the folder (it exists, is writable,
// no session holds it), room for the session, and a refresh the protocol accepts.
TEST(LiveWindow, AMissingResultsFolderOrARefusedRefreshStopsTheRunBeforeItsStartScreen) {
    const std::string dir = scratch("before-start");
    fs::create_directories(dir + "/shots");
    std::ofstream(dir + "/script.txt") << "start key esc\n";
    const std::string window = "SDL_AUDIODRIVER=dummy " + warplab::testing::onXvfb() + warplabBinary();
    const std::string shots = " --width 160 --height 90 --input-script " + dir + "/script.txt --screenshots " + dir +
        "/shots --participant M --seed 1";
    auto r = runCommand(window + " run --protocol " + tinyProtocol(dir) + " --out " + dir + "/missing" + shots);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.output, "warplab run: Results folder '" + dir + "/missing' does not exist.\n");
    EXPECT_FALSE(fs::exists(dir + "/shots/start.png")) << "the window opened";

    // shooter-thesis refuses a display not at its 120 Hz; Xvfb's, which reports no rate, too.
    const std::string thesis = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-thesis.json";
    r = runCommand(window + " run --protocol " + thesis + " --out " + dir + shots);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.output,
              "warplab run: the display reports no refresh rate, so it cannot be checked against the "
              "120 Hz that protocol '" +
                  thesis +
                  "' needs; set the display to 120 Hz on a system that reports it (or pass "
                  "--allow-refresh-mismatch for a pilot)\n");
    EXPECT_FALSE(fs::exists(dir + "/shots/start.png")) << "the start screen was shown";
    EXPECT_TRUE(sessionIn(dir).empty());
    // A pilot may: the run then paces by timer, as it says.
    r = runCommand(window + " run --protocol " + thesis + " --out " + dir + shots + " --allow-refresh-mismatch");
    EXPECT_EQ(r.status, 3) << "left at the start screen: " << r.output;
    EXPECT_TRUE(contains(r.output, "note: the display reports no refresh rate; frames are paced by a timer at 120 Hz"))
        << r.output;
    EXPECT_TRUE(fs::exists(dir + "/shots/start.png"));
}

// The window manager's close (its button, alt+F4) asks on a screen; Enter plays on, and a
// second close then Q ends the session, keeping everything as Esc then Q does.
TEST(LiveWindow, TheWindowManagersCloseAsksFirstAndKeepsEverything) {
    const std::string dir = scratch("close");
    const auto r = sessionWith(dir,
                               "sleep 0.5; $wm_close $id; waitfor 'asked to close'\n"
                               "sleep 1  # the screen waits for the supervisor\n"
                               "$x windowfocus --sync $id key Return\n"
                               "sleep 0.5; $wm_close $id; waitfor 'asked to close' 2\n"
                               "$x windowfocus --sync $id key q");
    ASSERT_TRUE(contains(r.output, "exit 3")) << r.output;  // ended early by the supervisor
    const long long first = numberAfter(r.output, "paused at frame ");
    const long long second = numberAfter(r.output, "paused at frame ", r.output.find("asked to close") + 1);
    ASSERT_GT(first, 0) << r.output;
    EXPECT_GT(second, first) << "Enter played on:\n" << r.output;
    EXPECT_TRUE(contains(r.output, "paused at frame " + std::to_string(first) + ": the window was asked to close"))
        << r.output;
    EXPECT_TRUE(contains(
        r.output,
        "session ended by the supervisor at frame " + std::to_string(second - 1) + "; everything recorded is kept"))
        << r.output;
    const std::string session = sessionIn(dir);
    const auto data = warplab::session::readSession(session);
    EXPECT_FALSE(data.completed);
    EXPECT_EQ(static_cast<long long>(data.inputs.size()), second) << "every frame up to the second close is kept";
    const std::string replayed = replayOf(session);
    EXPECT_TRUE(contains(replayed, "outcomes reproduced (")) << replayed;
}

// A window unmapped (minimised, or another window in front: it loses the focus) pauses the
// session like Esc; nothing is recorded until Enter, back in the window, resumes it.
TEST(LiveWindow, AWindowThatLeavesTheParticipantPausesTheSession) {
    const std::string dir = scratch("focus");
    const auto r = sessionWith(dir,
                               "sleep 0.5; $x windowunmap --sync $id; waitfor 'lost the focus'\n"
                               "sleep 2  # away: the trial must not run on\n"
                               "$x windowmap --sync $id windowfocus --sync $id; sleep 0.3; $x key Return\n"
                               "sleep 0.5; $x key Escape q");
    ASSERT_TRUE(contains(r.output, "exit 3")) << r.output;  // ended early by the supervisor
    const long long paused = numberAfter(r.output, "paused at frame ");
    const long long ended = numberAfter(r.output, "session ended by the supervisor at frame ");
    ASSERT_GT(paused, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "paused at frame " + std::to_string(paused) + ": the window lost the focus"))
        << r.output;
    EXPECT_GT(ended, paused) << "Enter resumed it:\n" << r.output;
    const auto data = warplab::session::readSession(sessionIn(dir));
    ASSERT_EQ(static_cast<long long>(data.inputs.size()), ended + 1);
    // Nothing of the 2 s away is in the record: the session's display time falls short of the
    // run's wall time by at least that, and no frame's measured time spans the pause.
    const double wall = std::stod(r.output.substr(r.output.find("wall ") + 5));
    EXPECT_LT(static_cast<double>(ended + 1) / 120.0, wall - 2.0) << r.output;
    for (const auto& f : data.frames) EXPECT_LT(f.frameMs, 1000.0) << "frame " << f.frame;
    EXPECT_TRUE(contains(replayOf(sessionIn(dir)), "outcomes reproduced ("));
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

TEST(LiveWindow, InfoOfAWindowSaysTheDisplaysRefreshAndWhetherVsyncTook) {
    const auto r = runCommand(warplab::testing::onXvfb() + warplabBinary() + " info --gl window");
    ASSERT_EQ(r.status, 0) << r.output;
    // Xvfb reports no refresh rate, and Mesa's software GLX there takes no swap interval.
    EXPECT_TRUE(contains(r.output, "\nrefresh:  unknown: the display reports none (0 Hz)\n")) << r.output;
    EXPECT_TRUE(contains(r.output, "\nvsync:    off: the driver refused a swap interval of 1\n")) << r.output;
}

}  // namespace
