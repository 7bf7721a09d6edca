// `warplab demo`: a tiny simulated study through run -> replay -> export -> analyse, end to end,
// and what it does with bad input. The numbers are carried through: every hit
// count the report gives is the one the session logged.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/cli_support.h"
#include "session/session_store.h"

namespace {

namespace fs = std::filesystem;
using warplab::testing::contains;
using warplab::testing::warplab;

std::string scratch(const std::string& name) { return warplab::testing::scratch("cli-demo", name); }

std::vector<fs::path> filesIn(const fs::path& dir, const std::string& extension) {
    std::vector<fs::path> found;
    if (fs::is_directory(dir))
        for (const auto& entry : fs::directory_iterator(dir))
            if (entry.path().extension() == extension) found.push_back(entry.path());
    return found;
}

bool isPng(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    in.read(magic, 8);
    return in && std::string(magic + 1, 3) == "PNG" && fs::file_size(path) > 2000;
}

TEST(CliDemo, ATinySimulatedStudyIsRunReplayedExportedAndAnalysed) {
    const std::string out = scratch("tiny");
    const auto demo = warplab("demo --out " + out + " --participants 2 --protocols shooter-quick,click-quick --jobs 2");
    ASSERT_EQ(demo.status, 0) << demo.output;
    EXPECT_TRUE(contains(demo.output, "2 simulated participants (sim) x 2 protocols, 2 at a time")) << demo.output;
    EXPECT_TRUE(contains(demo.output, "[4/4] ")) << demo.output;
    EXPECT_TRUE(contains(demo.output, "4 sessions in " + out + "/results, every outcome replayed")) << demo.output;

    // Four complete sessions by the perceptual participant, one log each.
    const auto sessions = filesIn(fs::path(out) / "results", ".warplab-session");
    ASSERT_EQ(sessions.size(), 4u);
    EXPECT_EQ(filesIn(fs::path(out) / "logs", ".log").size(), 4u);
    // participant -> condition -> test-phase hits as displayed, from the sessions themselves.
    std::map<std::string, std::map<std::string, int>> shooterHits;
    for (const auto& path : sessions) {
        const auto data = warplab::session::readSession(path.string());
        EXPECT_TRUE(data.completed) << path;
        EXPECT_EQ(data.header.player, "sim:" + data.header.participant.substr(4)) << path;
        if (nlohmann::json::parse(data.header.protocolJson).at("name") != "shooter-quick") continue;
        for (const auto& e : data.events)
            if (e.phase == "test" && (e.type == "shot" || e.type == "timeout"))
                shooterHits[data.header.participant][e.condition] += e.displayedOutcome == "hit";
    }
    ASSERT_EQ(shooterHits.size(), 2u);

    // Exported and analysed: the report's hit counts are the sessions' own.
    for (const char* csv : {"sessions.csv", "shots.csv", "hitrates.csv", "matches.csv", "ratings.csv"})
        EXPECT_TRUE(fs::is_regular_file(fs::path(out) / "export" / csv)) << csv;
    std::ifstream in(fs::path(out) / "report" / "report.json");
    ASSERT_TRUE(in) << demo.output;
    const nlohmann::json report = nlohmann::json::parse(in);
    const auto& rates = report.at("games").at("shooter").at("hit_rates");
    int compared = 0;
    for (const auto& [participant, conditions] : shooterHits) {
        ASSERT_EQ(conditions.size(), 3u) << participant;
        for (const auto& [condition, hits] : conditions) {
            EXPECT_EQ(rates.at(participant).at(condition).at("hits").get<int>(), hits)
                << participant << " " << condition;
            EXPECT_EQ(rates.at(participant).at(condition).at("shots").get<int>(), 4) << participant << " " << condition;
            ++compared;
        }
    }
    EXPECT_EQ(compared, 6);
    // Sign tests with a sample-size plan for every pair of the shooter's conditions, and the figures.
    int planned = 0;
    for (const auto& test : report.at("sign_tests"))
        planned += test.at("game") == "shooter" && test.at("participants") == 2 && test.contains("planning");
    EXPECT_EQ(planned, 3);
    const auto figures = report.at("figures");
    EXPECT_GE(figures.size(), 4u);
    for (const auto& figure : figures)
        EXPECT_TRUE(isPng(fs::path(out) / "report" / figure.get<std::string>())) << figure;
    std::ifstream md(fs::path(out) / "report" / "report.md");
    const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_TRUE(contains(text, "Planning (shooter)")) << text.substr(0, 2000);
    // The report opens with the trial-level mixed models and then their sample-size plan by
    // simulation, which two participants are too few to simulate new ones from: it says so.
    EXPECT_EQ(text.find("\n## "), text.find("\n## Mixed models, trial by trial")) << text.substr(0, 2000);
    EXPECT_FALSE(report.at("power").at("available").get<bool>());
    const std::string plan = report.at("power").at("sentence");
    // One reason per model, in the order the models were fitted (the export's order of games).
    EXPECT_EQ(plan.rfind("Sample size by simulation left out: ", 0), 0u) << plan;
    EXPECT_TRUE(contains(plan, "shooter/hit: the pilot has too little data: 2 participants")) << plan;
    EXPECT_TRUE(contains(plan, "click/hit: the pilot has too little data: 2 participants")) << plan;
    EXPECT_TRUE(contains(text, plan)) << text.substr(0, 4000);
}

// The demo runs a protocol whose conditions the protocol defines (Kim et al.'s late warp) end
// to end: its conditions reach the report under their own names, late warp compared with the
// lag it compensates.
TEST(CliDemo, RunsTheLateWarpProtocolWithItsOwnConditions) {
    const std::string out = scratch("kim");
    const auto demo =
        warplab("demo --out " + out + " --participants 2 --player bot --protocols latewarp-kim-quick --jobs 2");
    ASSERT_EQ(demo.status, 0) << demo.output;
    EXPECT_TRUE(contains(demo.output, "2 sessions in " + out + "/results, every outcome replayed")) << demo.output;
    std::ifstream in(fs::path(out) / "report" / "report.json");
    ASSERT_TRUE(in) << demo.output;
    const nlohmann::json report = nlohmann::json::parse(in);
    const auto& rates = report.at("games").at("shooter").at("hit_rates");
    ASSERT_EQ(rates.size(), 2u);
    for (const auto& [participant, conditions] : rates.items())
        for (const char* condition : {"base60", "lag60x5", "lag60x5-rotation", "lag60x5-depth"})
            EXPECT_EQ(conditions.at(condition).at("shots").get<int>(), 4) << participant << " " << condition;
    int lateAgainstLag = 0;
    for (const auto& test : report.at("sign_tests"))
        lateAgainstLag +=
            test.at("b") == "lag60x5" && (test.at("a") == "lag60x5-rotation" || test.at("a") == "lag60x5-depth");
    EXPECT_EQ(lateAgainstLag, 2);
}

// The discrimination task end to end: bots play it, every judgement replays, and the report has
// each session's thresholds and the comparison of the two procedures, though the task has no
// shots and so no hit rates.
TEST(CliDemo, RunsTheDiscriminationTaskToItsThresholds) {
    const std::string out = scratch("jnd");
    const auto demo =
        warplab("demo --out " + out + " --participants 3 --player bot --protocols latency-jnd-quick --jobs 2");
    ASSERT_EQ(demo.status, 0) << demo.output;
    EXPECT_TRUE(contains(demo.output, "3 sessions in " + out + "/results, every outcome replayed")) << demo.output;
    std::ifstream in(fs::path(out) / "report" / "report.json");
    ASSERT_TRUE(in) << demo.output;
    const nlohmann::json report = nlohmann::json::parse(in);
    const auto& discrimination = report.at("discrimination");
    EXPECT_EQ(discrimination.at("rows").size(), 6u) << "three sessions of two procedures";
    EXPECT_FALSE(discrimination.at("comparisons").empty());
    EXPECT_TRUE(fs::exists(fs::path(out) / "report" / "discrimination_lag_frames.png"));
}

TEST(CliDemo, BadInputIsRefusedWithASentenceAndAFailedSessionNamesItsLog) {
    const std::string out = scratch("refused");
    const auto unknown = warplab("demo --out " + out + " --protocols shooter-quick,no-such-protocol");
    EXPECT_EQ(unknown.status, 1) << unknown.output;
    EXPECT_TRUE(contains(unknown.output, "no-such-protocol.json")) << unknown.output;
    EXPECT_TRUE(filesIn(fs::path(out) / "results", ".warplab-session").empty());

    // A population that is no file is refused before any session starts; the bot has none.
    const auto population = warplab("demo --out " + out + " --protocols shooter-quick --population " + out + "/none");
    EXPECT_EQ(population.status, 1) << population.output;
    EXPECT_TRUE(contains(population.output, "population file '" + out + "/none': no such file")) << population.output;
    const auto bot = warplab("demo --out " + out + " --player bot --population " + out + "/none");
    EXPECT_EQ(bot.status, 2) << bot.output;
    EXPECT_TRUE(contains(bot.output, "--population only applies with --player sim")) << bot.output;
    EXPECT_TRUE(filesIn(fs::path(out) / "results", ".warplab-session").empty());

    // A malformed protocol is refused before any session starts, naming its field.
    const fs::path bad = fs::path(out) / "bad.json";
    {
        std::ifstream quick(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json");
        std::string text((std::istreambuf_iterator<char>(quick)), std::istreambuf_iterator<char>());
        text.replace(text.find("\"targets_per_condition\": 4"), 26, "\"targets_per_condition\": -4");
        std::ofstream(bad) << text;
    }
    const auto malformed = warplab("demo --out " + out + " --protocols " + bad.string());
    EXPECT_NE(malformed.status, 0);
    EXPECT_TRUE(contains(malformed.output, "targets_per_condition")) << malformed.output;
    EXPECT_TRUE(filesIn(fs::path(out) / "results", ".warplab-session").empty());

    // A session that cannot run (shaders that do not compile): the demo stops, naming the
    // session and its log, and the log says why.
    const fs::path data = fs::path(out) / "data";
    fs::create_directories(data / "shaders");
    for (const char* dir : {"assets", "protocol", "analysis"})
        fs::create_directory_symlink(fs::path(WARPLAB_SOURCE_DIR) / dir, data / dir);
    for (const auto& entry : fs::directory_iterator(fs::path(WARPLAB_SOURCE_DIR) / "shaders"))
        std::ofstream(data / "shaders" / entry.path().filename()) << "#version 410 core\nthis is not GLSL\n";
    const auto failed =
        warplab("demo --out " + out + "/broken --participants 2 --protocols shooter-quick --jobs 1 --data-dir " +
                data.string());
    EXPECT_EQ(failed.status, 1) << failed.output;
    const std::string log = out + "/broken/logs/sim-1-shooter-quick.log";
    EXPECT_TRUE(
        contains(failed.output, "the session of sim-1, shooter-quick failed (exit status 1); its log is " + log))
        << failed.output;
    EXPECT_TRUE(contains(failed.output, "stopped after 1 of 2 sessions")) << failed.output;
    std::ifstream logFile(log);
    const std::string logText((std::istreambuf_iterator<char>(logFile)), std::istreambuf_iterator<char>());
    EXPECT_TRUE(contains(logText, "error: ")) << logText;
    EXPECT_TRUE(contains(logText, "shaders/")) << logText;

    // A folder that already holds a demo's sessions is not mixed with another.
    const auto again = warplab("demo --out " + out + "/broken --participants 2 --player bot --protocols shooter-quick");
    EXPECT_EQ(again.status, 0) << again.output;  // the broken run left no session behind
    const auto twice = warplab("demo --out " + out + "/broken --participants 2 --player bot --protocols shooter-quick");
    EXPECT_EQ(twice.status, 2) << twice.output;
    EXPECT_TRUE(contains(twice.output, "already holds sessions")) << twice.output;
}

}  // namespace
