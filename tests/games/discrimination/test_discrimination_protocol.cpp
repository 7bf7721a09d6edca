// The discrimination task's protocol section: the shipped protocols, the canonical copy, the
// page that documents every key, and each kind of bad input refused in one sentence naming its
// JSON path.
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "discrimination/discrimination_protocol.h"
#include "protocol/documented_keys.h"
#include "protocol/study_protocol.h"

namespace warplab::discrimination {
namespace {

using Json = nlohmann::json;

std::string readAll(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string shipped(const std::string& name) {
    return readAll(std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name + ".json");
}

// The smallest valid protocol: one QUEST+ procedure over added lag at 120 Hz.
Json minimal() {
    return Json::parse(R"({
      "format_version": 1, "name": "jnd", "game": "discrimination",
      "trials": {"procedures": [{"name": "lag", "reference": "conv120", "levels": [1, 2, 4, 8],
                                 "thresholds": [1, 2, 4, 8], "slopes": [2, 4], "max_trials": 10}]}
    })");
}

std::string refusal(const Json& document) {
    try {
        parseDiscriminationProtocol(document.dump(), "jnd.json");
    } catch (const protocol::ProtocolError& e) {
        return e.what();
    }
    return "";
}

TEST(DiscriminationProtocol, TheShippedProtocolsParseAndRoundTrip) {
    for (const char* name : {"latency-jnd", "latency-jnd-quick", "latency-jnd-demo"}) {
        SCOPED_TRACE(name);
        const DiscriminationProtocol p = parseDiscriminationProtocol(shipped(name), name);
        ASSERT_EQ(p.procedures.size(), 2u);
        EXPECT_EQ(p.procedures[0].reference, "conv120");
        EXPECT_EQ(p.procedures[1].reference, "latewarp120");
        EXPECT_EQ(p.conditionTable.at("latewarp120").lateWarp, condition::LateWarp::Rotation);
        // The canonical copy a session stores parses back to the same text.
        const std::string copy = toJson(p);
        EXPECT_EQ(toJson(parseDiscriminationProtocol(copy, "copy")), copy);
    }
}

TEST(DiscriminationProtocol, EveryKeyIsDocumentedOnItsPageInOrder) {
    const std::string page = std::string(WARPLAB_SOURCE_DIR) + "/docs/discrimination-study.md";
    EXPECT_EQ(protocol::documentedKeys(page, "# The discrimination protocol"), discriminationProtocolKeys());
    EXPECT_GT(discriminationProtocolKeys().size(), 20u);
}

TEST(DiscriminationProtocol, StimuliAreHowMuchWorseTheTestIsThanTheReference) {
    Json d = minimal();
    d["trials"]["procedures"][0] = {{"name", "rate"},          {"reference", "conv120"}, {"dimension", "render_hz"},
                                    {"levels", {100, 60, 30}}, {"method", "staircase"},  {"max_trials", 20}};
    const DiscriminationProtocol p = parseDiscriminationProtocol(d.dump(), "jnd.json");
    EXPECT_EQ(stimuli(p, p.procedures[0]), (std::vector<double>{20, 60, 90}));
    EXPECT_EQ(testCondition(p, p.procedures[0], 2).name, "conv120@render_hz=30");
    const adaptive::ProcedureSettings s = procedureSettings(p, p.procedures[0]);
    EXPECT_EQ(s.staircase.start, 2u) << "a staircase starts at the easiest level unless told";
}

struct BadInput {
    const char* what;
    std::function<void(Json&)> change;
    const char* message;  // a part of the one sentence
};

class DiscriminationRefusal : public ::testing::TestWithParam<BadInput> {};

TEST_P(DiscriminationRefusal, SaysWhereAndWhatIsAllowed) {
    Json d = minimal();
    GetParam().change(d);
    const std::string message = refusal(d);
    EXPECT_NE(message.find(GetParam().message), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one sentence: " << message;
}

Json& first(Json& d) { return d["trials"]["procedures"][0]; }

INSTANTIATE_TEST_SUITE_P(
    BadInputs, DiscriminationRefusal,
    ::testing::Values(
        BadInput{"no procedures", [](Json& d) { d["trials"].erase("procedures"); }, "trials.procedures"},
        BadInput{"a dimension that is no condition part", [](Json& d) { first(d)["dimension"] = "fill"; },
                 "trials.procedures[0].dimension"},
        BadInput{"a lag that is not whole frames",
                 [](Json& d) {
                     first(d)["levels"] = {1, 2.5, 4};
                 },
                 "trials.procedures[0].levels[1]"},
        BadInput{"a rate above the refresh",
                 [](Json& d) {
                     first(d) = {{"name", "rate"},
                                 {"reference", "conv15"},
                                 {"dimension", "render_hz"},
                                 {"method", "constant_stimuli"},
                                 {"levels", {240}}};
                 },
                 "trials.procedures[0].levels[0]"},
        BadInput{"a level no worse than the reference",
                 [](Json& d) {
                     first(d)["levels"] = {0, 1, 2};
                 },
                 "must be worse than the reference conv120's lag_frames of 0 (higher)"},
        BadInput{"levels out of order",
                 [](Json& d) {
                     first(d)["levels"] = {1, 4, 2};
                 },
                 "trials.procedures[0].levels[2]"},
        BadInput{"a grid that does not rise",
                 [](Json& d) {
                     first(d)["thresholds"] = {1, 4, 2};
                 },
                 "trials.procedures[0].thresholds[2]"},
        BadInput{"a log grid at 0",
                 [](Json& d) {
                     first(d)["thresholds"] = {0, 1, 2};
                 },
                 "trials.procedures[0].thresholds[0]"},
        BadInput{"a lapse out of range", [](Json& d) { first(d)["lapses"] = {0.6}; }, "trials.procedures[0].lapses[0]"},
        BadInput{"a prior of the wrong size",
                 [](Json& d) {
                     first(d)["prior"] = {1, 2, 3};
                 },
                 "trials.procedures[0].prior"},
        BadInput{"a prior of no weight", [](Json& d) { first(d)["prior"] = std::vector<double>(8, 0.0); },
                 "trials.procedures[0].prior"},
        BadInput{"a percent correct the function never reaches",
                 [](Json& d) {
                     first(d)["lapses"] = {0.3};
                     first(d)["percent_correct"] = 75;
                 },
                 "trials.procedures[0].percent_correct"},
        BadInput{"a stopping rule that can never stop", [](Json& d) { first(d).erase("max_trials"); },
                 "trials.procedures[0].max_trials"},
        BadInput{"a quest_plus without its grids", [](Json& d) { first(d).erase("slopes"); },
                 "trials.procedures[0].slopes"},
        BadInput{"a key another method reads", [](Json& d) { first(d)["repeats"] = 5; },
                 "is only for method \"constant_stimuli\""},
        BadInput{"a staircase start that is no level",
                 [](Json& d) {
                     first(d) = {
                         {"name", "s"}, {"reference", "conv120"}, {"method", "staircase"}, {"levels", {1, 2, 4}},
                         {"start", 3},  {"max_trials", 10}};
                 },
                 "trials.procedures[0].start"},
        BadInput{"two procedures of one name", [](Json& d) { d["trials"]["procedures"].push_back(first(d)); },
                 "trials.procedures[1].name"},
        BadInput{"an unknown reference", [](Json& d) { first(d)["reference"] = "conv999"; },
                 "trials.procedures[0].reference"},
        BadInput{"an unknown key", [](Json& d) { first(d)["treshold"] = 1; }, "treshold"}),
    [](const ::testing::TestParamInfo<BadInput>& info) {
        std::string name = info.param.what;
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

}  // namespace
}  // namespace warplab::discrimination
