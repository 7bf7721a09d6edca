// The photodiode marker in a real SDL window (Mesa GLX under Xvfb): a scripted press, the
// corner's pixels read back from the window's frames, black before, white exactly on the frame
// the condition's schedule says (the README's latency table), black after; and the frames table
// marking that frame. Runs with --every-frame, so the scripted frames are the frames shown.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sqlite3.h>

#include "cli/cli_support.h"
#include "image/image.h"
#include "session/session_store.h"

namespace {

using warplab::testing::Result;
using warplab::testing::runCommand;
using warplab::testing::sessionIn;

Result inWindow(const std::string& arguments) {
    // Xvfb reports no refresh rate: the runs warn of it rather than refuse.
    return runCommand("SDL_AUDIODRIVER=dummy " + warplab::testing::onXvfb() + std::string(WARPLAB_BINARY) + " " +
                      arguments + " --every-frame --allow-refresh-mismatch");
}

constexpr int kWidth = 160, kHeight = 90;
constexpr int kSide = 16;  // 4 % of 90 pixels is less than the smallest square, 16 pixels

enum class Shade { Black, White, Other };

// The marker's square in the window's frame: all black, all white, or neither.
Shade markerIn(const std::string& png, bool left, bool top) {
    const auto image = warplab::image::readPng(png);
    EXPECT_EQ(image.width, kWidth);
    std::set<int> values;
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) {
            const std::uint8_t* p = image.at(left ? x : kWidth - 1 - x, top ? y : kHeight - 1 - y);
            for (int c = 0; c < 3; ++c) values.insert(p[c]);
        }
    if (values == std::set<int>{0}) return Shade::Black;
    if (values == std::set<int>{255}) return Shade::White;
    return Shade::Other;
}

// The frames whose record says the marker turned white, and the press each answers.
std::map<std::int64_t, std::int64_t> litFrames(const std::string& session) {
    std::map<std::int64_t, std::int64_t> lit;
    for (const auto& f : warplab::session::readSession(session).frames) {
        if (f.detailJson.empty()) continue;
        const auto detail = nlohmann::json::parse(f.detailJson);
        if (detail.contains("photon_marker")) {
            EXPECT_EQ(detail["photon_marker"], true);
            lit[f.frame] = detail.value("photon_press", std::int64_t{-1});
        }
    }
    return lit;
}

// The session's replay re-rendered: the marker in the session's corner, white exactly on the
// frames its window lit. The header names the corner the window drew.
void expectReplayDrawsTheMarker(const std::string& dir, const std::string& corner, bool left, bool top,
                                const std::map<int, Shade>& shades) {
    const std::string session = sessionIn(dir);
    EXPECT_EQ(warplab::session::readSessionHeader(session).photonMarker, corner);
    const std::string frames = dir + "/replayed";
    const auto replay =
        runCommand(std::string(WARPLAB_BINARY) + " replay " + session + " --render " + frames + " --frames " +
                   std::to_string(shades.begin()->first) + ":" + std::to_string(shades.rbegin()->first));
    ASSERT_EQ(replay.status, 3) << replay.output;  // the script ended the session: incomplete
    for (const auto& [frame, shade] : shades) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%07d.png", frame);
        EXPECT_EQ(markerIn(frames + name, left, top), shade) << "replayed frame " << frame;
    }
}

// lag50 in the click game at 60 Hz: a press at frame 20 is shown 3 frames later (50 ms, the
// README's least view latency at 60 Hz, since lag conditions render every frame there). The marker
// comes from the protocol (format 5).
TEST(PhotonMarker, LightsWhereLag50ShowsThePress) {
    const std::string dir = warplab::testing::scratch("photon-marker", "lag50");
    std::ofstream(dir + "/lag50.json") << R"({"format_version":5,"name":"click-marker","game":"click",
 "display":{"photon_marker":"bottom_right"},
 "matches":{"match_s":1.0,"modes":["lag50"],"rounds":[{"name":"scored","scored":true,"matches_per_mode":1,
   "instructions":""}]}})";
    // Enter at the ready screen (frame 0), the match from frame 1, the press at 20; then the
    // supervisor ends it.
    std::ofstream(dir + "/script.txt") << "start key enter\n0 key enter\n20 click\n40 key esc\n40 key q\n";
    const auto r = inWindow("run --seed 1 --protocol " + dir + "/lag50.json --participant M1 --out " + dir +
                            " --width 160 --height 90 --input-script " + dir + "/script.txt --screenshots " + dir +
                            " --screenshot-frames 20,22,23,24");
    ASSERT_EQ(r.status, 3) << "ended by the supervisor: " << r.output;
    for (const auto& [frame, shade] :
         std::map<int, Shade>{{20, Shade::Black}, {22, Shade::Black}, {23, Shade::White}, {24, Shade::Black}})
        EXPECT_EQ(markerIn(dir + "/frame_" + std::to_string(frame) + ".png", false, false), shade) << "frame " << frame;
    EXPECT_EQ(litFrames(sessionIn(dir)), (std::map<std::int64_t, std::int64_t>{{23, 20}}));
    expectReplayDrawsTheMarker(dir, "bottom_right", false, false,
                               {{22, Shade::Black}, {23, Shade::White}, {24, Shade::Black}});
    const auto replay = runCommand(std::string(WARPLAB_BINARY) + " replay " + sessionIn(dir));
    EXPECT_TRUE(warplab::testing::contains(replay.output, "outcomes reproduced")) << replay.output;
}

// warp15to120 in the shooter at 120 Hz reads the mouse for every frame: a press at frame 20 is
// shown by frame 20 itself, the first frame made after it (0 - 8.3 ms). The marker comes from
// the command line, for a protocol (format 2) that has none.
TEST(PhotonMarker, LightsWhereWarpShowsThePress) {
    const std::string dir = warplab::testing::scratch("photon-marker", "warp");
    std::ofstream(dir + "/warp.json") << R"({"format_version":2,"name":"shooter-marker","game":"shooter",
 "acclimation":{"duration_s":1.0,"level":0,"mode":"warp15to120"}})";
    std::ofstream(dir + "/script.txt") << "start key enter\n20 click\n40 key esc\n40 key q\n";
    const auto r = inWindow("run --seed 1 --protocol " + dir + "/warp.json --participant M2 --out " + dir +
                            " --width 160 --height 90 --photon-marker top_left --input-script " + dir +
                            "/script.txt --screenshots " + dir + " --screenshot-frames 19,20,21");
    ASSERT_EQ(r.status, 3) << "ended by the supervisor: " << r.output;
    for (const auto& [frame, shade] : std::map<int, Shade>{{19, Shade::Black}, {20, Shade::White}, {21, Shade::Black}})
        EXPECT_EQ(markerIn(dir + "/frame_" + std::to_string(frame) + ".png", true, true), shade) << "frame " << frame;
    EXPECT_EQ(litFrames(sessionIn(dir)), (std::map<std::int64_t, std::int64_t>{{20, 20}}));
    // The protocol has no marker: only the header knows the command line's.
    expectReplayDrawsTheMarker(dir, "top_left", true, true,
                               {{19, Shade::Black}, {20, Shade::White}, {21, Shade::Black}});
}

TEST(PhotonMarker, ABadCornerIsRefusedAndTheHeadlessRunHasNone) {
    const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/click-quick.json";
    const auto bad =
        runCommand(std::string(WARPLAB_BINARY) + " run --protocol " + protocol + " --participant X --photon-marker up");
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_TRUE(warplab::testing::contains(
        bad.output,
        "option --photon-marker needs one of off, top_left, top_right, bottom_left, bottom_right, got 'up'"))
        << bad.output;
    const auto headless = runCommand(std::string(WARPLAB_BINARY) + " run --protocol " + protocol +
                                     " --participant X --headless --photon-marker top_left");
    EXPECT_EQ(headless.status, 2) << headless.output;
    EXPECT_TRUE(warplab::testing::contains(headless.output, "option --photon-marker only applies in the window"))
        << headless.output;
}

// A headless session drew nothing, so its header says off, and its replay draws no marker even
// where the protocol has one; the corner the header names is what replay draws. One it does
// not know ends replay --render in one sentence naming the file and the key, exit status 1.
TEST(PhotonMarker, AHeadlessSessionSaysOffAndReplayDrawsWhatTheHeaderSays) {
    const std::string dir = warplab::testing::scratch("photon-marker", "headless");
    std::ofstream(dir + "/marked.json") << R"({"format_version":5,"name":"click-marked","game":"click",
 "display":{"photon_marker":"top_left"},
 "matches":{"match_s":0.5,"modes":["conv60"],"rounds":[{"name":"scored","scored":true,"matches_per_mode":1,
   "instructions":""}]}})";
    const auto run = runCommand(std::string(WARPLAB_BINARY) + " run --headless --seed 2 --protocol " + dir +
                                "/marked.json --participant H --out " + dir + " --width 160 --height 90");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string session = sessionIn(dir);
    EXPECT_EQ(warplab::session::readSessionHeader(session).photonMarker, "off");
    const auto replayed = [&](const std::string& stored, const std::string& out) {
        sqlite3* db = nullptr;
        EXPECT_EQ(sqlite3_open(session.c_str(), &db), SQLITE_OK);
        const std::string sql = "UPDATE meta SET value = '" + stored + "' WHERE key = 'photon_marker'";
        EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
        sqlite3_close(db);
        return runCommand(std::string(WARPLAB_BINARY) + " replay " + session + " --render " + dir + "/" + out +
                          " --frames 5:5");
    };
    auto replay = replayed("off", "off");
    ASSERT_EQ(replay.status, 0) << replay.output;
    EXPECT_NE(markerIn(dir + "/off/frame_0000005.png", true, true), Shade::Black);
    replay = replayed("top_left", "top-left");
    ASSERT_EQ(replay.status, 0) << replay.output;
    EXPECT_EQ(markerIn(dir + "/top-left/frame_0000005.png", true, true), Shade::Black);

    replay = replayed("centre", "centre");
    EXPECT_EQ(replay.status, 1) << replay.output;
    EXPECT_TRUE(warplab::testing::contains(replay.output, "session file " + session + " has photon_marker 'centre'"))
        << replay.output;
}

}  // namespace
