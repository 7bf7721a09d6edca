// The `warplab` binary as a user meets it: bad command lines and bad data end in one clear
// sentence naming the culprit and a non-zero exit, never a crash; good ones write files.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <thread>
#include <sqlite3.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "cli/cli_support.h"
#include "session/session_store.h"
#include "shooter/shooter_protocol.h"
#include "image/image.h"

namespace {

namespace fs = std::filesystem;

using warplab::testing::contains;
using warplab::testing::Result;
using warplab::testing::sessionAppearingIn;
using warplab::testing::sessionIn;
using warplab::testing::warplab;

std::string scratch(const std::string& name) { return warplab::testing::scratch("cli", name); }

// A data folder with the real shaders and assets, to be broken one piece at a time.
std::string copyOfData(const std::string& name) {
    const std::string dir = scratch(name);
    fs::copy(fs::path(WARPLAB_SOURCE_DIR) / "shaders", fs::path(dir) / "shaders", fs::copy_options::recursive);
    fs::copy(fs::path(WARPLAB_SOURCE_DIR) / "assets", fs::path(dir) / "assets", fs::copy_options::recursive);
    return dir;
}

TEST(Cli, UnknownCommand) {
    const auto r = warplab("frobnicate");
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.output, "unknown command 'frobnicate'")) << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;
}

TEST(Cli, UnknownOption) {
    const auto r = warplab("render --frobnicate");
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.output, "unknown option '--frobnicate'")) << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;
}

TEST(Cli, MissingOptionValue) {
    const auto r = warplab("render --time");
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.output, "--time")) << r.output;
}

TEST(Cli, BadSizesAreRefusedBeforeAnyContextIsMade) {
    for (const std::string bad : {"--width 0", "--width -4", "--height 16385", "--width abc", "--height 1e3"}) {
        const auto r = warplab("render " + bad + " --out /dev/null");
        EXPECT_EQ(r.status, 2) << bad;
        EXPECT_TRUE(contains(r.output, bad.substr(0, bad.find(' ')))) << bad << ": " << r.output;
        EXPECT_EQ(r.lines(), 1) << r.output;
    }
}

TEST(Cli, UnknownBackend) {
    const auto r = warplab("info --gl vulkan");
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.output, "unknown GL backend 'vulkan'")) << r.output;
}

TEST(Cli, HelpForEveryCommand) {
    for (const std::string c : {"info", "render"}) {
        const auto r = warplab(c + " --help");
        EXPECT_EQ(r.status, 0) << c;
        EXPECT_TRUE(contains(r.output, "usage: warplab " + c)) << r.output;
        EXPECT_TRUE(contains(r.output, "--gl")) << r.output;
    }
    EXPECT_EQ(warplab("--help").status, 0);
}

// The overview lists each command with its summary after a gap, never run into its name
// ("conditionsPrint the conditions ...").
TEST(Cli, HelpKeepsEveryCommandApartFromItsSummary) {
    const auto r = warplab("--help");
    for (const std::string c : {"conditions", "run", "replay", "export", "study", "check"})
        EXPECT_TRUE(contains(r.output, "\n  " + c + "  ")) << c << ": " << r.output;
}

TEST(Cli, InfoReportsACoreContextOfAtLeast41) {
    for (const std::string backend : {"osmesa", "egl"}) {
        const auto r = warplab("info --gl " + backend);
        ASSERT_EQ(r.status, 0) << r.output;
        EXPECT_TRUE(contains(r.output, "profile:  core 4.")) << r.output;
        EXPECT_TRUE(contains(r.output, "renderer: ")) << r.output;
    }
}

TEST(Cli, RenderWritesTheFrameAndBuffers) {
    const std::string dir = scratch("render");
    const auto r =
        warplab("render --time 1.0 --width 64 --height 36 --out " + dir + "/frame.png --depth " + dir +
                "/depth.png --ids " + dir + "/ids.png --velocity " + dir + "/velocity.png --raw " + dir + "/raw");
    ASSERT_EQ(r.status, 0) << r.output;
    for (const std::string f : {"frame.png", "depth.png", "ids.png", "velocity.png"}) {
        const auto image = warplab::image::readPng(dir + "/" + f);
        EXPECT_EQ(image.width, 64) << f;
        EXPECT_EQ(image.height, 36) << f;
    }
    const auto depth = warplab::image::readPfm(dir + "/raw-depth.pfm");
    EXPECT_EQ(depth.channels, 1);
    EXPECT_EQ(warplab::image::readPfm(dir + "/raw-velocity.pfm").channels, 3);
    EXPECT_EQ(warplab::image::readPfm(dir + "/raw-ids.pfm").width, 64);
}

// An output that exists and is not a regular file (a pipe would block the write forever).
TEST(Cli, AnOutputThatIsNotARegularFileIsRefused) {
    const std::string dir = scratch("fifo-out");
    const std::string fifo = dir + "/frame.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const auto r = warplab::testing::runCommand("timeout 30 " + std::string(WARPLAB_BINARY) + " render --out " + fifo +
                                                " --width 64 --height 36");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "'" + fifo + "': it exists and is not a regular file")) << r.output;
}

TEST(Cli, UnwritableOutputIsNamed) {
    const auto r = warplab("render --width 16 --height 16 --out /nonexistent-dir/frame.png");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.output, "/nonexistent-dir/frame.png")) << r.output;
}

TEST(Cli, MissingShaderIsNamed) {
    const std::string data = copyOfData("missing-shader");
    fs::remove(fs::path(data) / "shaders" / "conventional.frag");
    const auto r = warplab("render --width 16 --height 16 --out /dev/null --data-dir " + data);
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.output, data + "/shaders/conventional.frag")) << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;
}

TEST(Cli, ShaderThatFailsToCompileNamesFileAndLine) {
    const std::string data = copyOfData("broken-shader");
    const std::string path = data + "/shaders/conventional.frag";
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto mainPos = text.find("void main() {");
    ASSERT_NE(mainPos, std::string::npos);
    int line = 1;
    for (std::size_t i = 0; i < mainPos; ++i) line += text[i] == '\n';
    text.insert(text.find('\n', mainPos) + 1, "    this is not glsl;\n");
    std::ofstream(path) << text;
    const auto r = warplab("render --width 16 --height 16 --out /dev/null --data-dir " + data);
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.output, path + ":" + std::to_string(line + 1))) << r.output;
}

TEST(Cli, MissingOrMalformedModelIsNamed) {
    const std::string data = copyOfData("bad-model");
    const std::string obj = data + "/assets/hangar.obj";
    fs::remove(obj);
    auto r = warplab("render --width 16 --height 16 --out /dev/null --data-dir " + data);
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.output, obj)) << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;

    for (const std::string& bad : {std::string("v 0 0 0\nv 1 0 0\nf 1 2 7\n"),  // face refers past the vertices
                                   std::string("this is not an obj file\n"),  // no triangles at all
                                   std::string("v 0 0 0\nv nan 1 0\nv 0 1 1\nf 1 2 3\n")}) {
        std::ofstream(obj) << bad;
        r = warplab("render --width 16 --height 16 --out /dev/null --data-dir " + data);
        EXPECT_EQ(r.status, 1) << bad;
        EXPECT_TRUE(contains(r.output, obj)) << bad << ": " << r.output;
        EXPECT_LT(r.status, 128) << "crashed on " << bad;
    }
}

}  // namespace

namespace {

// The warps' sources get the guard band, and its cost is reported; --guard-band 0 turns it off.
TEST(CliBench, TheWarpsGuardBandIsRenderedAndItsCostReported) {
    const std::string dir = scratch("bench-band");
    const auto r =
        warplab("bench --quick --frames 4 --repeats 1 --sequences pan --methods hold15,warp-full --out " + dir);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output,
                         "- guard band: 10 % per side (32 and 18 px) for the sources of the methods that take "
                         "one, 1.44x the pixels; such a source costs "))
        << r.output;
    const auto off = warplab(
        "bench --quick --frames 4 --repeats 1 --sequences pan --methods warp-full --guard-band 0 "
        "--out " +
        dir + "-off");
    ASSERT_EQ(off.status, 0) << off.output;
    EXPECT_FALSE(contains(off.output, "- guard band:")) << off.output;
    // A pan turns content into view: the band shows it, so the border error drops.
    auto borderMae = [](const std::string& output) {
        const std::size_t row = output.find("| pan | warp-full |");
        std::stringstream cells(output.substr(row, output.find('\n', row) - row));
        std::string cell;
        for (int i = 0; i <= 8; ++i) std::getline(cells, cell, '|');  // "", pan, method, sources ... border MAE
        return std::stod(cell);
    };
    EXPECT_LT(borderMae(r.output), 0.5 * borderMae(off.output)) << r.output << off.output;
    const auto bad = warplab("bench --quick --guard-band 0.7 --out " + dir + "-bad");
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_TRUE(contains(bad.output, "--guard-band")) << bad.output;
}

TEST(CliBench, QuickRunWritesTheTableCsvAndPlot) {
    const std::string dir = scratch("bench");
    const auto r = warplab(
        "bench --quick --frames 2 --repeats 1 --sequences pan,thin --methods hold15,hold120,blend --out " + dir);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "| pan | hold15 |")) << r.output;
    EXPECT_TRUE(contains(r.output, "| **all** | blend |")) << r.output;
    // A pan turns content into view that the latest 15 Hz source lacks: the border mask is not
    // empty, and holding at the display rate (the truth itself) has no error on it.
    const std::size_t panTruth = r.output.find("| pan | hold120 |");
    ASSERT_NE(panTruth, std::string::npos) << r.output;
    const std::string panTruthRow = r.output.substr(panTruth, r.output.find('\n', panTruth) - panTruth);
    EXPECT_TRUE(contains(panTruthRow, "| inf (exact) | 1.0000 | 0.00 | 0.00 |")) << panTruthRow;
    std::ifstream csv(dir + "/bench.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind("sequence,method,frame,time_s,psnr_db,ssim,border_mae,border_px,disocc_mae,disocc_px,"
                           "corr_all_lt_0p1,corr_all_lt_0p5,"
                           "corr_all_lt_1,corr_hit_lt_0p1,corr_hit_lt_0p5,corr_hit_lt_1,pass_ms,",
                           0),
              0u)
        << header;
    int rows = 0, exact = 0;
    for (std::string line; std::getline(csv, line);) {
        ++rows;
        if (line.rfind("pan,hold120,", 0) == 0 || line.rfind("thin,hold120,", 0) == 0)
            exact += contains(line, ",inf,1.00000,");  // hold at the display rate is ground truth
    }
    EXPECT_EQ(rows, 2 * 2 * 3);
    EXPECT_EQ(exact, 4);
    EXPECT_TRUE(fs::exists(dir + "/summary.md"));
    EXPECT_GT(fs::file_size(dir + "/speed_vs_error.png"), 1000u);
    EXPECT_GT(fs::file_size(dir + "/budget_vs_error.png"), 1000u);
    // Holds take no guard band: nothing in this run has one to report.
    EXPECT_FALSE(contains(r.output, "- guard band:")) << r.output;
    // The equal-budget table: hold15 shades whole frames at an eighth of the display's rate, with
    // the 15 Hz source's age; hold120 every frame.
    EXPECT_TRUE(contains(r.output, "## Equal shading budgets")) << r.output;
    EXPECT_TRUE(contains(r.output, "| 1/8 | 0.86 M | hold15 | whole frames |")) << r.output;
    EXPECT_TRUE(contains(r.output, "| 1 | 6.91 M | hold120 | whole frames | 0.00 | inf | 1.0000 | 0.00 | 0.00 |"))
        << r.output;
}

// A method that shades part of every frame is in the equal-budget table at its share, with its
// cost at each shading cost of the sweep and the age of what it shows.
TEST(CliBench, TheEqualBudgetTableListsPartialShading) {
    const std::string dir = scratch("bench_budget");
    const auto r =
        warplab("bench --quick --frames 2 --repeats 1 --sequences spheres --methods hold30,stu-4 --out " + dir);
    ASSERT_EQ(r.status, 0) << r.output;
    const std::size_t at = r.output.find("| 1/4 | 1.73 M | stu-4 | pixel lattice |");
    ASSERT_NE(at, std::string::npos) << r.output;
    const std::string row = r.output.substr(at, r.output.find('\n', at) - at);
    EXPECT_TRUE(contains(row, "| 0.0 | 0.0 |")) << row;  // shaded at every displayed instant
    EXPECT_TRUE(contains(r.output, "| 1/4 | 1.73 M | hold30 | whole frames |")) << r.output;
    std::ifstream csv(dir + "/bench.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_TRUE(contains(header, ",budget_share,family,age_mean_ms,age_p95_ms")) << header;
    EXPECT_GT(fs::file_size(dir + "/budget_vs_error.png"), 1000u);
}

// A context older than OpenGL 4.3 (macOS's 4.1; here Mesa told to report 4.1) cannot run
// warp-splat's compute passes: the bench says so, leaves it out and runs the rest.
TEST(CliBench, SkipsAMethodTheContextCannotRunAndSaysWhy) {
    const std::string dir = scratch("bench-gl41");
    const auto r = warplab::testing::runCommand(
        "MESA_GL_VERSION_OVERRIDE=4.1 " + std::string(WARPLAB_BINARY) +
        " bench --quick --frames 1 --repeats 1 --sequences pan --shading-sweep 0 --methods hold15,warp-splat --out " +
        dir);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(
        contains(r.output, "- skipped: warp-splat needs OpenGL 4.3 compute shaders; this context is OpenGL 4.1"))
        << r.output;
    EXPECT_TRUE(contains(r.output, "| pan | hold15 |")) << r.output;
    EXPECT_FALSE(contains(r.output, "| pan | warp-splat |")) << r.output;
}

// A name the bench does not know is a wrong command line: exit 2, as README promises.
TEST(CliBench, UnknownSequenceOrMethodIsNamed) {
    auto r = warplab("bench --quick --sequences orbit --out " + scratch("bench-bad"));
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.output, "unknown bench sequence 'orbit' (valid: pan, track, translate, spheres, thin)"))
        << r.output;
    r = warplab("bench --quick --methods hold15,warp-magic --out " + scratch("bench-bad"));
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(contains(r.output, "unknown method 'warp-magic' (known: hold15,")) << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;
}

}  // namespace

namespace {

// The only session file a run left in `dir`.

// replay --render's tally: "pointer cross-check on N frames whose image is exact (E of them
// logged clicks or shots, ...): the id read back disagrees on D".
struct CrossCheck {
    int frames = -1, events = -1, disagreed = -1;
};
CrossCheck crossCheckIn(const std::string& output) {
    CrossCheck c;
    const auto at = output.find("pointer cross-check on ");
    if (at == std::string::npos) return c;
    std::sscanf(output.c_str() + at, "pointer cross-check on %d frames whose image is exact (%d", &c.frames, &c.events);
    const auto d = output.find("disagrees on ", at);
    if (d != std::string::npos) c.disagreed = std::stoi(output.substr(d + 13));
    return c;
}

// "N/N outcomes reproduced": N, or -1 when the two differ or the line is missing.
int reproducedIn(const std::string& output) {
    const auto at = output.find(" outcomes reproduced");
    if (at == std::string::npos) return -1;
    const auto start = output.rfind('\n', at) == std::string::npos ? 0 : output.rfind('\n', at) + 1;
    const std::string fraction = output.substr(start, at - start);
    const auto slash = fraction.find('/');
    if (slash == std::string::npos || fraction.substr(0, slash) != fraction.substr(slash + 1)) return -1;
    return std::stoi(fraction.substr(0, slash));
}

TEST(CliSession, HeadlessBotRunThenReplayReproducesEveryOutcome) {
    const std::string dir = scratch("session-bot");
    const auto run =
        warplab("run --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                "/protocol/shooter-quick.json --participant P01 --out " + dir + " --headless --player bot:3 --seed 5");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string session = sessionIn(dir);
    ASSERT_FALSE(session.empty());
    EXPECT_TRUE(contains(run.output, session)) << run.output;
    const auto replay = warplab("replay " + session);
    EXPECT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "outcomes reproduced")) << replay.output;
    // N/N with N = the 12 test targets plus training and acclimation shots.
    const auto slash = replay.output.find('/');
    ASSERT_NE(slash, std::string::npos);
    const std::string left = replay.output.substr(0, slash);
    const std::string right = replay.output.substr(slash + 1, replay.output.find(' ', slash) - slash - 1);
    EXPECT_EQ(left, right) << replay.output;
    EXPECT_GE(std::stoi(left), 12);
}

// Kim et al.'s late-warp study, its conditions defined in the protocol file: it runs headless,
// replays exactly, and replay --render's id-buffer check of the scoring covers the
// rotation-late-warped frames, the held renders turned to the display camera.
TEST(CliSession, TheLateWarpProtocolRunsReplaysAndScoresWhatTheWarpedFrameShows) {
    const std::string dir = scratch("session-kim"), framesDir = scratch("session-kim-frames");
    const auto run =
        warplab("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                "/protocol/latewarp-kim-quick.json --participant K --out " + dir + " --headless --player bot:3");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string session = sessionIn(dir);
    ASSERT_FALSE(session.empty());
    const auto data = warplab::session::readSession(session);
    std::map<std::string, int> shots;
    std::vector<std::int64_t> rotationShots;
    for (const auto& e : data.events)
        if (e.type == "shot") {
            ++shots[e.condition];
            if (e.condition == "lag60x5-rotation") rotationShots.push_back(e.frame);
        }
    for (const char* condition : {"base60", "lag60x5", "lag60x5-rotation", "lag60x5-depth"})
        EXPECT_GE(shots[condition], 1) << condition << " was never shot at";
    const auto replay = warplab("replay " + session);
    EXPECT_EQ(replay.status, 0) << replay.output;
    EXPECT_GE(reproducedIn(replay.output), 16) << replay.output;
    // The frames before a rotation shot, and the shot's own (one near a silhouette is skipped:
    // the check then tries the next shot).
    int frames = 0, events = 0;
    for (const std::int64_t shot : rotationShots) {
        const auto rendered = warplab("replay " + session + " --render " + framesDir + " --width 320 --height 180 " +
                                      "--frames " + std::to_string(shot - 12) + ":" + std::to_string(shot));
        ASSERT_EQ(rendered.status, 0) << rendered.output;
        // The frames before the range are re-simulated, not drawn, and it says so (on stderr):
        // a late range of a long session printed nothing for minutes.
        EXPECT_TRUE(contains(rendered.output,
                             "replay --render: re-simulating frames 0 to " + std::to_string(shot - 13) +
                                 " without drawing them, then drawing " + std::to_string(shot - 12) + " to " +
                                 std::to_string(shot) + "\n"))
            << rendered.output;
        const CrossCheck check = crossCheckIn(rendered.output);
        EXPECT_EQ(check.disagreed, 0) << rendered.output;
        frames += check.frames;
        events += check.events;
        if (events >= 1) break;
    }
    EXPECT_GE(frames, 6);  // late-warped frames count as exact
    EXPECT_GE(events, 1);  // a shot judged in a late-warped frame, against its id buffer
}

// `warplab conditions` prints what each condition of a protocol is and its latency, the table
// of the README for the presets and the same numbers for a lab's own.
TEST(CliConditions, PrintsEachConditionsPartsAndLatency) {
    const auto csv =
        warplab("conditions " + std::string(WARPLAB_SOURCE_DIR) + "/protocol/latewarp-kim-quick.json --csv");
    ASSERT_EQ(csv.status, 0) << csv.output;
    EXPECT_EQ(csv.output.substr(0, csv.output.find('\n')),
              "condition,render_hz,lag_frames,fill,late_warp,view_latency_min_ms,view_latency_max_ms,"
              "scene_latency_min_ms,scene_latency_max_ms,fill_hz,refresh_hz,game,description,used_in,mean_fps,"
              "low_1pct_fps,low_5pct_fps,frame_time_median_ms,frame_time_p95_ms,frame_time_p99_ms,frame_time_max_ms,"
              "stutters,view_latency_median_ms,view_latency_p95_ms,scene_latency_median_ms,scene_latency_p95_ms");
    EXPECT_TRUE(contains(csv.output,
                         "\nlag60x5-rotation,60,10,hold,rotation,0,8.333333333333334,83.33333333333333,"
                         "100,,120,shooter,"))
        << csv.output;
    EXPECT_TRUE(contains(csv.output, "\nlag60x5,60,10,hold,none,83.33333333333333,100,83.33333333333333,100,"))
        << csv.output;
    const auto table = warplab("conditions " + std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-thesis.json");
    ASSERT_EQ(table.status, 0) << table.output;
    EXPECT_TRUE(contains(table.output, "warp15to120")) << table.output;
    EXPECT_TRUE(contains(table.output, "0.0 - 66.7 ms (0 - 8 frames)")) << table.output;
    // A protocol that does not parse: its sentence and exit status 1; no protocol: usage, 2.
    const std::string dir = scratch("conditions-bad");
    std::ofstream(dir + "/bad.json") << R"({"format_version":3,"name":"b","game":"shooter",
      "conditions":{"x":{"render_hz":60,"fill":"bireproj","late_warp":"rotation"}},"test":{"conditions":["x"]}})";
    const auto bad = warplab("conditions " + dir + "/bad.json");
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_TRUE(contains(bad.output, "conditions.x.late_warp must be \"none\" with fill \"bireproj\"")) << bad.output;
    EXPECT_EQ(warplab("conditions").status, 2);
}

TEST(CliSession, ARunDrivenByARecordedSessionsInputGivesTheSameOutcomes) {
    const std::string dir = scratch("session-source"), again = scratch("session-again");
    const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json";
    ASSERT_EQ(
        warplab("run --protocol " + protocol + " --participant A --out " + dir + " --headless --player bot:8 --seed 2")
            .status,
        0);
    const std::string source = sessionIn(dir);
    const auto rerun = warplab("run --protocol " + protocol + " --participant A --out " + again +
                               " --headless --player replay:" + source + " --seed 2");
    ASSERT_EQ(rerun.status, 0) << rerun.output;
    const auto a = warplab("replay " + source), b = warplab("replay " + sessionIn(again));
    EXPECT_EQ(a.output.substr(0, a.output.find(' ')), b.output.substr(0, b.output.find(' ')));
}

// SIGKILL at random moments of a full-length session: every completed trial survives and
// replays exactly; the replay says where the store ends. The moments count from when the store
// appears: the run checks the folder's room before it starts, which takes its own time.
TEST(CliSession, KilledRunsKeepEveryCompletedTrialAndReplay) {
    const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-thesis.json";
    int withOutcomes = 0;
    for (const char* delay : {"0.05", "0.12", "0.25", "0.4", "0.6"}) {
        const std::string dir = scratch(std::string("session-kill-") + delay);
        const std::string command = "sh -c '" + std::string(WARPLAB_BINARY) + " run --protocol " + protocol +
            " --participant K --out " + dir + " --headless --player bot:1 --seed 9 > /dev/null 2>&1 & pid=$!; i=0; " +
            "until ls " + dir + "/*.warplab-session > /dev/null 2>&1 || [ $i -gt 3000 ]; do sleep 0.01; " +
            "i=$((i+1)); done; sleep " + delay + "; kill -KILL $pid; wait $pid'";
        const int raw = std::system(command.c_str());
        (void)raw;
        const std::string session = sessionIn(dir);
        if (session.empty()) continue;  // killed before the store existed: nothing to keep
        const auto replay = warplab("replay " + session);
        EXPECT_EQ(replay.status, 3) << delay << ": incomplete, every committed trial replayed: " << replay.output;
        EXPECT_TRUE(contains(replay.output, "outcomes reproduced")) << replay.output;
        if (!contains(replay.output, " 0/0 ") && replay.output.rfind("0/0", 0) != 0) ++withOutcomes;
    }
    EXPECT_GE(withOutcomes, 2) << "no kill landed after a completed trial";
}

TEST(CliSession, TruncatedStoreReplaysUpToItsLastCompleteRecord) {
    const std::string dir = scratch("session-truncate");
    ASSERT_EQ(warplab("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                      "/protocol/shooter-quick.json --participant T --out " + dir + " --headless --player bot:4")
                  .status,
              0);
    const std::string session = sessionIn(dir);
    const auto size = fs::file_size(session);
    for (const double keep : {0.9, 0.6, 0.3}) {
        const std::string copy = dir + "/cut-" + std::to_string(static_cast<int>(keep * 10)) + ".warplab-session";
        fs::copy_file(session, copy, fs::copy_options::overwrite_existing);
        fs::resize_file(copy, static_cast<std::uintmax_t>(static_cast<double>(size) * keep));
        const auto replay = warplab("replay " + copy);
        // A cut file has lost committed data: never success. Exit 4 (damaged), naming the
        // file and where reading stopped; before, a file cut to 8 KB replayed "0/0" with exit 0.
        EXPECT_EQ(replay.status, 4) << "a store cut to " << keep << ": " << replay.output;
        EXPECT_TRUE(contains(replay.output, copy)) << replay.output;
        EXPECT_LE(replay.lines(), 3) << replay.output;
    }
}

// `session` written again into `dir` as if recorded so, `doctor` having changed its data first:
// a whole, finished session whose every commit verifies.
std::string rewritten(const std::string& session, const std::string& dir,
                      const std::function<void(warplab::session::SessionData&)>& doctor) {
    warplab::session::SessionData data = warplab::session::readSession(session);
    doctor(data);
    auto writer = warplab::session::SessionWriter::create(dir, data.header);
    for (const auto& input : data.inputs) writer.addInput(input);
    for (const auto& frame : data.frames) writer.addFrame(frame);
    for (const auto& event : data.events) writer.addEvent(event);
    writer.finish();
    return writer.path();
}

// A script archiving sessions must tell "the game no longer plays as recorded" from any other
// failure: a record that differs exits 5, an error that is not the session's exits 1.
TEST(CliSession, ReplayTellsADifferenceFromAnError) {
    const std::string dir = scratch("session-doctored");
    ASSERT_EQ(warplab("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                      "/protocol/shooter-quick.json --participant D --out " + dir + " --headless --player bot:4")
                  .status,
              0);
    const std::string session = sessionIn(dir);
    ASSERT_EQ(warplab("replay " + session).status, 0);

    const std::string differs = rewritten(session, scratch("session-doctored-input"), [](auto& data) {
        for (auto& input : data.inputs) input.buttons = 0;  // the bot's shots never happened
    });
    auto r = warplab("replay " + differs);
    EXPECT_EQ(r.status, 5) << r.output;
    EXPECT_TRUE(contains(r.output, "replay differs at record ")) << r.output;

    const std::string unreadable = rewritten(session, scratch("session-doctored-protocol"), [](auto& data) {
        data.header.protocolJson = R"({"format_version": 99, "name": "future", "game": "shooter"})";
    });
    r = warplab("replay " + unreadable);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "format_version 99 is newer than this warplab supports")) << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;
}

// A player the run does not know is a wrong command line (exit 2), said before anything starts.
TEST(CliSession, UnknownPlayerIsABadCommandLine) {
    const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json";
    const std::string dir = scratch("session-bad-player");
    for (const char* player : {"wizard", "bot:x", "sim:-1"}) {
        const auto r = warplab("run --seed 1 --protocol " + protocol + " --participant P --out " + dir +
                               " --headless --player " + std::string(player));
        EXPECT_EQ(r.status, 2) << player << ": " << r.output;
        EXPECT_EQ(r.lines(), 1) << r.output;
    }
    const auto r = warplab("run --seed 1 --protocol " + protocol + " --participant P --out " + dir +
                           " --headless --player wizard");
    EXPECT_TRUE(contains(r.output, "unknown player 'wizard' (expected bot, bot:SEED, sim, sim:SEED or replay:SESSION)"))
        << r.output;
    EXPECT_TRUE(sessionIn(dir).empty());
}

TEST(CliSession, BadResultsFolderOrParticipantNeverEscapes) {
    const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json";
    auto r = warplab("run --seed 1 --protocol " + protocol + " --participant P --out /nonexistent/results --headless");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.output, "/nonexistent/results")) << r.output;
    const std::string dir = scratch("session-evil");
    r = warplab("run --seed 1 --protocol " + protocol + " --participant '../../evil/../x' --out " + dir +
                " --headless");
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string session = sessionIn(dir);
    ASSERT_FALSE(session.empty());
    EXPECT_EQ(fs::canonical(fs::path(session)).parent_path(), fs::canonical(dir));
}

TEST(CliSession, BadProtocolIsNamed) {
    const std::string dir = scratch("session-bad-protocol");
    std::ofstream(dir + "/p.json")
        << "{\"format_version\":1,\"name\":\"x\",\"game\":\"shooter\",\"test\":{\"targets\":3}}";
    const auto r = warplab("run --seed 1 --protocol " + dir + "/p.json --participant P --out " + dir + " --headless");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.output, "test.targets")) << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;
    EXPECT_TRUE(sessionIn(dir).empty()) << "a session was started from a bad protocol";
}

}  // namespace

namespace {

TEST(CliSession, ReplayRendersTheDisplayedFramesAndCrossChecksTheReticle) {
    const std::string dir = scratch("session-render");
    ASSERT_EQ(warplab("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                      "/protocol/shooter-quick.json --participant R --out " + dir + " --headless --player bot:2")
                  .status,
              0);
    const std::string frames = dir + "/frames";
    // The first target's 0.3 s or so up to the shot, the shot, and the frozen frames after it.
    const auto r =
        warplab("replay " + sessionIn(dir) + " --render " + frames + " --frames 0:59 --width 320 --height 180");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "wrote 60 frames")) << r.output;
    const CrossCheck check = crossCheckIn(r.output);
    EXPECT_GE(check.frames, 20) << r.output;  // the frames before the shot, the target clear of its outline
    EXPECT_EQ(check.events, 1) << r.output;  // the shot itself
    EXPECT_EQ(check.disagreed, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "outcomes reproduced")) << r.output;
    const auto image = warplab::image::readPng(frames + "/frame_0000040.png");
    EXPECT_EQ(image.width, 320);
    EXPECT_TRUE(fs::exists(frames + "/frame_0000059.png"));
    EXPECT_FALSE(fs::exists(frames + "/frame_0000060.png"));
    EXPECT_EQ(warplab("replay " + sessionIn(dir) + " --render " + frames + " --frames 9:3").status, 2);
}

}  // namespace

namespace {

// The study as published, start to end: acclimation, training, 675 test targets.
TEST(CliSession, FullThesisSessionRunsToTheEndAndReplaysExactly) {
    const std::string dir = scratch("session-thesis");
    const auto run =
        warplab("run --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                "/protocol/shooter-thesis.json --participant T01 --out " + dir + " --headless --player bot:4 --seed 8");
    ASSERT_EQ(run.status, 0) << run.output;
    const auto replay = warplab("replay " + sessionIn(dir));
    ASSERT_EQ(replay.status, 0) << replay.output;
    EXPECT_FALSE(contains(replay.output, "incomplete")) << replay.output;
    const int reproduced = std::stoi(replay.output.substr(0, replay.output.find('/')));
    EXPECT_EQ(replay.output.substr(0, replay.output.find(' ')),
              std::to_string(reproduced) + "/" + std::to_string(reproduced));
    EXPECT_GT(reproduced, 675);  // the test's 675 targets plus training and acclimation shots
}

}  // namespace

namespace {

// The click game (seed 000 section 8) through the same runner, replay and renderer.
TEST(CliClick, FullYangSessionHasEveryMatchAndRatingAndReplaysExactly) {
    const std::string dir = scratch("click-yang");
    const auto run =
        warplab("run --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                "/protocol/click-yang.json --participant C01 --out " + dir + " --headless --player bot:4 --seed 8");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_FALSE(contains(run.output, "stand")) << "every mode has its own renderer now: " << run.output;
    const auto data = warplab::session::readSession(sessionIn(dir));
    EXPECT_TRUE(data.completed) << data.note;
    int matches = 0, ratings = 0, clicks = 0;
    for (const auto& e : data.events) {
        matches += e.type == "match";
        ratings += e.type == "rating";
        clicks += e.type == "click";
    }
    EXPECT_EQ(matches, 21);  // 7 practice + 14 scored
    EXPECT_EQ(ratings, 84);
    const auto replay = warplab("replay " + sessionIn(dir));
    ASSERT_EQ(replay.status, 0) << replay.output;
    EXPECT_EQ(reproducedIn(replay.output), clicks) << replay.output;
    EXPECT_GT(clicks, 21 * 10);
}

TEST(CliClick, ReplayRenderDrawsTheCursorAndAssertsWhatIsUnderIt) {
    const std::string dir = scratch("click-render");
    ASSERT_EQ(warplab("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                      "/protocol/click-quick.json --participant R --out " + dir +
                      " --headless --player bot:2 --width 640 --height 360")
                  .status,
              0);
    const std::string frames = dir + "/frames";
    // From the ready screen well into the first match, clicks included.
    const auto r =
        warplab("replay " + sessionIn(dir) + " --render " + frames + " --frames 20:219 --width 320 --height 180");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "wrote 200 frames")) << r.output;
    const CrossCheck check = crossCheckIn(r.output);
    EXPECT_GE(check.frames, 60) << r.output;
    EXPECT_GE(check.events, 1) << r.output;
    EXPECT_EQ(check.disagreed, 0) << r.output;
    EXPECT_GT(reproducedIn(r.output), 0) << r.output;
}

TEST(CliClick, MalformedClickProtocolsAreNamed) {
    const std::string dir = scratch("click-bad-protocol");
    const std::pair<const char*, const char*> cases[] = {
        {R"("physics":{"gravity_m_per_s2":-9.81})", "physics.gravity_m_per_s2"},
        {R"("matches":{"rounds":[{"name":"a","scored":true,"matches_per_mode":0}]})", "matches_per_mode"},
        {R"("matches":{"modes":["conv60","conv61"]})", "conv61"},
        {R"("ratings":{"statements":["I enjoyed playing this game",""]})", "ratings.statements[1]"},
        // Only the physics can tell: the protocol's range allows it, the box does not.
        {R"("physics":{"sphere_radius_m":1.95})", "physics.sphere_radius_m must be"},
        {R"("physics":{"sphere_radius_m":1.0,"sphere_count":40})", "physics.sphere_count must be"},
    };
    for (const auto& [section, field] : cases) {
        std::ofstream(dir + "/p.json") << R"({"format_version":1,"name":"x","game":"click",)" << section << "}";
        const auto r =
            warplab("run --seed 1 --protocol " + dir + "/p.json --participant P --out " + dir + " --headless");
        EXPECT_EQ(r.status, 1) << section;
        EXPECT_TRUE(contains(r.output, field)) << section << ": " << r.output;
        EXPECT_EQ(r.lines(), 1) << r.output;
    }
    std::ofstream(dir + "/p.json") << R"({"format_version":1,"name":"x","game":"pong"})";
    const auto r = warplab("run --seed 1 --protocol " + dir + "/p.json --participant P --out " + dir + " --headless");
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(contains(r.output, "\"pong\"")) << r.output;
    // A shooter file whose "game" was changed to click: the game field is named, not the
    // shooter's format_version 3 that no click protocol has.
    std::ifstream kim(std::string(WARPLAB_SOURCE_DIR) + "/protocol/latewarp-kim-quick.json");
    std::string shooter((std::istreambuf_iterator<char>(kim)), std::istreambuf_iterator<char>());
    const std::string game = "\"game\": \"shooter\"";
    ASSERT_NE(shooter.find(game), std::string::npos);
    shooter.replace(shooter.find(game), game.size(), "\"game\": \"click\"");
    std::ofstream(dir + "/p.json") << shooter;
    const auto wrongGame =
        warplab("run --seed 1 --protocol " + dir + "/p.json --participant P --out " + dir + " --headless");
    EXPECT_EQ(wrongGame.status, 1);
    EXPECT_TRUE(contains(wrongGame.output, "p.json': game is \"click\", but format_version 3")) << wrongGame.output;
    EXPECT_TRUE(contains(wrongGame.output, "shooter protocol's")) << wrongGame.output;
    EXPECT_EQ(wrongGame.lines(), 1) << wrongGame.output;
    EXPECT_TRUE(sessionIn(dir).empty()) << "a session was started from a bad protocol";
}

// A kill in the middle of a match keeps every completed match, which replays exactly.
TEST(CliClick, KilledRunsKeepEveryCompletedMatch) {
    const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/click-yang.json";
    int withMatches = 0;
    // The later kills are for a loaded machine, where the first match takes longer to end.
    for (const char* delay : {"0.15", "0.3", "0.6", "1.2", "2.4"}) {
        const std::string dir = scratch(std::string("click-kill-") + delay);
        const std::string command = "timeout -s KILL " + std::string(delay) + " " + WARPLAB_BINARY +
            " run --protocol " + protocol + " --participant K --out " + dir +
            " --headless --player bot:1 --seed 9 > /dev/null 2>&1";
        (void)std::system(command.c_str());
        const std::string session = sessionIn(dir);
        if (session.empty()) continue;
        const auto data = warplab::session::readSession(session);
        if (data.completed) continue;  // finished before the kill
        int matches = 0, matchStarts = 0;
        for (const auto& e : data.events) matches += e.type == "match", matchStarts += e.type == "match_start";
        // Every match that was begun is either complete or the one the kill interrupted.
        EXPECT_LE(matchStarts - matches, 1) << delay;
        const auto replay = warplab("replay " + session);
        EXPECT_EQ(replay.status, 3) << delay << ": incomplete, every committed match replayed: " << replay.output;
        EXPECT_GE(reproducedIn(replay.output), 0) << replay.output;
        withMatches += matches > 0;
    }
    EXPECT_GE(withMatches, 1) << "no kill landed after a completed match";
}

// Sessions recorded in format 1 (before the games plugged in) still read and replay.
TEST(CliSession, AVersion1SessionStillReplaysExactly) {
    const auto replay =
        warplab("replay " + std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v1-shooter-quick.warplab-session");
    ASSERT_EQ(replay.status, 0) << replay.output;
    EXPECT_GT(reproducedIn(replay.output), 12) << replay.output;
}

// And format 2 (before per-session ids): the click game's outcomes, every one.
TEST(CliSession, AVersion2SessionStillReplaysExactly) {
    const auto replay =
        warplab("replay " + std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v2-click-quick.warplab-session");
    ASSERT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "78/78 outcomes reproduced")) << replay.output;
}

// And format 3 (before resumed sessions): the shooter's outcomes, every one.
TEST(CliSession, AVersion3SessionStillReplaysExactly) {
    const auto replay =
        warplab("replay " + std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v3-shooter-quick.warplab-session");
    ASSERT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "39/39 outcomes reproduced")) << replay.output;
}

// And format 4 (before typed text, its input rows read with text ""): the click game's
// outcomes, every one, its ratings included.
TEST(CliSession, AVersion4SessionStillReplaysExactly) {
    const auto replay =
        warplab("replay " + std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v4-click-quick.warplab-session");
    ASSERT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "4/4 outcomes reproduced (14 events, 306 frames")) << replay.output;
}

TEST(CliExport, ExportsARunAndNamesWhatIsWrongWithItsArguments) {
    const std::string results = scratch("export-results"), out = scratch("export-out");
    ASSERT_EQ(warplab("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json" +
                      " --participant E1 --out " + results + " --headless --player bot:2")
                  .status,
              0);
    const auto ok = warplab("export " + results + " --out " + out);
    EXPECT_EQ(ok.status, 0) << ok.output;
    for (const char* name : {"sessions.csv", "shots.csv", "hitrates.csv", "matches.csv", "ratings.csv",
                             "conditions.csv", "frametimes.csv", "latency.csv", "games.csv", "pacing.csv"}) {
        EXPECT_TRUE(fs::exists(out + "/" + name)) << name;
        EXPECT_TRUE(contains(ok.output, out + "/" + name)) << ok.output;
    }
    EXPECT_TRUE(contains(ok.output, "[1/1]")) << "progress per session: " << ok.output;

    const auto none = warplab("export");
    EXPECT_EQ(none.status, 2) << none.output;
    const auto two = warplab("export " + results + " " + results);
    EXPECT_EQ(two.status, 2) << two.output;
    const auto missing = warplab("export " + results + "/nope --out " + out);
    EXPECT_EQ(missing.status, 1) << missing.output;
    EXPECT_TRUE(contains(missing.output, results + "/nope")) << missing.output;
    EXPECT_EQ(missing.lines(), 1) << missing.output;
}

// A reader of the run's output that goes away (`| head -1`, a dying tee) must not end the
// session: before SIGPIPE was ignored this run died at its second progress line with 80 of
// 1353 outcomes.
TEST(CliSession, AClosedOutputPipeDoesNotEndTheSession) {
    const std::string dir = scratch("closed-pipe");
    const std::string command = "bash -c '" + std::string(WARPLAB_BINARY) + " run --seed 1 --protocol " +
        std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-thesis.json --participant P --out " + dir +
        " --headless --player bot:2 2>&1 | head -1; exit ${PIPESTATUS[0]}'";
    const auto r = warplab::testing::runCommand(command);
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;  // the pipe really closed after one line
    const std::string session = sessionIn(dir);
    ASSERT_FALSE(session.empty());
    const auto data = warplab::session::readSession(session);
    EXPECT_TRUE(data.completed) << data.note;
    int outcomes = 0;
    for (const auto& e : data.events) outcomes += e.type == "shot" || e.type == "timeout";
    EXPECT_GT(outcomes, 1000);
}

// Without --seed every participant got seed 1, so the same trial order and target spawns. Each
// run now draws its own, says it, and stores it, and each session replays from its own.
TEST(CliSession, RunsWithoutASeedDrawTheirOwnAndEachReplays) {
    const std::string dir = scratch("drawn-seeds");
    std::set<std::uint64_t> seeds;
    for (const char* participant : {"D1", "D2"}) {
        const auto r = warplab("run --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                               "/protocol/shooter-quick.json --participant " + participant + " --out " + dir +
                               " --headless --player bot:1");
        ASSERT_EQ(r.status, 0) << r.output;
        const std::string said = "seed ";
        const std::size_t at = r.output.find(said);
        ASSERT_NE(at, std::string::npos) << r.output;
        const std::uint64_t seed = std::stoull(r.output.substr(at + said.size()));
        EXPECT_TRUE(contains(r.output,
                             "seed " + std::to_string(seed) + " drawn at random; --seed " + std::to_string(seed) +
                                 " repeats this session"))
            << r.output;
        EXPECT_LE(seed, 1ULL << 62);
        seeds.insert(seed);
        std::string session;
        for (const auto& entry : fs::directory_iterator(dir))
            if (contains(entry.path().filename().string(), participant)) session = entry.path().string();
        EXPECT_EQ(warplab::session::readSession(session).header.seed, seed);
        const auto replay = warplab("replay " + session);
        EXPECT_EQ(replay.status, 0) << replay.output;
    }
    EXPECT_EQ(seeds.size(), 2u) << "two runs drew the same seed";
}

// Two runs into one results folder wrote two sessions side by side (two windows stacked on one
// rig). The second is refused while the first runs, naming the folder and who holds it, and
// creates nothing; once the first is killed with SIGKILL its lock file blocks no one.
TEST(CliSession, ASecondRunIntoAFolderInUseIsRefusedUntilTheFirstEnds) {
    const std::string dir = scratch("folder-in-use");
    const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-thesis.json";
    const std::string binary = WARPLAB_BINARY;
    const pid_t first = ::fork();
    ASSERT_GE(first, 0);
    if (first == 0) {
        ::freopen("/dev/null", "w", stdout);
        ::freopen("/dev/null", "w", stderr);
        ::execl(binary.c_str(), binary.c_str(), "run", "--protocol", protocol.c_str(), "--participant", "FIRST",
                "--out", dir.c_str(), "--headless", "--player", "bot:3", "--seed", "1", static_cast<char*>(nullptr));
        std::_Exit(127);
    }
    const std::string session = sessionAppearingIn(dir);
    ASSERT_FALSE(session.empty());
    // Session files only: the first run's -wal and -shm appear when it opens its file, at a
    // moment of its own.
    const auto sessionFiles = [&] {
        std::size_t n = 0;
        for (const auto& entry : fs::directory_iterator(dir)) n += entry.path().extension() == ".warplab-session";
        return n;
    };
    const std::size_t files = sessionFiles();

    const auto second = warplab("run --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                                "/protocol/shooter-quick.json --participant SECOND --out " + dir +
                                " --headless --player bot:1 --seed 1");
    EXPECT_EQ(second.status, 1) << second.output;
    EXPECT_TRUE(contains(second.output,
                         "'" + dir +
                             "' is in use by another warplab session (participant FIRST, "
                             "protocol shooter-thesis, pid " +
                             std::to_string(first)))
        << second.output;
    EXPECT_TRUE(contains(second.output, "wait for it to end, or use another --out")) << second.output;
    EXPECT_EQ(second.lines(), 1) << second.output;
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_FALSE(contains(entry.path().filename().string(), "SECOND")) << entry.path();
    EXPECT_EQ(sessionFiles(), files) << "the refused run created nothing";

    // Export reads the folder while it is in use, passing over the lock file.
    const auto exported = warplab("export " + dir + " --out " + scratch("folder-in-use-export"));
    EXPECT_EQ(exported.status, 0) << exported.output;
    EXPECT_FALSE(contains(exported.output, ".warplab-lock")) << exported.output;

    ::kill(first, SIGKILL);
    int status = 0;
    ::waitpid(first, &status, 0);
    ASSERT_TRUE(fs::exists(fs::path(dir) / ".warplab-lock")) << "a killed run leaves its lock file";
    const auto next =
        warplab("run --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                "/protocol/shooter-quick.json --participant NEXT --out " + dir + " --headless --player bot:1 --seed 1");
    EXPECT_EQ(next.status, 0) << next.output;
    EXPECT_FALSE(fs::exists(fs::path(dir) / ".warplab-lock")) << "a run that ends removes it";
}

// Another program holding the session file's write lock for 10 s (a DB browser, sqlite3
// without -readonly, a script's BEGIN IMMEDIATE) made the run exit 1 with "database is
// locked" at 245 of 1,353 outcomes. The run must go on, say so, and lose nothing.
TEST(CliSession, AnotherProgramsWriteLockDoesNotEndTheSession) {
    const std::string dir = scratch("write-lock");
    warplab::testing::Result run;
    std::thread runner([&] {
        run = warplab("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                      "/protocol/shooter-thesis.json --participant P --out " + dir + " --headless --player bot:3");
    });
    // As soon as the session file exists, take its write lock, as such a program would.
    const std::string session = sessionAppearingIn(dir);
    sqlite3* db = nullptr;
    bool locked =
        !session.empty() && sqlite3_open_v2(session.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK;
    if (locked) {
        sqlite3_busy_timeout(db, 2000);
        locked = sqlite3_exec(db, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr) == SQLITE_OK;
    }
    std::this_thread::sleep_for(std::chrono::seconds(10));
    if (db) sqlite3_exec(db, "COMMIT", nullptr, nullptr, nullptr);
    sqlite3_close(db);
    runner.join();
    ASSERT_TRUE(locked) << "could not take the lock on '" << session << "': " << run.output;

    EXPECT_EQ(run.status, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "holds the write lock")) << run.output;  // the supervisor was told
    EXPECT_TRUE(contains(run.output, "no commit was lost")) << run.output;
    const auto data = warplab::session::readSession(session);
    EXPECT_TRUE(data.completed) << data.note;
    int outcomes = 0;
    for (const auto& e : data.events) outcomes += e.type == "shot" || e.type == "timeout";
    EXPECT_GT(outcomes, 1000);
    const auto replay = warplab("replay " + session);
    EXPECT_EQ(replay.status, 0) << replay.output;
}

// A reader (an export, a lab's sqlite3 script) that holds a read transaction from the
// session's first commit until after its run ends keeps the last commits in the -wal: the run
// must still leave the whole session in the one file before it says it is done. The file is
// then copied alone, as an archive script would, and replays in full.
TEST(CliSession, AReaderHoldingTheFinishBackStillLeavesTheWholeSessionInTheFile) {
    const std::string dir = scratch("held-finish"), elsewhere = scratch("held-finish-copy");
    warplab::testing::Result run;
    std::thread runner([&] {
        run = warplab("run --seed 1 --protocol " + std::string(WARPLAB_SOURCE_DIR) +
                      "/protocol/click-quick.json --participant R --out " + dir + " --headless --player bot:3");
    });
    const std::string session = sessionAppearingIn(dir);
    sqlite3* db = nullptr;
    bool reading =
        !session.empty() && sqlite3_open_v2(session.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK;
    if (reading) {
        sqlite3_busy_timeout(db, 2000);  // the writer may be switching the new file to WAL mode
        reading = sqlite3_exec(db, "BEGIN; SELECT count(*) FROM events;", nullptr, nullptr, nullptr) == SQLITE_OK;
    }
    runner.join();  // the run ends while the reader still holds its snapshot
    ASSERT_TRUE(reading) << "could not read '" << session << "': " << run.output;
    EXPECT_EQ(run.status, 0) << run.output;
    const std::string copy = elsewhere + "/copy.warplab-session";
    fs::copy_file(session, copy);  // the file alone
    sqlite3_exec(db, "COMMIT", nullptr, nullptr, nullptr);
    sqlite3_close(db);
    // 0: every outcome reproduced, the session intact and finished -- as many as the original.
    const auto replay = warplab("replay " + copy), original = warplab("replay " + session);
    EXPECT_EQ(replay.status, 0) << replay.output;
    EXPECT_GT(reproducedIn(replay.output), 50) << replay.output;
    EXPECT_EQ(reproducedIn(replay.output), reproducedIn(original.output)) << original.output;
}

// Protocol files a parser could be driven into the ground by: 100,000 levels of '[' took 54 s
// and 9 GB before failing (and 30,000 overflowed the stack); an endless pipe hung the read.
TEST(CliSession, HostileProtocolFilesAreRefusedAtOnceByName) {
    const std::string dir = scratch("hostile-protocols");
    const std::string deep = dir + "/deep.json", wide = dir + "/big.json", pipe = dir + "/pipe.json";
    const std::string nul = dir + "/nul.json";
    { std::ofstream(deep) << std::string(100000, '[') << std::string(100000, ']'); }
    {
        // A valid protocol, a NUL, then another document: the parser used to stop at the NUL.
        std::ifstream quick(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
        std::ofstream(nul) << quick.rdbuf() << '\0' << R"({"format_version": 3})";
    }
    { std::ofstream(wide) << "{\"name\": \"" << std::string(2 << 20, 'x') << "\"}"; }
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    const std::pair<std::string, std::string> cases[] = {
        {deep, "nested deeper than 32 levels at line 1"},
        {wide, "more than a protocol may be"},
        {pipe, "is a FIFO (a named pipe), not a regular file"},
        {nul, "has a NUL byte at line 49"},
    };
    for (const auto& [file, why] : cases) {
        const auto r =
            warplab::testing::runCommand("timeout 20 " + std::string(WARPLAB_BINARY) + " run --seed 1 --protocol " +
                                         file + " --participant P --out " + dir + " --headless");
        EXPECT_EQ(r.status, 1) << r.output;
        EXPECT_TRUE(contains(r.output, file) && contains(r.output, why)) << r.output;
        EXPECT_EQ(r.lines(), 1) << r.output;
    }
}

// Values taken in part, flags ignored in a combination, a flag given twice, ids that cannot
// be read back: each was silently accepted (--frames 1e3:2e3 became 1:2, 0:10abc became 0:10,
// --shading-sweep 12abc became 12, a repeated --participant kept the last). Now exit 2 with
// one sentence naming the flag.
TEST(Cli, BadFlagValuesAreRefusedWithASentence) {
    const std::string dir = scratch("bad-flags");
    const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json";
    ASSERT_EQ(warplab("run --seed 1 --protocol " + protocol + " --participant P --out " + dir + " --headless").status,
              0);
    const std::string session = sessionIn(dir);
    const std::pair<std::string, std::string> cases[] = {
        {"replay " + session + " --render " + dir + "/f --frames 1e3:2e3", "--frames"},
        {"replay " + session + " --render " + dir + "/f --frames 0:10abc", "--frames"},
        {"replay " + session + " --render " + dir + "/f --frames :5", "--frames"},
        {"replay " + session + " --frames 0:10", "--frames only applies with --render"},
        // Past the session's end: refused before anything is simulated or written (it used to
        // re-simulate for minutes and write nothing).
        {"replay " + session + " --render " + dir + "/f --frames 10000000:10000010", "ends at frame"},
        {"replay " + session + " --width 64", "--width only applies with --render"},
        {"bench --shading-sweep 12abc --out " + dir + "/b", "--shading-sweep"},
        {"run --protocol " + protocol + " --participant A --participant B --out " + dir + " --headless",
         "--participant of 'warplab run' is given more than once"},
        {"run --protocol " + protocol + " --participant '' --out " + dir + " --headless",
         "--participant must not be empty"},
        {"run --protocol " + protocol + " --participant '  ' --out " + dir + " --headless",
         "--participant must not be empty"},
        {"run --protocol " + protocol + " --participant $'bad\\xffid' --out " + dir + " --headless",
         "--participant must be UTF-8"},
        {"run --protocol " + protocol + " --participant " + std::string(200, 'p') + " --out " + dir + " --headless",
         "at most 128 bytes"},
        // A player spec without its seed, a signed seed, a zero-sized render, empty lists: each
        // was taken as a default.
        {"run --protocol " + protocol + " --participant P --out " + dir + " --headless --player bot:",
         "--player bot:SEED needs a whole number, got ''"},
        {"run --protocol " + protocol + " --participant P --out " + dir + " --headless --seed +5",
         "--seed of 'warplab run' needs an integer, got '+5'"},
        {"replay " + session + " --render " + dir + "/f --width 0", "--width of 'warplab replay' must be"},
        {"bench --sequences '' --out " + dir + "/b", "--sequences of 'warplab bench' needs a list"},
        {"bench --methods , --out " + dir + "/b", "--methods of 'warplab bench' needs a list"},
        {"bench --shading-sweep '' --out " + dir + "/b", "--shading-sweep of 'warplab bench' needs a list"},
        // Window-only options under --headless were ignored, a bad value unnoticed.
        {"run --protocol " + protocol + " --participant P --out " + dir + " --headless --cm-per-360 abc",
         "--cm-per-360 only applies in the window"},
        {"run --protocol " + protocol + " --participant P --out " + dir + " --headless --input-script s.txt",
         "--input-script only applies in the window"},
    };
    for (const auto& [arguments, named] : cases) {
        const auto r =
            warplab::testing::runCommand("bash -c \"" + std::string(WARPLAB_BINARY) + " " + arguments + "\"");
        EXPECT_EQ(r.status, 2) << arguments << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, named)) << arguments << "\n" << r.output;
        EXPECT_EQ(r.lines(), 1) << arguments << "\n" << r.output;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "no session was started";
}

// `warplab render` run from inside `dir`, so a file written by a path left empty lands there.
Result renderIn(const std::string& dir, const std::string& arguments) {
    return warplab::testing::runCommand("cd '" + dir + "' && " + std::string(WARPLAB_BINARY) + " render " + arguments);
}

std::size_t filesIn(const std::string& dir) {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// Each numeric flag of render is written whole and lies in a stated range. Out of range they
// rendered a broken frame (--yaw 1e308 turned the camera by an infinite angle, --pitch 90 turned
// the view over) or failed after the context was made without naming the flag (--time 1e308:
// "t: must be finite"). Refused before anything is made, naming the flag, the range, the value.
TEST(Cli, RenderNumbersOutsideTheirRangeAreRefusedWithTheRange) {
    const std::string dir = scratch("render-ranges");
    const std::string range = "of 'warplab render' must be between ";
    const std::pair<std::string, std::string> cases[] = {
        {"--yaw 1e308", "option --yaw " + range + "-36000 and 36000, got 1e308"},
        {"--yaw -36000.5", "option --yaw " + range + "-36000 and 36000, got -36000.5"},
        {"--pitch 90", "option --pitch " + range + "-89 and 89, got 90"},
        {"--pitch -1e308", "option --pitch " + range + "-89 and 89, got -1e308"},
        {"--time 1e308", "option --time " + range + "0 and 1000000, got 1e308"},
        {"--time -0.5", "option --time " + range + "0 and 1000000, got -0.5"},
        {"--speed 100.5", "option --speed " + range + "0 and 100, got 100.5"},
        {"--speed -1", "option --speed " + range + "0 and 100, got -1"},
        {"--fov 0.5", "option --fov " + range + "1 and 179, got 0.5"},
        {"--show -1", "option --show " + range + "0 and 3600, got -1"},
        {"--show 1e308", "option --show " + range + "0 and 3600, got 1e308"},
        {"--method warp-sparse8 --source-yaw 1e308", "option --source-yaw " + range + "-36000 and 36000, got 1e308"},
        {"--method warp-sparse8 --source-pitch -90", "option --source-pitch " + range + "-89 and 89, got -90"},
        {"--method warp-sparse8 --source-time 1000001", "option --source-time " + range + "0 and 1000000, got 1000001"},
        {"--method blend --next-time 1e308", "option --next-time " + range + "0 and 1000000, got 1e308"},
        // Not numbers at all, or not only numbers.
        {"--yaw 5deg", "option --yaw of 'warplab render' needs a number, got '5deg'"},
        {"--yaw nan", "option --yaw of 'warplab render' needs a number, got 'nan'"},
        {"--time ' 1'", "option --time of 'warplab render' needs a number, got ' 1'"},
        {"--seed ' 64'", "option --seed of 'warplab render' needs an integer, got ' 64'"},
        {"--method ''", "option --method of 'warplab render' needs a method name, got ''"},
    };
    for (const auto& [arguments, sentence] : cases) {
        const auto r = renderIn(dir, "--width 16 --height 16 " + arguments);
        EXPECT_EQ(r.status, 2) << arguments << "\n" << r.output;
        EXPECT_TRUE(contains(r.output, sentence)) << arguments << "\n" << r.output;
        EXPECT_EQ(r.lines(), 1) << arguments << "\n" << r.output;
    }
    EXPECT_EQ(filesIn(dir), 0u) << "a refused render wrote something";
    // The ends of every range are frames worth rendering.
    for (const std::string edges : {"--yaw -36000 --pitch -89 --time 0 --speed 0 --show 0",
                                    "--yaw 36000 --pitch 89 --time 1000000 --speed 100"}) {
        const auto r = renderIn(dir, "--width 16 --height 16 --out edge.png " + edges);
        EXPECT_EQ(r.status, 0) << edges << "\n" << r.output;
    }
}

// An empty or blank path named a file by its suffix alone: --raw '' wrote "-depth.pfm" into the
// working directory, --out '' failed only after rendering. Now each is refused by name.
TEST(Cli, RenderRefusesEmptyOrBlankPaths) {
    const std::string dir = scratch("render-empty-paths");
    for (const std::string flag : {"out", "depth", "ids", "velocity", "raw", "truth"}) {
        for (const std::string value : {"''", "'  '"}) {
            const std::string method = flag == "truth" ? "--method blend " : "";
            const std::string arguments = "--width 16 --height 16 " + method + "--" + flag + " " + value;
            const auto r = renderIn(dir, arguments);
            EXPECT_EQ(r.status, 2) << arguments << "\n" << r.output;
            EXPECT_TRUE(contains(r.output, "option --" + flag + " of 'warplab render' needs a path, got " + value))
                << arguments << "\n"
                << r.output;
            EXPECT_EQ(r.lines(), 1) << arguments << "\n" << r.output;
        }
    }
    EXPECT_EQ(filesIn(dir), 0u) << "a refused render wrote something";
}

// render and the protocols share one field-of-view range (shooter/shooter_protocol.h): a view a
// protocol may ask for can be rendered, and a value the one refuses the other refuses, naming
// the same range. render once refused the ends 1 and 179 that protocols accept.
TEST(Cli, RenderAndProtocolsShareTheFieldOfViewRange) {
    const std::string dir = scratch("render-fov");
    for (const double fov : {warplab::protocol::kMinVerticalFovDeg, warplab::protocol::kMaxVerticalFovDeg}) {
        const auto r = renderIn(dir, "--width 16 --height 16 --out fov.png --fov " + std::to_string(fov));
        EXPECT_EQ(r.status, 0) << fov << "\n" << r.output;
    }
    const std::string wide = "179.5";
    const auto rendered = renderIn(dir, "--width 16 --height 16 --fov " + wide);
    EXPECT_EQ(rendered.status, 2) << rendered.output;
    EXPECT_TRUE(contains(rendered.output, "option --fov of 'warplab render' must be between 1 and 179, got " + wide))
        << rendered.output;

    const std::string protocol = dir + "/wide.json";
    std::ofstream(protocol) << R"({"format_version": 2, "name": "wide", "game": "shooter",
                                   "display": {"vertical_fov_deg": )"
                            << wide << "}}";
    const auto run = warplab("run --seed 1 --protocol " + protocol + " --participant P --out " + dir + " --headless");
    EXPECT_EQ(run.status, 1) << run.output;
    EXPECT_TRUE(contains(run.output, "display.vertical_fov_deg must be a number between 1 and 179, got " + wide))
        << run.output;
}

}  // namespace
