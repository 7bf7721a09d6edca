// `warplab run --headless --player sim[:SEED]`: the perceptual simulated participant plays a
// whole protocol through the command line, and the session replays from its input log alone.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cli/cli_support.h"
#include "participants/population.h"
#include "session/session_store.h"

namespace {

using warplab::testing::contains;
using warplab::testing::sessionIn;
using warplab::testing::warplab;

std::string scratch(const std::string& name) { return warplab::testing::scratch("cli-sim", name); }

std::string protocol(const std::string& name) {
    return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name + ".json";
}

TEST(CliSimulatedParticipant, PlaysShooterQuickToTheEndAndTheSessionReplays) {
    const std::string dir = scratch("shooter");
    const auto run = warplab("run --seed 1 --protocol " + protocol("shooter-quick") + " --participant S1 --out " + dir +
                             " --headless --player sim:1");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string session = sessionIn(dir);
    ASSERT_FALSE(session.empty()) << run.output;
    const auto data = warplab::session::readSession(session);
    EXPECT_TRUE(data.completed);
    EXPECT_EQ(data.header.player, "sim:1");
    // Its traits, drawn from its seed out of the shipped population, are in the header.
    const auto population = warplab::participants::readPopulation(
        warplab::participants::populationPath(std::string(WARPLAB_SOURCE_DIR) + "/assets"));
    EXPECT_EQ(data.header.playerModel,
              warplab::participants::participantJson(warplab::participants::drawParticipant(population, 1)));
    // The header says which GL drew its percepts: the input log is reproducible on that one.
    EXPECT_TRUE(contains(data.header.glRenderer, "simulated participant")) << data.header.glRenderer;
    int testTrials = 0;
    for (const auto& e : data.events) testTrials += e.phase == "test" && (e.type == "shot" || e.type == "timeout");
    EXPECT_EQ(testTrials, 12);

    const auto replay = warplab("replay " + session);
    EXPECT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "outcomes reproduced")) << replay.output;

    // Byte-identical input logs from the same seeds: tests/gl/test_simulated_participant.cpp
    // (TheSameSeedGivesTheSameInputsAndAnotherSeedOthers), in-process and cheaper.
}

TEST(CliSimulatedParticipant, PlaysClickQuickToTheEndAndTheSessionReplays) {
    const std::string dir = scratch("click");
    const auto run = warplab("run --seed 1 --protocol " + protocol("click-quick") + " --participant S1 --out " + dir +
                             " --headless --player sim:2");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string session = sessionIn(dir);
    ASSERT_FALSE(session.empty()) << run.output;
    const auto data = warplab::session::readSession(session);
    EXPECT_TRUE(data.completed);
    int matches = 0, ratings = 0, clicks = 0;
    for (const auto& e : data.events) {
        matches += e.type == "match";
        ratings += e.type == "rating";
        clicks += e.type == "click";
    }
    EXPECT_EQ(matches, 14);
    EXPECT_EQ(ratings, 56);
    EXPECT_GT(clicks, 14);
    const auto replay = warplab("replay " + session);
    EXPECT_EQ(replay.status, 0) << replay.output;
}

TEST(CliSimulatedParticipant, WrongUsesAreRefusedWithASentence) {
    const std::string dir = scratch("refused");
    const auto seed = warplab("run --seed 1 --protocol " + protocol("shooter-quick") + " --participant S1 --out " +
                              dir + " --headless --player sim:x");
    EXPECT_NE(seed.status, 0);
    EXPECT_TRUE(contains(seed.output, "sim:SEED needs a whole number")) << seed.output;
    const auto gl = warplab("run --seed 1 --protocol " + protocol("shooter-quick") + " --participant S1 --out " + dir +
                            " --headless --player bot --gl egl");
    EXPECT_NE(gl.status, 0);
    EXPECT_TRUE(contains(gl.output, "--gl only applies with --headless --player sim")) << gl.output;
    const auto window = warplab("run --seed 1 --protocol " + protocol("shooter-quick") + " --participant S1 --out " +
                                dir + " --player sim");
    EXPECT_EQ(window.status, 2);
    EXPECT_TRUE(contains(window.output, "runs headless only")) << window.output;
    EXPECT_TRUE(sessionIn(dir).empty());
    // A population file that is not one: one sentence naming the file and the field, exit 1.
    const std::string bad = dir + "/population.json";
    std::ofstream(bad) << R"({"traits": {"reaction_s": {"median": 7, "spread": 0.1}}})";
    const auto population = warplab("run --seed 1 --protocol " + protocol("shooter-quick") +
                                    " --participant S1 --out " + dir + " --headless --player sim --population " + bad);
    EXPECT_EQ(population.status, 1);
    EXPECT_TRUE(
        contains(population.output,
                 "population file '" + bad + "': traits.reaction_s.median must be a number between 0.1 and 0.5, got 7"))
        << population.output;
    const auto forBot = warplab("run --seed 1 --protocol " + protocol("shooter-quick") + " --participant S1 --out " +
                                dir + " --headless --player bot --population " + bad);
    EXPECT_EQ(forBot.status, 2);
    EXPECT_TRUE(contains(forBot.output, "--population only applies with --headless --player sim")) << forBot.output;
    EXPECT_TRUE(sessionIn(dir).empty());
}

}  // namespace
