// Uneven render cadences end to end: a protocol on the displays labs own (144, 165, 240 and
// 360 Hz) with a render rate the refresh does not divide, seeded jitter and hitches runs
// headless with a scripted player and replays exactly.
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

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

// The line of `warplab conditions` that starts with the condition's name, and the one after it.
std::pair<std::string, std::string> conditionLines(const std::string& output, const std::string& name) {
    const std::size_t first = output.find("\n" + name + " ");
    if (first == std::string::npos) return {};
    const std::size_t second = output.find('\n', first + 1) + 1;
    return {output.substr(first + 1, second - first - 2), output.substr(second, output.find('\n', second) - second)};
}

// `warplab conditions` says each condition's pacing on its second line: 60 fps on 144 Hz is a
// 3, 2, 3, 2, 2 cadence, frame times of 13.9 and 20.8 ms, so both lows are 48 fps. A 100 ms
// hitch every 0.5 s is 20 stutters in the 10 s looked at, each a frame time of 111.1 ms (the
// hitch and the 60 fps interval it stalls, at a refresh).
TEST(CliPacing, ConditionsPrintsEachConditionsPacing) {
    const std::string dir = warplab::testing::scratch("pacing", "conditions");
    const auto table = warplab("conditions " + pacedProtocol(dir, 144));
    ASSERT_EQ(table.status, 0) << table.output;
    EXPECT_EQ(conditionLines(table.output, "even60").second,
              "    60 fps (1% low 48, 5% low 48); frame time 13.9 / 20.8 / 20.8 / 20.8 ms, 0 stutters; latency min / "
              "median / p95 / max: view 0.0 / 8.3 / 18.8 / 20.8 ms, scene 0.0 / 8.3 / 18.8 / 20.8 ms")
        << table.output;
    EXPECT_EQ(conditionLines(table.output, "jitter60").second,
              "    60.1 fps (1% low 36, 5% low 48); frame time 13.9 / 20.8 / 27.8 / 34.7 ms, 1 stutter; latency min / "
              "median / p95 / max: view 0.0 / 8.5 / 19.6 / 34.7 ms, scene 0.0 / 8.5 / 19.6 / 34.7 ms")
        << table.output;
    EXPECT_EQ(conditionLines(table.output, "hitch60-bireproj").second,
              "    98 fps (1% low 9, 5% low 72); frame time 6.9 / 13.9 / 111.1 / 111.1 ms, 20 stutters; latency min / "
              "median / p95 / max: view 13.9 / 20.6 / 113.9 / 125.0 ms, scene 6.9 / 17.4 / 100.0 / 125.0 ms")
        << table.output;
    const auto csv = warplab("conditions " + pacedProtocol(dir, 144) + " --csv");
    ASSERT_EQ(csv.status, 0) << csv.output;
    EXPECT_TRUE(contains(csv.output, ",stutters,")) << csv.output;
}

// A game's frame times as conditions: written inline, and in a file beside the protocol (a
// MangoHud log played from 50 ms in, rescaled to 50 frames a second, under bidirectional
// reprojection, which waits through its longest frames).
std::string tracedProtocol(const std::string& dir) {
    std::filesystem::create_directories(dir + "/traces");
    std::ofstream(dir + "/traces/game.csv")
        << "os,cpu,gpu,ram,kernel,driver,cpuscheduler\n"
           "Debian GNU/Linux 12,AMD Ryzen 7 5800X,AMD Radeon RX 6800,32768,6.1.0-27-amd64,Mesa 22.3.6,\n"
           "fps,frametime,cpu_load,gpu_load,elapsed\n"
           "59.88,16.7,31,88,16700000\n120.48,8.3,30,87,25000000\n29.94,33.4,29,86,58400000\n"
           "80,12.5,31,88,70900000\n59.88,16.7,31,88,87600000\n21.2,47.1,35,90,134700000\n";
    const std::string path = dir + "/traced.json";
    std::ofstream(path) << R"({"format_version":8,"name":"traced","game":"shooter",
 "display":{"refresh_hz":144,"refresh_mismatch":"warn"},
 "conditions":{
  "inline-trace":{"frame_times":{"ms":[16.7,8.3,33.4,12.5,16.7,20.0,11.1]}},
  "file-trace":{"fill":"bireproj","frame_times":{"file":"traces/game.csv","offset_s":0.05,"mean_hz":50}}},
 "acclimation":{"duration_s":0.5,"level":0,"mode":"inline-trace"},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.5,
  "high_mode":"inline-trace","low_mode":"file-trace"},
 "test":{"conditions":["inline-trace","file-trace"],"targets_per_condition":3,
  "timeout_s":0.75,"pause_s":0.25,"supervisor_starts":false}})";
    return path;
}

// The session keeps the frame times in its protocol copy: with the trace file gone, or changed
// to other frame times, the session still replays every outcome.
TEST(CliPacing, TracedConditionsRunHeadlessAndReplayWithoutTheTraceFile) {
    const std::string dir = warplab::testing::scratch("pacing", "traced");
    const std::string protocol = tracedProtocol(dir);
    const auto run = warplab("run --protocol " + protocol + " --participant P --out " + dir +
                             " --headless --player bot:3 --seed 11");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string session = warplab::testing::sessionIn(dir);
    ASSERT_FALSE(session.empty());
    const auto replay = warplab("replay " + session);
    EXPECT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "outcomes reproduced")) << replay.output;

    std::filesystem::remove(dir + "/traces/game.csv");
    const auto without = warplab("replay " + session);
    EXPECT_EQ(without.status, 0) << without.output;
    EXPECT_TRUE(contains(without.output, "outcomes reproduced")) << without.output;
    std::ofstream(dir + "/traces/game.csv") << "40\n5\n40\n5\n";
    const auto changed = warplab("replay " + session);
    EXPECT_EQ(changed.status, 0) << changed.output;
    EXPECT_TRUE(contains(changed.output, "outcomes reproduced")) << changed.output;
}

// `warplab conditions` lists both traced conditions of the protocol: the inline trace at its
// own rate (7 frames in 118.7 ms), the file's rescaled to 50 frames a second and played from
// 50 ms in: its longest frame, 47.1 ms rescaled by 44.54 / 50 fps to 41.96 ms, shows 6 refreshes apart.
TEST(CliPacing, ConditionsListsTracedConditions) {
    const std::string dir = warplab::testing::scratch("pacing", "traced-conditions");
    const auto table = warplab("conditions " + tracedProtocol(dir));
    ASSERT_EQ(table.status, 0) << table.output;
    const auto [inlineFirst, inlineSecond] = conditionLines(table.output, "inline-trace");
    EXPECT_TRUE(contains(inlineFirst, " 58.9722 Hz  0 frames hold ")) << table.output;
    EXPECT_EQ(inlineSecond,
              "    59 fps (1% low 28.8, 5% low 28.8); frame time 13.9 / 34.7 / 34.7 / 34.7 ms, 68 stutters; latency "
              "min / median / p95 / max: view 0.0 / 8.9 / 27.4 / 34.7 ms, scene 0.0 / 8.9 / 27.4 / 34.7 ms")
        << table.output;
    const auto [fileFirst, fileSecond] = conditionLines(table.output, "file-trace");
    EXPECT_TRUE(contains(fileFirst, " 50 Hz  0 frames bireproj 144 ")) << table.output;
    EXPECT_EQ(fileSecond,
              "    80 fps (1% low 28.8, 5% low 28.8); frame time 6.9 / 34.7 / 34.7 / 41.7 ms, 176 stutters; latency "
              "min / median / p95 / max: view 6.9 / 20.8 / 46.0 / 55.6 ms, scene 6.9 / 17.8 / 42.8 / 55.6 ms")
        << table.output;
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
