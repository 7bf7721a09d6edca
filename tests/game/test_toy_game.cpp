// The seam a game plugs into, proved by a game the application has never heard of: the toy
// (tests/game/toy_game.*) registers itself and then runs headless, replays bit for bit and
// exports, through the same runner, replay and export as the shooter and the click game.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "export/export.h"
#include "study/session_runner.h"
#include "game/registry.h"
#include "game/toy_game.h"

namespace warplab {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

class ToyGame : public ::testing::TestWithParam<const char*> {};

TEST_P(ToyGame, RunsReplaysAndExportsThroughTheStudyInterfaceAlone) {
    game::toy::registerToyGame();
    const std::string mode = GetParam();
    const fs::path dir = fs::path(testing::TempDir()) / ("warplab-toy-" + mode);
    fs::remove_all(dir);
    fs::create_directories(dir / "results");
    const fs::path protocolPath = dir / "toy.json";
    std::ofstream(protocolPath) << game::toy::toyProtocol(mode);

    study::HeadlessRun run;
    run.protocolPath = protocolPath.string();
    run.participant = "toy-bot";
    run.resultsDir = (dir / "results").string();
    run.player = "bot";
    std::ostringstream progress;
    const std::string session = study::runHeadless(run, progress);

    const study::ReplayResult replayed = study::replaySession(session);
    EXPECT_EQ(replayed.difference, "");
    EXPECT_TRUE(replayed.completed);
    EXPECT_FALSE(replayed.damaged);
    EXPECT_GE(replayed.outcomes, 3u) << "the bot clicks a few times";
    EXPECT_EQ(replayed.reproduced, replayed.outcomes);
    EXPECT_EQ(study::replayExitCode(replayed), study::kReplayReproduced);

    std::ostringstream log;
    const exporter::ExportSummary summary = exporter::exportResults(run.resultsDir, (dir / "csv").string(), {}, log);
    ASSERT_EQ(summary.sessions.size(), 1u);
    EXPECT_TRUE(summary.sessions[0].included) << summary.sessions[0].why;
    const std::string shots = readAll(dir / "csv" / "shots.csv");
    EXPECT_NE(shots.find(",toy,"), std::string::npos) << shots;
    EXPECT_NE(shots.find(mode), std::string::npos) << shots;
    const std::string rates = readAll(dir / "csv" / "hitrates.csv");
    EXPECT_NE(rates.find("toy-bot,toy," + mode + ","), std::string::npos) << rates;
    // What its hit rate counts, in its own words, for the report.
    const std::string games = readAll(dir / "csv" / "games.csv");
    EXPECT_EQ(games, "game,hits_are,shots_are\ntoy,toy hits,clicks\n");
}

// Held, warped and interpolated frames: each way a condition shows the world.
INSTANTIATE_TEST_SUITE_P(Modes, ToyGame, ::testing::Values("conv15", "warp15to120", "bireproj15to60"));

TEST(Registry, AGameRegisteredAtRunTimeIsKnownAfterTheBuiltInOnes) {
    game::toy::registerToyGame();
    const auto names = game::gameNames();
    ASSERT_GE(names.size(), 3u);
    EXPECT_EQ(names[0], "shooter");
    EXPECT_EQ(names[1], "click");
    EXPECT_NE(std::find(names.begin(), names.end(), "toy"), names.end());
    EXPECT_THROW(
        game::registerGame(
            "click", [](const std::string&, const std::string&) -> std::unique_ptr<game::Study> { return nullptr; }),
        std::invalid_argument);
    EXPECT_EQ(game::parseStudy(game::toy::toyProtocol("conv60"), "toy.json")->game(), "toy");
}

}  // namespace
}  // namespace warplab
