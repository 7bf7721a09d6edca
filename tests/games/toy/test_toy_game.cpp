// The seam a game plugs into, proved by a game the application has never heard of: the toy
// (tests/games/toy/, a module of its own) is registered by one line and then runs headless,
// replays bit for bit and exports, through the same runner, replay and export as the shooter
// and the click game.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "export/documented_columns.h"
#include "export/export.h"
#include "export/export_test_support.h"
#include "runner/session_runner.h"
#include "game/registry.h"
#include "session/records.h"
#include "session/session_store.h"
#include "support/cut_session.h"
#include "toy/toy.h"

namespace warplab {
namespace {

namespace fs = std::filesystem;

// The toy's one registration line, after the built-in games (as a lab's own task would add it).
class RegisterTheToy : public ::testing::Environment {
    void SetUp() override { game::registerGame(toy::kGameName, toy::parseStudy, toy::exports()); }
};
[[maybe_unused]] const auto* const registered = ::testing::AddGlobalTestEnvironment(new RegisterTheToy);

std::string readAll(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

class ToyGame : public ::testing::TestWithParam<const char*> {};

TEST_P(ToyGame, RunsReplaysAndExportsThroughTheStudyInterfaceAlone) {
    const std::string condition = GetParam();
    const fs::path dir = fs::path(testing::TempDir()) / ("warplab-toy-" + condition);
    fs::remove_all(dir);
    fs::create_directories(dir / "results");
    const fs::path protocolPath = dir / "toy.json";
    std::ofstream(protocolPath) << toy::toyProtocol(condition);

    runner::HeadlessRun run;
    run.protocolPath = protocolPath.string();
    run.participant = "toy-bot";
    run.resultsDir = (dir / "results").string();
    run.player = "bot";
    std::ostringstream progress;
    const std::string session = runner::runHeadless(run, progress);

    const runner::ReplayResult replayed = runner::replaySession(session);
    EXPECT_EQ(replayed.difference, "");
    EXPECT_TRUE(replayed.completed);
    EXPECT_FALSE(replayed.damaged);
    EXPECT_GE(replayed.outcomes, 3u) << "the bot clicks a few times";
    EXPECT_EQ(replayed.reproduced, replayed.outcomes);
    EXPECT_EQ(runner::replayExitCode(replayed), runner::kReplayReproduced);

    // What the bot typed is in the input record, and the session replays from it (the clicks'
    // `typed` above); played back as a player, it is recorded again as it was.
    const session::SessionData recorded = session::readSession(session);
    const auto typing = std::count_if(recorded.inputs.begin(), recorded.inputs.end(),
                                      [](const session::InputRecord& in) { return !in.text.empty(); });
    EXPECT_GT(typing, 10);
    runner::HeadlessRun again = run;
    again.player = "replay:" + session;
    again.resultsDir = (dir / "again").string();
    fs::create_directories(again.resultsDir);
    const session::SessionData replayedRun = session::readSession(runner::runHeadless(again, progress));
    ASSERT_EQ(replayedRun.inputs.size(), recorded.inputs.size());
    for (std::size_t i = 0; i < recorded.inputs.size(); ++i)
        ASSERT_EQ(session::firstDifference(recorded.inputs[i], replayedRun.inputs[i]), "") << "input " << i;
    ASSERT_EQ(replayedRun.events.size(), recorded.events.size());
    for (std::size_t i = 0; i < recorded.events.size(); ++i)
        ASSERT_EQ(session::firstDifference(recorded.events[i], replayedRun.events[i]), "") << "event " << i;

    std::ostringstream log;
    const exporter::ExportSummary summary = exporter::exportResults(run.resultsDir, (dir / "csv").string(), {}, log);
    ASSERT_EQ(summary.sessions.size(), 1u);
    EXPECT_TRUE(summary.sessions[0].included) << summary.sessions[0].why;
    const std::string shots = readAll(dir / "csv" / "shots.csv");
    EXPECT_NE(shots.find(",toy,"), std::string::npos) << shots;
    EXPECT_NE(shots.find(condition), std::string::npos) << shots;
    const std::string rates = readAll(dir / "csv" / "hitrates.csv");
    EXPECT_NE(rates.find("toy-bot,toy," + condition + ","), std::string::npos) << rates;
    // What its hit rate counts, in its own words, for the report.
    const std::string games = readAll(dir / "csv" / "games.csv");
    EXPECT_EQ(games, "game,hits_are,shots_are,tables\ntoy,toy hits,clicks,toy_clicks.csv\n");
    // Its own table, one row per click, in the layout export gives a game's own tables; and the
    // other games' own tables, header only.
    const std::string clicks = readAll(dir / "csv" / "toy_clicks.csv");
    EXPECT_EQ(
        clicks.substr(0, clicks.find('\n')),
        "participant,session,click,condition,shown_x_m,true_x_m,shown_offset_m,typed,player_kind,condition_position");
    EXPECT_EQ(std::count(clicks.begin(), clicks.end(), '\n'), std::count(shots.begin(), shots.end(), '\n'));
    EXPECT_NE(clicks.find("toy-bot," + fs::path(session).filename().string() + ",0," + condition + ","),
              std::string::npos)
        << clicks;
    const std::string matches = readAll(dir / "csv" / "matches.csv");
    EXPECT_EQ(std::count(matches.begin(), matches.end(), '\n'), 1) << matches;

    // Its own column of shots.csv after the other games', filled in its rows (the offset its
    // table has too) and the other games' columns empty there.
    EXPECT_NE(shots.find(",aim_time_s,angular_error_deg,difficulty,target_speed,error_px,toy_offset_m,skipped_frames,"),
              std::string::npos)
        << shots.substr(0, shots.find('\n'));
    const auto shotRows = app::exporttest::readCsv((dir / "csv" / "shots.csv").string());
    const auto clickRows = app::exporttest::readCsv((dir / "csv" / "toy_clicks.csv").string());
    ASSERT_EQ(shotRows.size(), clickRows.size());
    ASSERT_GE(shotRows.size(), 3u);
    for (std::size_t i = 0; i < shotRows.size(); ++i) {
        EXPECT_EQ(shotRows[i].at("toy_offset_m"), clickRows[i].at("shown_offset_m")) << "click " << i;
        EXPECT_FALSE(shotRows[i].at("toy_offset_m").empty()) << "click " << i;
        for (const char* other : {"angular_error_deg", "difficulty", "target_speed", "error_px"})
            EXPECT_EQ(shotRows[i].at(other), "") << other;
    }
}

// The toy's own table is documented on its page, column for column, as export writes it.
TEST(ToyModule, ItsOwnTableMatchesItsPage) {
    const std::vector<game::GameTable> own = toy::tables();
    ASSERT_EQ(own.size(), 1u);
    const exporter::CsvColumns written = exporter::gameTableColumns(own.front());
    const std::vector<std::string> pages = testing_docs::pagesDocumenting(written.file);
    ASSERT_EQ(pages.size(), 1u);
    EXPECT_EQ(fs::path(pages.front()).parent_path().filename(), "toy");
    const testing_docs::DocumentedColumns documented = testing_docs::documentedColumns(written.file, pages.front());
    EXPECT_EQ(documented.columns, written.columns);
    EXPECT_EQ(documented.numbered, written.numbered);
    // And its own column of shots.csv.
    EXPECT_EQ(testing_docs::documentedColumns("shots.csv", pages.front()).columns, toy::exports().shotColumns);
    EXPECT_FALSE(toy::exports().shotColumns.empty());
}

// Held, warped and interpolated frames: each way a condition shows the world.
INSTANTIATE_TEST_SUITE_P(Conditions, ToyGame, ::testing::Values("conv15", "warp15to120", "bireproj15to60"));

// A session interrupted after a click and resumed carries on from what was typed before the
// interruption: its kept frames are played again with their text, so the clicks after it
// report the uninterrupted session's `typed`, and the whole is that session, row for row.
TEST(ToyGameResume, AResumedSessionIsTheUninterruptedOneTypingIncluded) {
    const fs::path dir = fs::path(testing::TempDir()) / "warplab-toy-resume";
    fs::remove_all(dir);
    for (const char* folder : {"whole", "cut", "resumed"}) fs::create_directories(dir / folder);
    std::ofstream(dir / "toy.json") << toy::toyProtocol("conv15");

    runner::HeadlessRun run;
    run.protocolPath = (dir / "toy.json").string();
    run.participant = "toy-bot";
    run.resultsDir = (dir / "whole").string();
    run.player = "bot";
    std::ostringstream progress;
    const session::SessionData whole = session::readSession(runner::runHeadless(run, progress));
    ASSERT_TRUE(whole.completed);

    // Cut after its second click, as a kill just after that click's commit leaves it.
    std::size_t kept = 0;
    for (int clicks = 0; kept < whole.events.size() && clicks < 2; ++kept) clicks += whole.events[kept].type == "click";
    ASSERT_LT(kept, whole.events.size()) << "the bot clicks more than twice";
    const std::int64_t lastFrame = whole.events[kept - 1].frame;
    const std::string cut = testing_sessions::cutSession(whole, kept, (dir / "cut").string());

    runner::HeadlessRun resume = run;
    resume.resumeFrom = cut;
    resume.resultsDir = (dir / "resumed").string();
    const session::SessionData resumed = session::readSession(runner::runHeadless(resume, progress));
    EXPECT_TRUE(resumed.completed);
    ASSERT_EQ(resumed.header.resumed.size(), 1u);
    EXPECT_EQ(resumed.header.resumed[0].frame, lastFrame + 1);
    ASSERT_EQ(resumed.inputs.size(), whole.inputs.size());
    for (std::size_t i = 0; i < whole.inputs.size(); ++i)
        ASSERT_EQ(session::firstDifference(whole.inputs[i], resumed.inputs[i]), "") << "input " << i;
    ASSERT_EQ(resumed.frames.size(), whole.frames.size());
    for (std::size_t i = 0; i < whole.frames.size(); ++i)
        ASSERT_EQ(session::firstDifference(whole.frames[i], resumed.frames[i]), "") << "frame " << i;
    ASSERT_EQ(resumed.events.size(), whole.events.size());
    for (std::size_t i = 0; i < whole.events.size(); ++i)
        ASSERT_EQ(session::firstDifference(whole.events[i], resumed.events[i]), "") << "event " << i;
}

TEST(Registry, AGameRegisteredAtRunTimeIsKnownAfterTheBuiltInOnes) {
    const auto names = game::gameNames();
    ASSERT_GE(names.size(), 3u);
    EXPECT_EQ(names[0], "shooter");
    EXPECT_EQ(names[1], "click");
    EXPECT_NE(std::find(names.begin(), names.end(), "toy"), names.end());
    EXPECT_THROW(
        game::registerGame(
            "click", [](const std::string&, const std::string&) -> std::unique_ptr<game::Study> { return nullptr; }),
        std::invalid_argument);
    EXPECT_EQ(game::parseStudy(toy::toyProtocol("conv60"), "toy.json")->game(), "toy");
    // One file, one game: a second game naming the toy's table is refused, and not registered;
    // so is one naming a column of shots.csv that is the toy's, or its own twice.
    EXPECT_THROW(game::registerGame("toy-copy", toy::parseStudy, {{}, toy::tables}), std::invalid_argument);
    EXPECT_THROW(game::registerGame("toy-copy", toy::parseStudy, {toy::exports().shotColumns, nullptr}),
                 std::invalid_argument);
    EXPECT_THROW(game::registerGame("toy-copy", toy::parseStudy, {{"copy_m", "copy_m"}, nullptr}),
                 std::invalid_argument);
    const auto after = game::gameNames();
    EXPECT_EQ(std::find(after.begin(), after.end(), "toy-copy"), after.end());
    std::size_t toyClicks = 0;
    for (const auto& [owner, table] : game::gameTables()) toyClicks += table.file == "toy_clicks.csv";
    EXPECT_EQ(toyClicks, 1u);
}

}  // namespace
}  // namespace warplab
