// `warplab check`, the supervisor's pre-flight, on Xvfb and Mesa llvmpipe: a display that
// reports no refresh rate, no vsync, a software renderer's frame times. Every line is asserted:
// the machine's own (whose numbers vary) by its form and by its verdict against its numbers.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <regex>
#include <sstream>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

#include "cli/cli_support.h"
#include "session/results_lock.h"

namespace {

using warplab::testing::contains;
using warplab::testing::Result;
using warplab::testing::runCommand;

std::string scratch(const std::string& name) { return warplab::testing::scratch("check", name); }

Result check(const std::string& arguments) {
    return runCommand("SDL_AUDIODRIVER=dummy " + warplab::testing::onXvfb() + std::string(WARPLAB_BINARY) +
                      " check --width 160 --height 90 " + arguments);
}

std::vector<std::string> linesOf(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::string protocol(const std::string& name) {
    return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name + ".json";
}

const char* const kGl =
    "warn  gl: llvmpipe \\(LLVM [^)]+\\), OpenGL 4\\.[0-9] \\(Core Profile\\) Mesa [0-9.]+: a software "
    "renderer, for tests and replays, not for participants";
const char* const kVsync =
    "warn  vsync: off: the driver refused a swap interval of 1; a session would pace its frames by a timer";
const char* const kMeasured =
    "warn  measured refresh: [0-9.]+ Hz over [0-9.]+ s of swaps: without vsync that is the "
    "machine's speed, not the display's";
const char* const kAudio = "warn  audio: SDL's dummy audio driver plays nowhere (SDL_AUDIODRIVER)";

// A frame-time line: its form, and a verdict that says what its numbers say (FAIL: more than
// 1 % of the frames longer than one refresh, as a session flags them, and how many frames a
// second a session would show; warn: some). Returns whether it fails.
bool expectFrameTime(const std::string& line, const std::string& condition, const std::string& refresh,
                     const std::string& budget) {
    const std::regex form(
        "(ok  |warn|FAIL)  frame time " + condition +
        ": median ([0-9.]+) ms, p95 [0-9.]+ ms, max [0-9.]+ ms over ([0-9]+) frames at 160x90; ([0-9]+) longer than "
        "one refresh \\(" +
        budget + " ms at " + refresh + "\\)(.*)");
    std::smatch m;
    EXPECT_TRUE(std::regex_match(line, m, form)) << line;
    if (m.empty()) return false;
    const double medianMs = std::stod(m[2]), frames = std::stod(m[3]), late = std::stod(m[4]);
    EXPECT_GT(frames, 10) << line;
    const std::string verdict = m[1];
    if (late > 0.01 * frames) {
        EXPECT_EQ(verdict, "FAIL") << line;
        // How many frames a second a session would show: the refresh over the whole refreshes
        // the larger of the two medians spans. Each is printed to a tenth of a millisecond:
        // either side of it may be the one the tool divided.
        const std::regex shortfall(
            ": more than 1 % of a session's frames would miss their vsync, and it would be flagged; its frames that "
            "draw a render take a median ([0-9.]+) ms, so a session would show about ([0-9.]+) frames a second of the "
            "display's ([0-9]+)");
        std::smatch s;
        const std::string rest = m[5];
        EXPECT_TRUE(std::regex_match(rest, s, shortfall)) << line;
        if (s.empty()) return true;
        const double refreshHz = std::stod(refresh), drawingMs = std::stod(s[1]), shows = std::stod(s[2]);
        EXPECT_EQ(std::stod(s[3]), refreshHz) << line;
        EXPECT_GT(drawingMs, 0.0) << line;
        auto showsAt = [&](double ms) { return refreshHz / std::max(1.0, std::ceil(ms * refreshHz / 1000.0)); };
        const double typical = std::max(medianMs, drawingMs);
        EXPECT_TRUE(std::abs(shows - showsAt(typical - 0.05)) < 0.051 ||
                    std::abs(shows - showsAt(typical + 0.05)) < 0.051)
            << line;
    } else if (late > 0) {
        EXPECT_EQ(verdict, "warn") << line;
        EXPECT_EQ(m[5], ": those would miss their vsync");
    } else {
        EXPECT_EQ(verdict, "ok  ") << line;
        EXPECT_EQ(m[5], "");
    }
    return verdict == "FAIL";
}

// A cadence line: its form, the schedule's shortest and longest intervals between new images,
// and a verdict that says what its numbers say (FAIL: the p95 is longer than the shortest).
// Returns whether it fails.
bool expectCadence(const std::string& line, const std::string& condition, int refreshHz, int shortest, int longest) {
    const std::regex form("(ok  |FAIL)  cadence " + condition +
                          ": its frames that make a new image take p95 ([0-9.]+) ms over [0-9]+ frames, (within|longer "
                          "than) the ([0-9.]+) ms its schedule leaves the shortest of its intervals between new images "
                          "\\(" +
                          std::to_string(shortest) + (shortest == 1 ? " refresh" : " refreshes") + " at " +
                          std::to_string(refreshHz) + " Hz; they run " + std::to_string(shortest) + " to " +
                          std::to_string(longest) + "\\)(.*)");
    std::smatch m;
    EXPECT_TRUE(std::regex_match(line, m, form)) << line;
    if (m.empty()) return false;
    char budget[16];
    std::snprintf(budget, sizeof budget, "%.2f", 1000.0 * shortest / refreshHz);
    EXPECT_EQ(m[4], budget) << line;
    const bool fails = std::stod(m[2]) > 1000.0 * shortest / refreshHz + 0.05;
    if (std::abs(std::stod(m[2]) - 1000.0 * shortest / refreshHz) > 0.05) {  // the p95 is printed to a tenth
        EXPECT_EQ(m[1], fails ? "FAIL" : "ok  ") << line;
        EXPECT_EQ(m[3], fails ? "longer than" : "within") << line;
    }
    EXPECT_EQ(
        m[5],
        m[1] == "FAIL" ? ": its new images would reach the screen after the refreshes the schedule gives them" : "")
        << line;
    return m[1] == "FAIL";
}

void expectMachineLines(const std::vector<std::string>& lines) {
    ASSERT_GE(lines.size(), 4u);
    EXPECT_TRUE(std::regex_match(lines[0], std::regex(kGl))) << lines[0];
    EXPECT_EQ(lines[2], kVsync);
    EXPECT_TRUE(std::regex_match(lines[3], std::regex(kMeasured))) << lines[3];
}

// shooter-thesis refuses a display not at its 120 Hz, and Xvfb's reports none: FAIL, exit 1.
TEST(Check, OnXvfbTheThesisProtocolFailsTheUnknownRefresh) {
    const std::string dir = scratch("thesis");
    const auto r = check("--protocol " + protocol("shooter-thesis") + " --out " + dir);
    EXPECT_EQ(r.status, 1) << r.output;
    const auto lines = linesOf(r.output);
    ASSERT_EQ(lines.size(), 13u) << r.output;
    expectMachineLines(lines);
    EXPECT_EQ(lines[1],
              "FAIL  refresh: the display reports no refresh rate, so it cannot be checked against the "
              "120 Hz that protocol '" +
                  protocol("shooter-thesis") +
                  "' needs; set the display to 120 Hz on a system that reports it (or pass "
                  "--allow-refresh-mismatch for a pilot)");
    // Each of its conditions once, in the protocol's order, and whether it keeps its cadence.
    expectFrameTime(lines[4], "conv120", "120 Hz", "8.33");
    expectCadence(lines[5], "conv120", 120, 1, 1);
    expectFrameTime(lines[6], "conv15", "120 Hz", "8.33");
    expectCadence(lines[7], "conv15", 120, 8, 8);
    expectFrameTime(lines[8], "warp15to120", "120 Hz", "8.33");
    expectCadence(lines[9], "warp15to120", 120, 1, 1);
    EXPECT_EQ(lines[10], "ok    results folder: '" + dir + "' is writable and no session holds it");
    // 248385 frames: the bot's session, which replays the same on every machine.
    EXPECT_TRUE(std::regex_match(lines[11],
                                 std::regex("ok    disk: [0-9.]+ [kMG]B free in '" + dir +
                                            "'; a session of shooter-thesis writes about [0-9.]+ MB and "
                                            "needs [0-9.]+ MB free \\(248385 frames by its bot at [0-9]+ "
                                            "bytes each, doubled for a participant, doubled again as it "
                                            "finishes\\)")))
        << lines[11];
    EXPECT_EQ(lines[12], kAudio);
}

// shooter-quick warns of another refresh, so only the machine's speed can fail it: exit 1
// exactly when a frame-time or cadence line fails (on llvmpipe under load, it may).
TEST(Check, OnXvfbTheQuickProtocolWarnsOfTheUnknownRefreshAndFailsOnlyOnSpeed) {
    const std::string dir = scratch("quick");
    const auto r = check("--protocol " + protocol("shooter-quick") + " --out " + dir);
    const auto lines = linesOf(r.output);
    ASSERT_EQ(lines.size(), 13u) << r.output;
    expectMachineLines(lines);
    EXPECT_EQ(lines[1],
              "warn  refresh: the display reports no refresh rate, so it cannot be checked against the "
              "120 Hz that protocol '" +
                  protocol("shooter-quick") + "' needs; a session would pace its frames by a timer");
    bool slow = false;
    const char* const conditions[] = {"conv120", "conv15", "warp15to120"};
    const int shortest[] = {1, 8, 1};
    for (int i = 0; i < 3; ++i) {
        slow = expectFrameTime(lines[4 + 2 * i], conditions[i], "120 Hz", "8.33") || slow;
        slow = expectCadence(lines[5 + 2 * i], conditions[i], 120, shortest[i], shortest[i]) || slow;
    }
    EXPECT_EQ(lines[10], "ok    results folder: '" + dir + "' is writable and no session holds it");
    EXPECT_TRUE(contains(lines[11], "; a session of shooter-quick writes about ")) << lines[11];
    EXPECT_EQ(lines[12], kAudio);
    EXPECT_EQ(r.status, slow ? 1 : 0) << r.output;
}

// A protocol at 144 Hz with uneven conditions: each is held against its own shortest interval
// between new images -- 60 fps 2 refreshes, 90 fps with jitter and hitches 1 -- not one refresh.
TEST(Check, AnUnevenConditionIsHeldAgainstItsShortestInterval) {
    const std::string dir = scratch("uneven");
    std::ofstream(dir + "/uneven.json") << R"({"format_version":8,"name":"uneven","game":"shooter",
 "display":{"refresh_hz":144,"refresh_mismatch":"warn"},
 "conditions":{"even60":{"render_hz":60},
  "rough60":{"render_hz":60,"frame_time_jitter":{"distribution":"normal","sd_ms":4},"hitches":{"ms":100,"every_s":0.5}}},
 "acclimation":{"duration_s":0.5,"level":0,"mode":"even60"},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.5,
  "high_mode":"even60","low_mode":"rough60"},
 "test":{"conditions":["even60","rough60"],"targets_per_condition":1,"timeout_s":0.5,"pause_s":0.25}})";
    const auto r = check("--protocol " + dir + "/uneven.json --out " + dir);
    const auto lines = linesOf(r.output);
    ASSERT_EQ(lines.size(), 11u) << r.output;
    bool slow = expectFrameTime(lines[4], "even60", "144 Hz", "6.94");
    slow = expectCadence(lines[5], "even60", 144, 2, 3) || slow;
    slow = expectFrameTime(lines[6], "rough60", "144 Hz", "6.94") || slow;
    const std::regex rough("(ok  |FAIL)  cadence rough60: .* \\(1 refresh at 144 Hz; they run 1 to ([0-9]+)\\).*");
    std::smatch m;
    ASSERT_TRUE(std::regex_match(lines[7], m, rough)) << lines[7];
    EXPECT_GE(std::stoi(m[2]), 15) << "the 100 ms hitch";
    slow = expectCadence(lines[7], "rough60", 144, 1, std::stoi(m[2])) || slow;
    EXPECT_EQ(r.status, slow ? 1 : 0) << r.output;
}

// Without a protocol it checks the machine alone; a folder that is missing, or that a session
// holds, fails with the sentence `run` would refuse it with.
TEST(Check, AMissingResultsFolderOrOneInUseFails) {
    const std::string dir = scratch("folder");
    auto r = check("--out " + dir + "/missing");
    EXPECT_EQ(r.status, 1) << r.output;
    auto lines = linesOf(r.output);
    ASSERT_EQ(lines.size(), 6u) << r.output;
    expectMachineLines(lines);
    EXPECT_EQ(lines[1], "warn  refresh: the display reports no refresh rate");
    EXPECT_EQ(lines[4], "FAIL  results folder: Results folder '" + dir + "/missing' does not exist.");
    EXPECT_EQ(lines[5], kAudio);

    const warplab::session::ResultsFolderLock held(dir, "P07", "shooter-thesis");
    r = check("--out " + dir);
    EXPECT_EQ(r.status, 1) << r.output;
    lines = linesOf(r.output);
    ASSERT_EQ(lines.size(), 6u) << r.output;
    EXPECT_EQ(lines[4].rfind("FAIL  results folder: Results folder '" + dir +
                                 "' is in use by another warplab session (participant P07, protocol shooter-thesis, "
                                 "pid " +
                                 std::to_string(::getpid()),
                             0),
              0u)
        << lines[4];
}

// No display: the window's checks fail in one line, at once; the rest are still checked.
TEST(Check, WithoutADisplayTheWindowFailsAndTheRestIsChecked) {
    const std::string dir = scratch("no-display");
    const auto started = std::chrono::steady_clock::now();
    const auto r = runCommand("env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER SDL_AUDIODRIVER=dummy timeout 10 " +
                              std::string(WARPLAB_BINARY) + " check --out " + dir);
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5));
    EXPECT_EQ(r.status, 1);
    const auto lines = linesOf(r.output);
    ASSERT_EQ(lines.size(), 4u) << r.output;
    EXPECT_EQ(lines[0],
              "FAIL  window: no window can be shown: DISPLAY is not set (start warplab from the desktop, or set "
              "DISPLAY=:0 for the machine's own screen)");
    EXPECT_EQ(lines[1], "ok    results folder: '" + dir + "' is writable and no session holds it");
    EXPECT_TRUE(std::regex_match(lines[2], std::regex("ok    disk: [0-9.]+ [kMG]B free in '" + dir + "'"))) << lines[2];
    EXPECT_EQ(lines[3], kAudio);
}

TEST(Check, HelpAndABadCommandLine) {
    auto r = warplab::testing::warplab("check --help");
    EXPECT_EQ(r.status, 0);
    EXPECT_TRUE(contains(r.output, "usage: warplab check [--protocol P]")) << r.output;
    EXPECT_TRUE(contains(r.output, "--allow-refresh-mismatch")) << r.output;
    EXPECT_TRUE(contains(warplab::testing::warplab("--help").output, "\n  check ")) << "listed among the commands";
    for (const std::string bad : {"--width 0", "--display -1", "--bogus"}) {
        r = warplab::testing::warplab("check " + bad);
        EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
        EXPECT_EQ(r.lines(), 1) << r.output;
    }
}

}  // namespace

namespace {

// --photon shows the marker's square wave and says what a meter over it should read: at
// Xvfb's unknown refresh the frames are paced at 60 Hz, so 0.25 s is 15 frames and a cycle 0.5 s.
TEST(Check, ThePhotonPatternSaysWhatAMeterShouldRead) {
    const Result r = check("--photon bottom_right");
    EXPECT_TRUE(warplab::testing::contains(
        r.output,
        "photon: the marker in the bottom_right corner was white for 15 frames and black for 15, 10 times (5.0 s): "
        "a meter over it reads a 2.00 Hz square wave"))
        << r.output;
    const Result bad = check("--photon middle");
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_TRUE(warplab::testing::contains(bad.output, "photon: 'middle' is no corner for the marker")) << bad.output;
}

}  // namespace
