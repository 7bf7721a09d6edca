// Uneven render cadences end to end: a protocol on the displays labs own (144, 165, 240 and
// 360 Hz) with a render rate the refresh does not divide, seeded jitter and hitches runs
// headless with a scripted player and replays exactly.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cli/cli_support.h"

namespace {

using warplab::testing::contains;
using warplab::testing::warplab;

std::string pacedProtocol(const std::string& dir, int refreshHz) {
    const std::string path = dir + "/paced.json";
    std::ofstream(path) << R"({"format_version":8,"name":"paced","game":"shooter",
 "display":{"refresh_hz":)" +
            std::to_string(refreshHz) + R"(,"refresh_mismatch":"warn"},
 "conditions":{
  "even60":{"render_hz":60},
  "jitter60":{"render_hz":60,"frame_time_jitter":{"distribution":"normal","sd_ms":4}},
  "hitch60-bireproj":{"render_hz":60,"fill":"bireproj","hitches":{"ms":100,"every_s":0.5}}},
 "acclimation":{"duration_s":0.5,"level":0,"mode":"even60"},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.5,
  "high_mode":"even60","low_mode":"conv15"},
 "test":{"conditions":["even60","jitter60","hitch60-bireproj","conv60"],"targets_per_condition":2,
  "timeout_s":0.75,"pause_s":0.25,"supervisor_starts":false}})";
    return path;
}

TEST(CliPacing, UnevenConditionsRunHeadlessOnTheDisplaysLabsOwnAndReplayExactly) {
    for (const int refresh : {144, 165, 240, 360}) {
        const std::string dir = warplab::testing::scratch("pacing", "run" + std::to_string(refresh));
        const auto run = warplab("run --protocol " + pacedProtocol(dir, refresh) + " --participant P --out " + dir +
                                 " --headless --player bot:3 --seed 11");
        ASSERT_EQ(run.status, 0) << refresh << " Hz: " << run.output;
        const std::string session = warplab::testing::sessionIn(dir);
        ASSERT_FALSE(session.empty()) << refresh;
        const auto replay = warplab("replay " + session);
        EXPECT_EQ(replay.status, 0) << refresh << " Hz: " << replay.output;
        EXPECT_TRUE(contains(replay.output, "outcomes reproduced")) << replay.output;
    }
}

// `warplab conditions` says each condition's pacing on its second line: 60 fps on 144 Hz is a
// 3, 2, 3, 2, 2 cadence, frame times of 13.9 and 20.8 ms, so both lows are 48 fps.
TEST(CliPacing, ConditionsPrintsEachConditionsPacing) {
    const std::string dir = warplab::testing::scratch("pacing", "conditions");
    const auto table = warplab("conditions " + pacedProtocol(dir, 144));
    ASSERT_EQ(table.status, 0) << table.output;
    const std::size_t even = table.output.find("\neven60 ");
    ASSERT_NE(even, std::string::npos) << table.output;
    const std::size_t second = table.output.find('\n', even + 1) + 1;
    EXPECT_EQ(table.output.substr(second, table.output.find('\n', second) - second),
              "    60 fps (1% low 48, 5% low 48); frame time 13.9 / 20.8 / 20.8 / 20.8 ms, 0 stutters; latency min / "
              "median / p95 / max: view 0.0 / 8.3 / 18.8 / 20.8 ms, scene 0.0 / 8.3 / 18.8 / 20.8 ms")
        << table.output;
    const auto csv = warplab("conditions " + pacedProtocol(dir, 144) + " --csv");
    ASSERT_EQ(csv.status, 0) << csv.output;
    EXPECT_TRUE(contains(csv.output, ",stutters,")) << csv.output;
}

// A render rate above the refresh is one sentence naming the path, exit 1, nothing written.
TEST(CliPacing, ARenderRateAboveTheRefreshIsRefused) {
    const std::string dir = warplab::testing::scratch("pacing", "above");
    std::string path = pacedProtocol(dir, 50);
    const auto run =
        warplab("run --protocol " + path + " --participant P --out " + dir + " --headless --player bot:3 --seed 11");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_TRUE(contains(run.output, "conditions.even60.render_hz is 60 Hz, above the refresh (50 Hz)")) << run.output;
    EXPECT_TRUE(warplab::testing::sessionIn(dir).empty());
}

}  // namespace
