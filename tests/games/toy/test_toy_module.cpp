// The toy as its developer works on it: a strict protocol section held to its own page, the
// list a study plan counterbalances, its conditions played in order, and what a participant is
// told -- all from inside its module and through the interfaces every game implements.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "game/registry.h"
#include "plan/study_plan.h"
#include "protocol/documented_keys.h"
#include "protocol/study_protocol.h"
#include "session/session_store.h"
#include "runner/session_runner.h"
#include "toy/toy.h"
#include "toy_protocol.h"

namespace warplab {
namespace {

namespace fs = std::filesystem;

// (The toy is registered once for this executable, in test_toy_game.cpp.)

// The sentence the toy's parser refuses `text` with; "" when it reads.
std::string refusal(const std::string& text) {
    try {
        toy::parseStudy(text, "toy.json");
    } catch (const protocol::ProtocolError& e) {
        return e.what();
    }
    return "";
}

std::string withPlay(const std::string& key, const std::string& valueJson) {
    std::string text = toy::toyProtocol(std::vector<std::string>{"conv60", "conv15"});
    const std::string play = "\"play\": {";
    return text.insert(text.find(play) + play.size(), "\"" + key + "\": " + valueJson + ", ");
}

TEST(ToyProtocol, ReadsStrictlyAndRefusesInOneSentenceNamingTheField) {
    EXPECT_EQ(refusal(toy::toyProtocol(std::vector<std::string>{"conv60", "conv15"})), "");
    EXPECT_EQ(refusal(withPlay("seconds", "3")),
              "protocol 'toy.json': play.seconds is not a known field (play may have conditions, shuffle, "
              "seconds_per_condition)");
    EXPECT_NE(refusal(R"({"format_version": 1, "name": "t", "game": "toy", "play": {"conditions": ["conv7"]}})")
                  .find("play.conditions[0]"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"format_version": 1, "name": "t", "game": "toy", "play": {"seconds_per_condition": 0}})")
                  .find("play.seconds_per_condition"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"format_version": 2, "name": "t", "game": "toy"})").find("format_version"),
              std::string::npos);
}

TEST(ToyProtocol, ItsCanonicalCopyReadsBackTheSame) {
    const auto study =
        toy::parseStudy(toy::toyProtocol(std::vector<std::string>{"warp15to120", "conv15"}, 2.5, true), "toy.json");
    const auto again = toy::parseStudy(study->protocolJson(), "copy.json");
    EXPECT_EQ(again->protocolJson(), study->protocolJson());
    EXPECT_EQ(again->conditionNames(), (std::vector<std::string>{"warp15to120", "conv15"}));
}

// Its page is the contract: it documents exactly the keys the parser's tables read, in order.
TEST(ToyProtocol, EveryKeyIsDocumentedOnItsPageInOrder) {
    const std::string page = std::string(WARPLAB_SOURCE_DIR) + "/tests/games/toy/README.md";
    EXPECT_EQ(protocol::documentedKeys(page, "# The toy protocol"), toy::toyProtocolKeys());
    EXPECT_FALSE(toy::toyProtocolKeys().empty());
}

TEST(ToyStudy, SaysWhatAParticipantIsTold) {
    const game::Instructions told = toy::parseStudy(toy::toyProtocol("conv60"), "toy.json")->instructions();
    EXPECT_EQ(told.pointer, game::PointerKind::Reticle);
    EXPECT_EQ(told.radiansPerCount, 0.0) << "the mouse does not turn the view";
    EXPECT_EQ(told.targets, game::Instructions::Targets::All);
    EXPECT_EQ(told.task, "Click while the sphere is under the reticle.");
}

std::vector<std::string> conditionsPlayed(const std::string& protocolText, const std::string& dirName,
                                          std::uint64_t seed) {
    const fs::path dir = fs::path(testing::TempDir()) / dirName;
    fs::remove_all(dir);
    fs::create_directories(dir / "results");
    std::ofstream(dir / "toy.json") << protocolText;
    runner::HeadlessRun run;
    run.protocolPath = (dir / "toy.json").string();
    run.participant = "toy-bot";
    run.resultsDir = (dir / "results").string();
    run.player = "bot";
    run.seed = seed;
    std::ostringstream progress;
    const session::SessionData data = session::readSession(runner::runHeadless(run, progress));
    std::vector<std::string> conditions;
    for (const auto& frame : data.frames)
        if (conditions.empty() || conditions.back() != frame.condition) conditions.push_back(frame.condition);
    return conditions;
}

TEST(ToyGame, PlaysItsConditionsInTheListedOrderOrTheSeeds) {
    EXPECT_EQ(conditionsPlayed(toy::toyProtocol(std::vector<std::string>{"conv15", "conv60", "warp15to120"}, 0.5),
                               "toy-order", 1),
              (std::vector<std::string>{"conv15", "conv60", "warp15to120"}));
    // Shuffled: each seed's own order, every condition once; some seed moves the first.
    const std::string shuffled =
        toy::toyProtocol(std::vector<std::string>{"conv15", "conv60", "warp15to120"}, 0.25, true);
    bool moved = false;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const auto conditions = conditionsPlayed(shuffled, "toy-shuffled-" + std::to_string(seed), seed);
        EXPECT_EQ(conditions, conditionsPlayed(shuffled, "toy-shuffled-again", seed));
        auto sorted = conditions;
        std::sort(sorted.begin(), sorted.end());
        EXPECT_EQ(sorted, (std::vector<std::string>{"conv15", "conv60", "warp15to120"}));
        moved = moved || conditions.front() != "conv15";
    }
    EXPECT_TRUE(moved);
}

// A study plan counterbalances the toy's play.conditions without knowing its name: the Study
// says which list, and writes each participant's order into the copy they run.
TEST(ToyStudy, AStudyPlanCounterbalancesItsConditions) {
    const fs::path dir = fs::path(testing::TempDir()) / "toy-plan";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path protocolPath = fs::path(testing::TempDir()) / "toy-plan.json";
    std::ofstream(protocolPath) << toy::toyProtocol(std::vector<std::string>{"conv15", "conv60", "warp15to120"});
    const plan::StudyPlan made = plan::makePlan(dir.string(), {protocolPath.string()}, 6, {}, 7);
    plan::writePlan(dir.string(), made);
    const plan::StudyPlan read = plan::readPlan(dir.string());
    ASSERT_EQ(read.protocols.size(), 1u);
    EXPECT_EQ(read.protocols[0].game, "toy");
    EXPECT_EQ(read.protocols[0].conditions, (std::vector<std::string>{"conv15", "conv60", "warp15to120"}));
    EXPECT_TRUE(read.protocols[0].blocked);
    std::set<std::vector<std::string>> orders;
    for (const plan::ParticipantPlan& p : read.participants) {
        const std::string text = plan::participantProtocolJson(dir.string(), read, p, 0);
        EXPECT_EQ(game::parseStudy(text, "participant.json")->conditionNames(), p.conditionOrder[0]) << p.id;
        orders.insert(p.conditionOrder[0]);
    }
    EXPECT_EQ(orders.size(), 6u) << "a balanced Latin square of three conditions has six rows";
}

}  // namespace
}  // namespace warplab
