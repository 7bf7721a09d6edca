// A condition's pacing in a protocol: frame_time_jitter and hitches read, written back and
// refused in older formats and out of range naming their path; render rates the refresh does
// not divide accepted; and every shipped protocol's conditions on the schedules they had.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "condition/reference_schedule.h"
#include "game/registry.h"
#include "click/click_protocol.h"
#include "shooter/shooter_protocol.h"

namespace warplab::protocol {
namespace {

using Json = nlohmann::ordered_json;

// Every protocol shipped in protocol/, each condition it can name at its refresh, frame by
// frame against the schedule as it was before pacing (tests/condition/reference_schedule.h):
// their sessions replay unchanged.
TEST(ProtocolPacing, EveryShippedProtocolKeepsItsSchedules) {
    int protocols = 0, conditions = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(WARPLAB_SOURCE_DIR) + "/protocol")) {
        if (entry.path().extension() != ".json") continue;
        std::ifstream in(entry.path());
        std::stringstream text;
        text << in.rdbuf();
        // Whichever game: the shared loader picks the parser, and its Study has the conditions.
        const auto study = game::parseStudy(text.str(), entry.path().string());
        const condition::ConditionTable& table = study->conditions();
        const double refresh = study->refreshHz();
        ++protocols;
        for (const std::string& name : table.names()) {
            if (!table.check(name, refresh).empty()) continue;
            const condition::Condition& c = table.at(name);
            if (!condition::wholeRatio(refresh, c.renderHz)) continue;  // refused before: no session has it
            EXPECT_EQ(condition::reference::firstDifference(c, refresh, -2500, 30000), "") << entry.path();
            ++conditions;
        }
    }
    EXPECT_GE(protocols, 10);
    EXPECT_GE(conditions, 40);
}

Json paced(int formatVersion) {
    return Json::parse(R"({
      "format_version": )" +
                       std::to_string(formatVersion) + R"(, "name": "paced", "game": "shooter",
      "display": {"refresh_hz": 144},
      "conditions": {
        "even60": {"render_hz": 60},
        "jitter4": {"render_hz": 60, "frame_time_jitter": {"distribution": "normal", "sd_ms": 4}},
        "jitter12": {"render_hz": 60, "frame_time_jitter": {"distribution": "lognormal", "sd_ms": 12}},
        "wobble": {"render_hz": 60, "frame_time_jitter": {"distribution": "uniform", "range_ms": 8}},
        "hitch": {"render_hz": 60, "hitches": {"ms": 100, "every_s": 2}},
        "rare": {"render_hz": 90, "fill": "warp-sparse8", "hitches": {"ms": 50, "rate_per_s": 0.25}}
      },
      "acclimation": {"mode": "even60"},
      "training": {"high_mode": "even60", "low_mode": "hitch"},
      "test": {"conditions": ["even60", "jitter4", "jitter12", "wobble", "hitch", "rare"]}
    })");
}

std::string errorOf(const Json& document) {
    try {
        parseShooterProtocol(document.dump(), "p.json");
    } catch (const ProtocolError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        return message;
    }
    return "";
}

TEST(ProtocolPacing, JitterAndHitchesReadAndWriteBack) {
    const ShooterProtocol p = parseShooterProtocol(paced(8).dump(), "p.json");
    EXPECT_EQ(p.conditionTable.at("jitter12").jitter.shape, condition::JitterShape::Lognormal);
    EXPECT_EQ(p.conditionTable.at("jitter12").jitter.sdMs, 12);
    EXPECT_EQ(p.conditionTable.at("wobble").jitter.rangeMs, 8);
    EXPECT_EQ(p.conditionTable.at("hitch").hitches.everyS, 2);
    EXPECT_EQ(p.conditionTable.at("rare").hitches.ratePerS, 0.25);
    EXPECT_TRUE(parseShooterProtocol(toJson(p), "copy").conditionTable == p.conditionTable);
    // On a 144 Hz display every preset whose rates the refresh does not divide runs too (the
    // lag presets' lags are not whole frames there).
    Json presets = paced(8);
    for (const char* preset : {"conv15", "conv30", "conv60", "conv120", "warp15to120", "bireproj15to60"})
        presets["test"]["conditions"].push_back(preset);
    EXPECT_EQ(errorOf(presets), "");
}

TEST(ProtocolPacing, BadPacingNamesItsPath) {
    EXPECT_EQ(errorOf(paced(7)),
              "protocol 'p.json': conditions.jitter4.frame_time_jitter is new in format_version 8, but this file is "
              "format_version 7");
    struct Case {
        const char* pointer;
        Json value;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {"/conditions/jitter4/frame_time_jitter/sd_ms", 7,
         "conditions.jitter4.frame_time_jitter.sd_ms is 7 ms; a normal jitter's SD must be above 0 and at most a "
         "third of the mean render interval (16.6667 ms at render_hz 60), so intervals stay positive "
         "(\"lognormal\" allows wider)"},
        {"/conditions/jitter4/frame_time_jitter/sd_ms", -1,
         "conditions.jitter4.frame_time_jitter.sd_ms must be a number greater than 0 and at most 10000, got -1"},
        {"/conditions/jitter4/frame_time_jitter/distribution", "gamma",
         "conditions.jitter4.frame_time_jitter.distribution must be \"normal\", \"lognormal\" or \"uniform\", got "
         "string \"gamma\""},
        {"/conditions/wobble/frame_time_jitter/sd_ms", 2,
         "conditions.wobble.frame_time_jitter.sd_ms is not a parameter of a uniform jitter (give range_ms)"},
        {"/conditions/hitch/hitches/ms", 2500,
         "conditions.hitch.hitches.ms is 2500 ms, not shorter than its period (every_s 2 s); a hitch must end "
         "before the next is due"},
        {"/conditions/hitch/hitches/rate_per_s", 1,
         "conditions.hitch.hitches needs one of every_s (periodic) and rate_per_s (random), not both or neither"},
        {"/conditions/even60/render_hz", 200,
         "conditions.even60.render_hz is 200 Hz, above the refresh (144 Hz): a display shows at most one new render "
         "per refresh; allowed: up to 144 Hz"},
    };
    for (const Case& c : cases) {
        Json document = paced(8);
        document[Json::json_pointer(c.pointer)] = c.value;
        EXPECT_EQ(errorOf(document), "protocol 'p.json': " + c.expected) << c.pointer;
    }
}

}  // namespace
}  // namespace warplab::protocol
