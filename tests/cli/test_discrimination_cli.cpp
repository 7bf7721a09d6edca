// The discrimination task as a participant meets it: in a real SDL window (Mesa GLX under Xvfb,
// paced by timer since Xvfb reports no refresh), the instructions read, both intervals followed
// with the mouse, each question answered with a digit key; the session replays exactly. And
// headless through the command line: run, replay, export.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/cli_support.h"
#include "image/image.h"
#include "session/session_store.h"

namespace {

using warplab::testing::contains;
using warplab::testing::runCommand;
using warplab::testing::sessionIn;

// Two trials: constant stimuli at 2 and 8 added lag frames, once each, half-second intervals.
std::string tinyDiscrimination(const std::string& dir) {
    std::ofstream(dir + "/tiny-jnd.json") << R"({"format_version":1,"name":"jnd-tiny","game":"discrimination",
 "display":{"refresh_mismatch":"warn"},
 "trials":{"interval_s":0.5,"blank_s":0.1,"instructions":"Follow the ball, then press 1 or 2.",
  "procedures":[{"name":"lag","reference":"conv120","method":"constant_stimuli","levels":[2,8],"repeats":1}]}})";
    return dir + "/tiny-jnd.json";
}

TEST(DiscriminationWindow, AParticipantFollowsBothIntervalsAndAnswersByKey) {
    const std::string dir = warplab::testing::scratch("discrimination", "window");
    // Frames at 120 Hz: the instructions until Enter at 5, a 12-frame blank, interval 1 (60
    // frames from 17), a blank, interval 2 (from 89), the question from 149 (a press in its
    // first 60 frames is dropped), answered at 215; the second trial's question from 359.
    std::ofstream(dir + "/script.txt") << "start key enter\n5 key enter\n30 move 25 0\n100 move -25 4\n"
                                          "215 key 1\n300 move 10 -3\n425 key 2\nend key enter\n";
    const auto r = runCommand("SDL_AUDIODRIVER=dummy " + warplab::testing::onXvfb() + std::string(WARPLAB_BINARY) +
                              " run --seed 5 --protocol " + tinyDiscrimination(dir) + " --participant D1 --out " + dir +
                              " --width 192 --height 108 --every-frame --input-script " + dir +
                              "/script.txt --screenshots " + dir + " --screenshot-frames 40,180");
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string session = sessionIn(dir);
    ASSERT_FALSE(session.empty()) << r.output;
    const auto data = warplab::session::readSession(session);
    EXPECT_TRUE(data.completed) << data.note;
    std::vector<nlohmann::json> answers;
    for (const auto& e : data.events)
        if (e.type == "judgement") answers.push_back(nlohmann::json::parse(e.detailJson));
    ASSERT_EQ(answers.size(), 2u);
    EXPECT_EQ(answers[0]["answer"], 1);
    EXPECT_EQ(answers[1]["answer"], 2);
    for (const auto& a : answers) EXPECT_EQ(a["answered_with"], "key");
    EXPECT_EQ(data.inputs.at(30).mouseDx, 25.0);
    const std::string replay = runCommand(std::string(WARPLAB_BINARY) + " replay " + session).output;
    EXPECT_TRUE(contains(replay, "2/2 outcomes reproduced")) << replay;
    // An interval: the hangar with the ball and the reticle; the question: its two boxes.
    const auto interval = warplab::image::readPng(dir + "/frame_40.png");
    const auto question = warplab::image::readPng(dir + "/frame_180.png");
    EXPECT_EQ(interval.width, 192);
    long differing = 0;
    for (int y = 0; y < 108; ++y)
        for (int x = 0; x < 192; ++x) differing += interval.at(x, y)[0] != question.at(x, y)[0];
    EXPECT_GT(differing, 192 * 108 / 4) << "the question screen is not the interval's picture";
}

TEST(DiscriminationCli, ABotSessionRunsReplaysAndExports) {
    const std::string dir = warplab::testing::scratch("discrimination", "headless");
    const std::string quick = std::string(WARPLAB_SOURCE_DIR) + "/protocol/latency-jnd-quick.json";
    const auto run = runCommand(std::string(WARPLAB_BINARY) + " run --headless --seed 2 --protocol " + quick +
                                " --participant B1 --out " + dir + " --width 320 --height 180");
    ASSERT_EQ(run.status, 0) << run.output;
    const auto replay = runCommand(std::string(WARPLAB_BINARY) + " replay " + sessionIn(dir));
    EXPECT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "16/16 outcomes reproduced")) << replay.output;
    const auto exported = runCommand(std::string(WARPLAB_BINARY) + " export " + dir + " --out " + dir + "/export");
    ASSERT_EQ(exported.status, 0) << exported.output;
    EXPECT_TRUE(std::filesystem::exists(dir + "/export/thresholds.csv"));
    // A protocol with a level the display cannot show: one sentence naming the path, exit 1.
    std::ofstream(dir + "/bad.json") << R"({"format_version":1,"name":"bad","game":"discrimination",
 "trials":{"procedures":[{"name":"lag","reference":"conv120","levels":[1,2.5],"max_trials":4,
  "thresholds":[1,2],"slopes":[2]}]}})";
    const auto bad = runCommand(std::string(WARPLAB_BINARY) + " run --headless --protocol " + dir +
                                "/bad.json --participant B1 --out " + dir);
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_TRUE(contains(bad.output, "trials.procedures[0].levels[1]")) << bad.output;
}

}  // namespace
