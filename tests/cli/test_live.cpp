// Sessions in a real SDL window (Mesa GLX under Xvfb): a participant's input scripted as window
// events, the supervisor's pause and abort, and the bot in the window writing the same session
// as headless. Xvfb reports no refresh rate, so these runs use protocols that warn of it (a
// protocol that refuses a wrong refresh refuses an unknown one) and pace frames by timer, as
// the tool says it will; feedback sounds go to SDL's dummy audio driver.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>

#include "cli/cli_support.h"
#include "gl/gl_test_support.h"
#include "session/records.h"
#include "session/results_lock.h"
#include "session/pacing.h"
#include "session/session_store.h"
#include "image/image.h"

namespace {

namespace fs = std::filesystem;

using warplab::testing::contains;
using warplab::testing::Result;
using warplab::testing::runCommand;
using warplab::testing::sessionIn;

// warplab in a window on a fresh virtual X display.
Result inWindowAsTheDisplayGoes(const std::string& arguments) {
    return runCommand("SDL_AUDIODRIVER=dummy " + warplab::testing::onXvfb() + std::string(WARPLAB_BINARY) + " " +
                      arguments);
}
// ... with every display frame shown (--every-frame): these tests name session frames in their
// scripts and screenshots, and Mesa's llvmpipe under Xvfb is slower than the protocols' rates,
// so a run that follows the display would skip the frames they name.
Result inWindow(const std::string& arguments) {
    const bool run = arguments.rfind("run ", 0) == 0;
    return inWindowAsTheDisplayGoes(arguments + (run ? " --every-frame" : ""));
}

std::string scratch(const std::string& name) { return warplab::testing::scratch("live", name); }

// "" when two sessions hold the same events and inputs, record for record (a window's session
// and the headless one the same player plays); else the first that differs.
std::string firstRecordDifference(const warplab::session::SessionData& a, const warplab::session::SessionData& b) {
    if (a.events.size() != b.events.size())
        return std::to_string(a.events.size()) + " events against " + std::to_string(b.events.size());
    for (std::size_t i = 0; i < a.events.size(); ++i)
        if (const std::string d = warplab::session::firstDifference(a.events[i], b.events[i]); !d.empty())
            return "event " + std::to_string(i) + ": " + d;
    if (a.inputs.size() != b.inputs.size())
        return std::to_string(a.inputs.size()) + " inputs against " + std::to_string(b.inputs.size());
    for (std::size_t i = 0; i < a.inputs.size(); ++i)
        if (const std::string d = warplab::session::firstDifference(a.inputs[i], b.inputs[i]); !d.empty())
            return "input " + std::to_string(i) + ": " + d;
    return "";
}

using warplab::testing::tinyProtocol;

// The click game in a few seconds: two conditions (one of them interpolating between renders),
// one short match each, each followed by its four ratings; it too warns of another refresh.
std::string tinyClickProtocol(const std::string& dir) {
    std::ofstream(dir + "/tiny-click.json") << R"({"format_version":1,"name":"click-tiny","game":"click",
 "display":{"refresh_mismatch":"warn"},
 "matches":{"match_s":1.0,"modes":["conv30","bireproj15to60"],"rounds":[{"name":"scored","scored":true,"matches_per_mode":1}]}})";
    return dir + "/tiny-click.json";
}

std::string replayOf(const std::string& session) {
    return runCommand(std::string(WARPLAB_BINARY) + " replay " + session).output;
}

TEST(LiveSession, AScriptedParticipantRunsTheWholeFlowAndTheSessionReplays) {
    const std::string dir = scratch("participant");
    std::ofstream(dir + "/script.txt") << "# the supervisor starts, the participant turns and shoots\n"
                                          "start key enter\n5 move 40 0\n12 click\n30 move 0 -20\n"
                                          "# Esc pauses; Enter resumes; nothing is recorded meanwhile\n"
                                          "60 key esc\n60 key enter\n"
                                          "# the supervisor's Enter after acclimation begins the test\n"
                                          "200 key enter\nend key enter\n";
    const auto r = inWindow("run --seed 1 --protocol " + tinyProtocol(dir) + " --participant H1 --out " + dir +
                            " --width 192 --height 108 --input-script " + dir + "/script.txt --screenshots " + dir +
                            " --screenshot-frames 12,20");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "paced by a timer")) << r.output;
    const std::string session = sessionIn(dir);
    ASSERT_FALSE(session.empty()) << r.output;
    const auto data = warplab::session::readSession(session);
    EXPECT_TRUE(data.completed) << data.note;
    EXPECT_TRUE(contains(data.header.player, "human")) << data.header.player;
    EXPECT_EQ(data.header.displayWidth, 192);
    ASSERT_GT(data.inputs.size(), 201u);
    // The window's input, as the script gave it, on the frames it named.
    EXPECT_EQ(data.inputs[5].mouseDx, 40.0);
    EXPECT_EQ(data.inputs[12].buttons, 1u);
    EXPECT_EQ(data.inputs[30].mouseDy, -20.0);
    EXPECT_EQ(data.inputs[200].keys, 1u);
    int shotsAt12 = 0, frozen = 0;
    for (const auto& e : data.events) shotsAt12 += e.type == "shot" && e.frame == 12;
    for (const auto& f : data.frames) frozen += f.kind == "frozen";
    EXPECT_EQ(shotsAt12, 1);
    EXPECT_GT(frozen, 0);
    for (const auto& f : data.frames) {
        EXPECT_GT(f.frameMs, 0.0) << "frame " << f.frame << " has no measured time";
        EXPECT_GT(f.renderMs, 0.0) << "frame " << f.frame << " has no render time";
        EXPECT_LT(f.renderMs, f.frameMs + 1e-9) << "frame " << f.frame << " took longer to make than to show";
    }
    const std::string replay = replayOf(session);
    EXPECT_TRUE(contains(replay, "outcomes reproduced")) << replay;
    EXPECT_FALSE(contains(replay, "differs")) << replay;
    // The screens: start, the frame of the shot (reticle on the hallway), the HIT/MISS pause, the end.
    for (const char* name : {"start", "frame_12", "frame_20", "end"})
        EXPECT_TRUE(fs::exists(dir + "/" + name + ".png")) << name;
    const auto start = warplab::image::readPng(dir + "/start.png");
    EXPECT_EQ(start.width, 192);
    const auto shot = warplab::image::readPng(dir + "/frame_12.png");
    const std::uint8_t* centre = shot.at(96, 54);
    EXPECT_GT(centre[0] + centre[1] + centre[2], 600) << "no reticle at the centre";
    // Each screen against its approved reference (scripts/approve-references.sh), with the GL
    // tests' thresholds: the frames are the same offscreen renders the window shows.
    EXPECT_TRUE(warplab::testing::matchesReference("live_start", start));
    EXPECT_TRUE(warplab::testing::matchesReference("live_shot", shot));
    EXPECT_TRUE(warplab::testing::matchesReference("live_miss_pause", warplab::image::readPng(dir + "/frame_20.png")));
    EXPECT_TRUE(warplab::testing::matchesReference("live_end", warplab::image::readPng(dir + "/end.png")));
}

TEST(LiveSession, TheSupervisorCanEndASessionAndKeepsWhatWasRecorded) {
    const std::string dir = scratch("abort");
    std::ofstream(dir + "/script.txt") << "start key enter\n80 key esc\n80 key q\n";
    const auto r = inWindow("run --seed 1 --protocol " + tinyProtocol(dir) + " --participant A1 --out " + dir +
                            " --width 160 --height 90 --input-script " + dir + "/script.txt");
    // Not 0, which a complete session exits with: a script chaining runs must not go on as if
    // it were one. 3 is what replay says of the file: incomplete.
    ASSERT_EQ(r.status, 3) << r.output;
    EXPECT_TRUE(contains(r.output,
                         "ended by the supervisor at frame 79; everything recorded is kept "
                         "(warplab run --resume carries it on)"))
        << r.output;
    const auto data = warplab::session::readSession(sessionIn(dir));
    EXPECT_FALSE(data.completed);
    EXPECT_EQ(data.inputs.size(), 80u) << "every frame up to the pause is kept";
    const std::string replayed = replayOf(sessionIn(dir));
    EXPECT_TRUE(contains(replayed, "outcomes reproduced"));
    // 80 frames at 120 Hz: said as such, not as "0 s of display time".
    EXPECT_TRUE(contains(replayed, "80 frames, 0.66 s of display time replayed")) << replayed;
    EXPECT_EQ(runCommand(std::string(WARPLAB_BINARY) + " replay " + sessionIn(dir)).status, 3);
}

// S on the start screen plays the feedback sounds for the supervisor; the session starts only
// with Enter after it, and records nothing of the check.
TEST(LiveSession, SOnTheStartScreenPlaysTheFeedbackSoundsBeforeEnterStarts) {
    const std::string dir = scratch("sound-check");
    std::ofstream(dir + "/script.txt") << "start key s\nstart key enter\n10 key esc\n10 key q\n";
    const auto r = inWindow("run --protocol " + tinyProtocol(dir) + " --participant S1 --out " + dir +
                            " --width 160 --height 90 --input-script " + dir + "/script.txt");
    ASSERT_EQ(r.status, 3) << r.output;
    EXPECT_TRUE(contains(r.output, "sound check: hit miss timeout")) << r.output;
    EXPECT_TRUE(contains(r.output, "ended by the supervisor at frame 9")) << r.output;
    const auto data = warplab::session::readSession(sessionIn(dir));
    EXPECT_EQ(data.inputs.size(), 10u);
}

// The machine's own audio (no SDL_AUDIODRIVER=dummy): where it has no sound card, as under Xvfb
// here, the run says so in its own one note; ALSA's library printed eight raw "ALSA lib ..."
// lines before it.
TEST(LiveSession, AMachineWithoutSoundSaysSoOnceWithoutALSAsOwnLines) {
    const std::string dir = scratch("no-sound");
    std::ofstream(dir + "/script.txt") << "start key s\nstart key enter\n5 key esc\n5 key q\n";
    const auto r = runCommand("env -u SDL_AUDIODRIVER " + warplab::testing::onXvfb() + std::string(WARPLAB_BINARY) +
                              " run --seed 1 --protocol " + tinyProtocol(dir) + " --participant N --out " + dir +
                              " --width 160 --height 90 --every-frame --input-script " + dir + "/script.txt");
    ASSERT_EQ(r.status, 3) << r.output;
    EXPECT_TRUE(contains(r.output, "sound check: hit miss timeout")) << r.output;
    EXPECT_FALSE(contains(r.output, "ALSA lib")) << r.output;
}

// The window changes how frames reach a person, never what the session is.
TEST(LiveSession, TheBotInTheWindowWritesTheSameSessionAsHeadless) {
    for (const std::string protocol : {"tiny", "click-tiny"}) {
        const std::string dir = scratch("bot-" + protocol), headless = scratch("bot-headless-" + protocol);
        const std::string path = protocol == "tiny" ? tinyProtocol(dir) : tinyClickProtocol(dir);
        const auto window = inWindow("run --protocol " + path + " --participant B --out " + dir +
                                     " --width 160 --height 90 --player bot:3 --seed 4 --screenshots " + dir +
                                     " --screenshot-frames 40,100");
        ASSERT_EQ(window.status, 0) << window.output;
        const auto plain =
            runCommand(std::string(WARPLAB_BINARY) + " run --protocol " + path + " --participant B --out " + headless +
                       " --headless --width 160 --height 90 --player bot:3 --seed 4");
        ASSERT_EQ(plain.status, 0) << plain.output;
        const auto a = warplab::session::readSession(sessionIn(dir));
        const auto b = warplab::session::readSession(sessionIn(headless));
        EXPECT_TRUE(a.completed) << a.note;
        ASSERT_EQ(firstRecordDifference(a, b), "") << protocol;
    }
    // Frame 100 of the tiny click session is on the first rating screen: the dark backdrop
    // (its top-left corner) and the seven boxes across the middle.
    const auto rating = warplab::image::readPng(
        (fs::path(WARPLAB_BINARY_DIR) / "test-output" / "live" / "bot-click-tiny" / "frame_100.png").string());
    ASSERT_EQ(rating.width, 160);
    const std::uint8_t* corner = rating.at(1, 1);
    EXPECT_LT(std::abs(corner[0] - 31), 4);
    EXPECT_LT(std::abs(corner[2] - 41), 4);
    int boxRows = 0;  // pixels of the boxes' light outline on the row through their middle
    for (int x = 0; x < 160; ++x) boxRows += rating.at(x, 50)[0] > 200;
    EXPECT_GE(boxRows, 7) << "no rating boxes";
    EXPECT_TRUE(warplab::testing::matchesReference("live_rating", rating));
}

// A machine too slow for its protocol (here: every 7th frame made 100 ms late, at 120 Hz 12
// display frames) plays at the display's pace, not in slow motion: each late frame is followed
// by as many skipped display frames as it was late, the frames shown took as long as the
// display frames they stand for, and the session is the one a bot plays headless, event for
// event and input for input (a player gives its input for every frame, shown or not).
TEST(LiveSession, ASlowMachineSkipsDisplayFramesAndKeepsTheProtocolsTime) {
    const std::string dir = scratch("slow"), headless = scratch("slow-headless");
    const std::string path = tinyProtocol(dir);
    const auto window =
        inWindowAsTheDisplayGoes("run --protocol " + path + " --participant B --out " + dir +
                                 " --width 160 --height 90 --player bot:3 --seed 4 --slow-frames 100:7");
    ASSERT_EQ(window.status, 0) << window.output;
    const auto plain = runCommand(std::string(WARPLAB_BINARY) + " run --protocol " + path + " --participant B --out " +
                                  headless + " --headless --width 160 --height 90 --player bot:3 --seed 4");
    ASSERT_EQ(plain.status, 0) << plain.output;
    const auto a = warplab::session::readSession(sessionIn(dir));
    const auto b = warplab::session::readSession(sessionIn(headless));
    ASSERT_TRUE(a.completed) << a.note;
    ASSERT_EQ(firstRecordDifference(a, b), "");

    // Every late frame is followed by the display frames it took, skipped; no other frame is.
    const double periodMs = 1000.0 / 120.0;
    int skipped = 0, lateByThe100Ms = 0;
    double shownMs = 0.0;
    // The display frames up to the last one shown and those it took: the game can end before
    // it steps through all of those (a late last frame), which are then never recorded.
    std::size_t displayFrames = 0;
    for (std::size_t i = 0; i < a.frames.size(); ++i) {
        const auto& f = a.frames[i];
        if (f.kind == warplab::session::kSkippedFrameKind) {
            ++skipped;
            continue;
        }
        displayFrames = i + static_cast<std::size_t>(f.missedVsyncs);
        if (i > 0)
            shownMs += f.frameMs;  // the first frame's time is the start's (shaders compiled), not a display frame's
        lateByThe100Ms += f.missedVsyncs >= 11;
        for (int k = 1; k <= f.missedVsyncs && i + k < a.frames.size(); ++k)
            ASSERT_EQ(a.frames[i + k].kind, warplab::session::kSkippedFrameKind) << "frame " << f.frame + k;
        if (i + f.missedVsyncs + 1 < a.frames.size()) {
            ASSERT_NE(a.frames[i + f.missedVsyncs + 1].kind, warplab::session::kSkippedFrameKind)
                << "frame " << f.frame + f.missedVsyncs + 1;
        }
    }
    EXPECT_GE(lateByThe100Ms, static_cast<int>(a.frames.size() / 7 / 13 / 2)) << "the slow frames were not late";
    EXPECT_GT(skipped, 0);
    // After the first, the shown frames' present-to-present times add up to the display frames
    // they stand for (a timer paces these frames: Xvfb reports no refresh): within 2 % and 3
    // periods.
    const double displayMs = static_cast<double>(displayFrames) * periodMs;
    EXPECT_NEAR(shownMs, displayMs, 0.02 * displayMs + 3 * periodMs) << skipped << " skipped of " << a.frames.size();

    // The pacing, printed and stored.
    EXPECT_TRUE(contains(window.output, "pacing per condition (a display frame every 8.33 ms)")) << window.output;
    std::vector<warplab::session::ConditionPacing> pacing;
    ASSERT_TRUE(warplab::session::parsePacing(a.summaries.at("pacing"), pacing));
    std::int64_t storedSkipped = 0;
    for (const auto& p : pacing) storedSkipped += p.skipped;
    EXPECT_EQ(storedSkipped, skipped);
    EXPECT_EQ(a.flags.count("missed_frames"), 1u);
    const std::string replay = replayOf(sessionIn(dir));
    EXPECT_TRUE(contains(replay, "outcomes reproduced")) << replay;
    EXPECT_FALSE(contains(replay, "differs")) << replay;
    // The export says it: the session's skipped frames, the pacing per condition.
    const std::string exported = scratch("slow-export");
    const auto ex =
        runCommand(std::string(WARPLAB_BINARY) + " export " + dir + " --out " + exported + " --include-flagged");
    ASSERT_EQ(ex.status, 0) << ex.output;
    auto cellsOf = [](const std::string& line) {
        std::vector<std::string> cells;
        std::stringstream in(line);
        for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
        return cells;
    };
    std::ifstream sessionsCsv(exported + "/sessions.csv");
    std::string header, row;
    std::getline(sessionsCsv, header);
    std::getline(sessionsCsv, row);
    const auto names = cellsOf(header), cells = cellsOf(row);
    const auto column = std::find(names.begin(), names.end(), "skipped_frames");
    ASSERT_NE(column, names.end()) << header;
    EXPECT_EQ(cells.at(static_cast<std::size_t>(column - names.begin())), std::to_string(skipped)) << row;
    std::ifstream pacingCsv(exported + "/pacing.csv");
    std::string pacingText((std::istreambuf_iterator<char>(pacingCsv)), std::istreambuf_iterator<char>());
    EXPECT_TRUE(contains(pacingText, "conv120,")) << pacingText;

    // replay --render writes the frames shown, and none for the frames skipped.
    std::int64_t firstSkipped = -1;
    for (const auto& f : a.frames)
        if (f.kind == warplab::session::kSkippedFrameKind && firstSkipped < 0) firstSkipped = f.frame;
    ASSERT_GT(firstSkipped, 0);
    const std::string pictures = scratch("slow-render");
    const auto rendered =
        runCommand(std::string(WARPLAB_BINARY) + " replay " + sessionIn(dir) + " --render " + pictures + " --frames " +
                   std::to_string(firstSkipped - 1) + ":" + std::to_string(firstSkipped));
    ASSERT_EQ(rendered.status, 0) << rendered.output;
    EXPECT_TRUE(contains(rendered.output, "wrote 1 frames")) << rendered.output;
    EXPECT_TRUE(contains(rendered.output, "not 1 the session skipped")) << rendered.output;
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%07lld.png", static_cast<long long>(firstSkipped - 1));
    EXPECT_TRUE(fs::exists(pictures + name));
}

// A machine that cannot draw the protocol's frames at its refresh (llvmpipe at 640x360 against
// 120 Hz: a conventional frame takes several refreshes) shows the game in true time at the rate
// it manages, never frozen: the display frames a late frame took are stepped through without
// drawing renders no frame shown needs (FrameMaker draws a source when a frame made needs it).
// Before, every skipped frame still drew its render, so each late frame made the next later:
// one frame stayed up for 100 s while the game played on unseen. Every condition is shown at
// least every half second of wall time (more on a machine busy with other tests: see below),
// the loop's wall time stays within 1.5x the display time it played, and the session replays
// exactly.
TEST(LiveSession, AnOverloadedMachineShowsEveryConditionInTrueTime) {
    const std::string dir = scratch("overloaded");
    std::ofstream(dir + "/overloaded.json") << R"({"format_version":2,"name":"shooter-overloaded","game":"shooter",
 "display":{"refresh_mismatch":"warn"},
 "acclimation":{"duration_s":1.0,"level":0,"mode":"conv120"},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.5},
 "test":{"conditions":["conv15","conv120","warp15to120"],"targets_per_condition":3,"timeout_s":1.0,"pause_s":0.5,
         "supervisor_starts":false}})";
    const auto start = std::chrono::steady_clock::now();
    const auto window = inWindowAsTheDisplayGoes("run --protocol " + dir + "/overloaded.json --participant O --out " +
                                                 dir + " --width 640 --height 360 --player bot:5 --seed 5");
    const double wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(window.status, 0) << window.output;
    const auto a = warplab::session::readSession(sessionIn(dir));
    ASSERT_TRUE(a.completed) << a.note;

    std::map<std::string, std::int64_t> shown, skipped;
    std::map<std::string, double> longestMs;
    std::vector<double> makingMs;
    double loopMs = 0.0;
    for (std::size_t i = 1; i < a.frames.size(); ++i) {  // the first frame's time is the start's
        const auto& f = a.frames[i];
        if (f.kind == warplab::session::kSkippedFrameKind) {
            ++skipped[f.condition];
            continue;
        }
        ++shown[f.condition];
        loopMs += f.frameMs;
        makingMs.push_back(f.renderMs);
        longestMs[f.condition] = std::max(longestMs[f.condition], f.frameMs);
    }
    // A frame stays up while the next is made, and no longer: half a second, or on a machine
    // this busy (ctest runs tests side by side) four times what the slowest twentieth of the
    // frames took to make. Before, a frame stayed up for the renders of every frame skipped
    // behind it, growing without bound (seconds to minutes).
    std::sort(makingMs.begin(), makingMs.end());
    ASSERT_FALSE(makingMs.empty());
    const double p95MakingMs = makingMs[makingMs.size() * 95 / 100];
    const double longestAllowedMs = std::max(500.0, 4.0 * p95MakingMs);
    const double displayMs = static_cast<double>(a.frames.size() - 1) * 1000.0 / 120.0;
    for (const std::string condition : {"conv15", "conv120", "warp15to120"}) {
        SCOPED_TRACE(condition);
        EXPECT_GT(skipped[condition], 0) << "the machine must be overloaded for this case to mean anything";
        EXPECT_GE(shown[condition], 2) << skipped[condition] << " skipped";
        EXPECT_LE(longestMs[condition], longestAllowedMs)
            << shown[condition] << " shown, " << skipped[condition] << " skipped; p95 making " << p95MakingMs << " ms";
    }
    EXPECT_LE(loopMs, 1.5 * displayMs);
    // The whole run, window and shader compiles included, against the display time: within
    // 1.5x and 10 s for the start.
    EXPECT_LE(wallS, 1.5 * displayMs / 1000.0 + 10.0) << window.output;
    // The pacing says how far short it fell.
    EXPECT_TRUE(contains(window.output, "a second of 120")) << window.output;
    const std::string replay = replayOf(sessionIn(dir));
    EXPECT_TRUE(contains(replay, "outcomes reproduced")) << replay;
    EXPECT_FALSE(contains(replay, "differs")) << replay;
}

// A text question answered by typing in the window: the answer as typed, Backspace included,
// is the session's, and the session replays with it.
TEST(LiveSession, ATextQuestionIsTypedInTheWindowAndTheSessionReplays) {
    const std::string dir = scratch("typed");
    std::ofstream(dir + "/questions.json") << R"({"format_version":4,"name":"click-typed","game":"click",
 "display":{"refresh_mismatch":"warn"},
 "matches":{"match_s":1.0,"modes":["conv30"],"rounds":[{"name":"scored","scored":true,"matches_per_mode":1,
   "instructions":""}],
   "questions":[{"id":"comment","kind":"text","prompt":"How did it look?"},
                {"id":"better","kind":"choice","prompt":"Which?","options":["this","that"]}]}})";
    // Enter at the ready screen (frame 0); the match is frames 1-60; the question from 61, taking
    // answers from 91.
    std::ofstream(dir + "/script.txt") << "start key enter\n0 key enter\n95 type smooth, but laggx\n"
                                          "96 type \\by \u2014 ok\n100 key enter\n140 key 2\nend key enter\n";
    const auto r = inWindow("run --seed 1 --protocol " + dir + "/questions.json --participant T1 --out " + dir +
                            " --width 160 --height 90 --input-script " + dir + "/script.txt --screenshots " + dir +
                            " --screenshot-frames 97");
    ASSERT_EQ(r.status, 0) << r.output;
    const auto data = warplab::session::readSession(sessionIn(dir));
    EXPECT_TRUE(data.completed) << data.note;
    std::vector<std::string> answers;
    for (const auto& e : data.events)
        if (e.type == "answer") answers.push_back(e.detailJson);
    ASSERT_EQ(answers.size(), 2u) << r.output;
    EXPECT_TRUE(contains(answers[0], "\"text\":\"smooth, but laggy \u2014 ok\"")) << answers[0];
    EXPECT_TRUE(contains(answers[0], "\"answered_with\":\"typed\"")) << answers[0];
    EXPECT_TRUE(contains(answers[1], "\"text\":\"that\"")) << answers[1];
    EXPECT_EQ(data.inputs[96].text, "\by \u2014 ok");
    const std::string replay = replayOf(sessionIn(dir));
    EXPECT_TRUE(contains(replay, "outcomes reproduced")) << replay;
    EXPECT_FALSE(contains(replay, "differs")) << replay;
    // The question on screen as it was typed: its field holds light text.
    const auto typed = warplab::image::readPng(dir + "/frame_97.png");
    int light = 0;
    for (int y = 45; y < 53; ++y)
        for (int x = 40; x < 120; ++x) light += typed.at(x, y)[0] > 200;
    EXPECT_GT(light, 10) << "no typed text in the field";
}

// A window session ended by the supervisor mid-test and resumed in a window: its first frames
// after the resume point (the frozen last frame of a warp15to120 trial, a warp of a source
// rendered before that point) look exactly like the uninterrupted session's, since the sources
// were rendered again from the kept frames; and the whole is the uninterrupted session, event
// for event.
TEST(LiveSession, ASessionEndedMidwayResumesInTheWindowAsIfNeverStopped) {
    const std::string dir = scratch("resume"), whole = scratch("resume-whole"), probe = scratch("resume-probe");
    const std::string protocol = tinyProtocol(dir);
    const std::string play = " --width 160 --height 90 --player bot:3";
    std::ofstream(dir + "/script.txt") << "470 key esc\n470 key q\n";
    auto r = inWindow("run --protocol " + protocol + " --participant B --out " + dir + play + " --seed 4" +
                      " --input-script " + dir + "/script.txt");
    ASSERT_EQ(r.status, 3) << r.output;
    const std::string interrupted = sessionIn(dir);
    ASSERT_FALSE(warplab::session::readSession(interrupted).completed);
    // Where it resumes: what a headless resume of it says.
    r = runCommand(std::string(WARPLAB_BINARY) + " run --resume " + interrupted + " --out " + probe +
                   " --headless --player bot:3");
    ASSERT_EQ(r.status, 0) << r.output;
    const std::int64_t at = warplab::session::readSession(sessionIn(probe)).header.resumed.at(0).frame;
    ASSERT_GT(at, 200) << "resumed in the test phase, after a trial";
    std::string frames;
    for (std::int64_t f = at; f < at + 6; ++f) frames += (frames.empty() ? "" : ",") + std::to_string(f);

    const std::string resumedShots = scratch("resume-shots"), wholeShots = scratch("resume-whole-shots");
    // Its size is the interrupted session's.
    r = inWindow("run --resume " + interrupted + " --player bot:3 --screenshots " + resumedShots +
                 " --screenshot-frames " + frames);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "resuming " + interrupted + " at frame " + std::to_string(at))) << r.output;
    r = inWindow("run --protocol " + protocol + " --participant B --out " + whole + play + " --seed 4" +
                 " --screenshots " + wholeShots + " --screenshot-frames " + frames);
    ASSERT_EQ(r.status, 0) << r.output;

    std::string resumed;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".warplab-session" && entry.path().string() != interrupted)
            resumed = entry.path().string();
    ASSERT_FALSE(resumed.empty());
    const auto a = warplab::session::readSession(resumed);
    const auto b = warplab::session::readSession(sessionIn(whole));
    EXPECT_TRUE(a.completed) << a.note;
    ASSERT_EQ(a.events.size(), b.events.size());
    for (std::size_t i = 0; i < a.events.size(); ++i)
        ASSERT_EQ(warplab::session::firstDifference(a.events[i], b.events[i]), "") << "event " << i;
    ASSERT_EQ(a.inputs.size(), b.inputs.size());
    EXPECT_TRUE(contains(replayOf(resumed), "outcomes reproduced (")) << replayOf(resumed);
    for (std::int64_t f = at; f < at + 6; ++f) {
        const std::string name = "/frame_" + std::to_string(f) + ".png";
        const auto shown = warplab::image::readPng(resumedShots + name);
        const auto expected = warplab::image::readPng(wholeShots + name);
        ASSERT_EQ(shown.width, expected.width);
        EXPECT_EQ(shown.pixels, expected.pixels) << "frame " << f << " differs from the uninterrupted session's";
    }
}

// Kim et al.'s late-warp study (its quick protocol, conditions defined in the file) in a real
// window: the bot's session is the headless one, input for input and event for event, and it
// replays. About 45 s: the window paces the 43 s of display time in real time.
TEST(LiveSession, TheLateWarpProtocolRunsInTheWindowAsHeadless) {
    const std::string dir = scratch("kim"), headless = scratch("kim-headless");
    const std::string path = std::string(WARPLAB_SOURCE_DIR) + "/protocol/latewarp-kim-quick.json";
    const auto window =
        inWindow("run --protocol " + path + " --participant K --out " + dir +
                 " --width 160 --height 90 --player bot:3 --seed 4 --screenshots " + dir + " --screenshot-frames 4000");
    ASSERT_EQ(window.status, 0) << window.output;
    const auto plain = runCommand(std::string(WARPLAB_BINARY) + " run --protocol " + path + " --participant K --out " +
                                  headless + " --headless --width 160 --height 90 --player bot:3 --seed 4");
    ASSERT_EQ(plain.status, 0) << plain.output;
    const auto a = warplab::session::readSession(sessionIn(dir));
    const auto b = warplab::session::readSession(sessionIn(headless));
    EXPECT_TRUE(a.completed) << a.note;
    ASSERT_EQ(firstRecordDifference(a, b), "");
    std::set<std::string> conditions;
    for (const auto& e : a.events)
        if (e.type == "shot") conditions.insert(e.condition);
    EXPECT_EQ(conditions, (std::set<std::string>{"base60", "lag60x5", "lag60x5-depth", "lag60x5-rotation"}));
    const std::string replayed = replayOf(sessionIn(dir));
    EXPECT_TRUE(contains(replayed, " outcomes reproduced")) << replayed;
    EXPECT_FALSE(contains(replayed, "differ")) << replayed;
    EXPECT_TRUE(fs::exists(dir + "/frame_4000.png"));
}

// Uneven cadences in a real window (docs/frame-pacing.md): 60 fps on a 144 Hz protocol (new
// images 2 and 3 refreshes apart) and 60 fps with jitter and hitches play as headless, event
// for event, and replay exactly; the stored pacing holds each condition's own unevenness
// (its intended intervals between new images) apart from what the machine missed.
TEST(LiveSession, UnevenConditionsRunInTheWindowAndReplay) {
    const std::string dir = scratch("uneven"), headless = scratch("uneven-headless");
    std::ofstream(dir + "/uneven.json") << R"({"format_version":8,"name":"uneven","game":"shooter",
 "display":{"refresh_hz":144,"refresh_mismatch":"warn"},
 "conditions":{"even60":{"render_hz":60},
  "rough60":{"render_hz":60,"frame_time_jitter":{"distribution":"normal","sd_ms":4},"hitches":{"ms":100,"every_s":0.2}}},
 "acclimation":{"duration_s":0.25,"level":0,"mode":"even60"},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.25,
  "high_mode":"even60","low_mode":"rough60"},
 "test":{"conditions":["even60","rough60"],"targets_per_condition":1,"timeout_s":1.0,"pause_s":0.25}})";
    const std::string path = dir + "/uneven.json";
    const auto window = inWindow("run --protocol " + path + " --participant U --out " + dir +
                                 " --width 320 --height 180 --player bot:3 --seed 4");
    ASSERT_EQ(window.status, 0) << window.output;
    const auto plain = runCommand(std::string(WARPLAB_BINARY) + " run --protocol " + path + " --participant U --out " +
                                  headless + " --headless --width 320 --height 180 --player bot:3 --seed 4");
    ASSERT_EQ(plain.status, 0) << plain.output;
    const auto a = warplab::session::readSession(sessionIn(dir));
    const auto b = warplab::session::readSession(sessionIn(headless));
    EXPECT_TRUE(a.completed) << a.note;
    ASSERT_EQ(firstRecordDifference(a, b), "");
    ASSERT_EQ(a.frames.size(), b.frames.size());
    for (std::size_t i = 0; i < a.frames.size(); ++i) ASSERT_EQ(a.frames[i].kind, b.frames[i].kind) << "frame " << i;
    const std::string replayed = replayOf(sessionIn(dir));
    EXPECT_TRUE(contains(replayed, " outcomes reproduced")) << replayed;
    EXPECT_FALSE(contains(replayed, "differ")) << replayed;

    std::vector<warplab::session::ConditionPacing> pacing;
    ASSERT_TRUE(warplab::session::parsePacing(a.summaries.at("pacing"), pacing));
    std::map<std::string, warplab::session::ConditionPacing> byCondition;
    for (const auto& p : pacing) byCondition[p.condition] = p;
    ASSERT_EQ(byCondition.count("even60"), 1u) << a.summaries.at("pacing");
    ASSERT_EQ(byCondition.count("rough60"), 1u) << a.summaries.at("pacing");
    const double refreshMs = 1000.0 / 144.0;
    EXPECT_NEAR(byCondition["even60"].intendedMaxMs, 3 * refreshMs, 1e-9);  // never a hitch's stall
    EXPECT_GE(byCondition["rough60"].intendedMaxMs, 100.0);  // the hitch, as the schedule meant it
    EXPECT_GT(byCondition["even60"].newImages, 0);
    EXPECT_LT(byCondition["even60"].newImages, byCondition["even60"].shown);  // held frames between renders
    EXPECT_FALSE(std::isnan(byCondition["even60"].shownMaxMs)) << "the window measured what it showed";
}

// A second window on the rig recorded into the folder beside the first. While another session
// holds the folder the window run is refused before it opens its window: no start screen, no file.
TEST(LiveSession, AFolderInUseIsRefusedBeforeTheWindowOpens) {
    const std::string dir = scratch("folder-in-use");
    std::ofstream(dir + "/script.txt") << "start key enter\nend key enter\n";
    const std::string protocol = tinyProtocol(dir);
    fs::create_directories(dir + "/shots");
    const warplab::session::ResultsFolderLock held(dir, "HOLDER", "shooter-thesis");
    const auto r = inWindow("run --seed 1 --protocol " + protocol + " --participant W --out " + dir +
                            " --width 160 --height 90 --player bot:3 --input-script " + dir +
                            "/script.txt --screenshots " + dir + "/shots");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(contains(r.output,
                         "'" + dir + "' is in use by another warplab session (participant HOLDER, " +
                             "protocol shooter-thesis, pid " + std::to_string(::getpid())))
        << r.output;
    EXPECT_TRUE(sessionIn(dir).empty());
    EXPECT_FALSE(fs::exists(dir + "/shots/start.png")) << "the window opened";
}

TEST(LiveSession, ABadInputScriptIsNamedWithItsLine) {
    const std::string dir = scratch("bad-script");
    std::ofstream(dir + "/script.txt") << "start key enter\n12 jump\n";
    const auto r = inWindow("run --seed 1 --protocol " + tinyProtocol(dir) + " --participant X --out " + dir +
                            " --width 160 --height 90 --input-script " + dir + "/script.txt");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "script.txt' line 2: unknown action 'jump'")) << r.output;
    EXPECT_TRUE(sessionIn(dir).empty());
}

// Free play: the supervisor switches conditions and difficulty live; a condition the display cannot run
// is refused with its reason; nothing is recorded.
TEST(LiveSession, FreePlaySwitchesConditionsLiveAndRecordsNothing) {
    const std::string dir = scratch("free-play");
    std::ofstream(dir + "/script.txt") << "5 key 1\n20 key u\n40 key 8\n70 key esc\n70 key q\n";
    const auto r = inWindow("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                            "/protocol/click-quick.json --free-play --width 160 --height 90 --out " + dir +
                            " --input-script " + dir + "/script.txt");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "free play: conv15, level 0")) << r.output;
    EXPECT_TRUE(contains(r.output, "free play: conv15, level 1")) << r.output;
    // warp15to120 needs a 120 Hz display; the click game's is 60 Hz: refused, still conv15.
    EXPECT_FALSE(contains(r.output, "free play: warp15to120")) << r.output;
    EXPECT_TRUE(contains(r.output, "free play ended")) << r.output;
    EXPECT_TRUE(sessionIn(dir).empty()) << "free play wrote a session";
}

// ] and [ (PageDown and PageUp) step through every condition, past the ninth that the digits end
// at, around the list, and over the conditions the display cannot run.
// The condition to start in is --condition, or --mode, its older name.
TEST(LiveSession, FreePlayStepsPastTheNinthConditionAndAroundTheList) {
    for (const char* option : {"--condition", "--mode"}) {
        SCOPED_TRACE(option);
        const std::string dir = scratch("free-play-steps");
        std::ofstream(dir + "/script.txt") << "5 key ]\n20 key ]\n35 key [\n50 key pageup\n65 key pagedown\n"
                                              "80 key esc\n80 key q\n";
        const auto r =
            inWindow("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                     "/protocol/click-quick.json --free-play " + option + " lag200 --width 320 --height 180 --out " +
                     dir + " --input-script " + dir + "/script.txt --screenshots " + dir + " --screenshot-frames 30");
        ASSERT_EQ(r.status, 0) << r.output;
        // lag200 (the seventh) -> past warp15to120, which needs 120 Hz -> bireproj15to60 (the
        // ninth) -> around to conv15 -> back -> lag200 -> bireproj15to60.
        std::size_t at = 0;
        for (const char* condition : {"bireproj15to60", "conv15", "bireproj15to60", "lag200", "bireproj15to60"}) {
            const std::size_t found = r.output.find("free play: " + std::string(condition) + ", level 0", at);
            ASSERT_NE(found, std::string::npos) << "no switch to " << condition << " after offset " << at << ":\n"
                                                << r.output;
            at = found + 1;
        }
        EXPECT_FALSE(contains(r.output, "free play: warp15to120")) << r.output;
        EXPECT_TRUE(fs::exists(dir + "/free_30.png"));
        fs::remove_all(dir);
    }
    const auto both = inWindow("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                               "/protocol/click-quick.json --free-play --condition lag200 --mode lag100 --out " +
                               scratch("free-play-both"));
    EXPECT_EQ(both.status, 2) << both.output;
    EXPECT_TRUE(contains(both.output, "options --condition and --mode are one option")) << both.output;
}

TEST(LiveSession, AHumanNeedsTheWindow) {
    const auto r = runCommand(std::string(WARPLAB_BINARY) +
                              " run --seed 1 --protocol x.json --participant P --headless --player human");
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_TRUE(contains(r.output, "needs the window")) << r.output;
}

}  // namespace
