// A protocol's own conditions: parsed from its "conditions" object, named like presets by the
// fields that list conditions, written back by toJson, and every bad definition refused in one
// sentence naming the JSON path and what is allowed.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "click/click_protocol.h"
#include "shooter/shooter_protocol.h"

namespace warplab::protocol {
namespace {

using Json = nlohmann::ordered_json;

Json kim() {
    return Json::parse(R"({
      "format_version": 3, "name": "kim", "game": "shooter",
      "conditions": {
        "base60": {"render_hz": 60, "description": "60 Hz, no added delay"},
        "lag60x5": {"render_hz": 60, "lag_frames": 10},
        "lag60x5-rotation": {"render_hz": 60, "lag_frames": 10, "fill": "hold", "late_warp": "rotation"},
        "lag60x5-depth": {"render_hz": 60, "lag_ms": 83.33333333333333, "late_warp": "depth"}
      },
      "acclimation": {"mode": "base60"},
      "training": {"high_mode": "base60", "low_mode": "lag60x5"},
      "test": {"conditions": ["base60", "lag60x5", "lag60x5-rotation", "lag60x5-depth", "conv120"]}
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

TEST(ProtocolConditions, ALabDefinesItsOwnAndNamesThemLikePresets) {
    const ShooterProtocol p = parseShooterProtocol(kim().dump(), "p.json");
    ASSERT_EQ(p.conditionTable.defined().size(), 4u);
    const auto& rotation = p.conditionTable.at("lag60x5-rotation");
    EXPECT_EQ(rotation.renderHz, 60);
    EXPECT_EQ(rotation.lagFrames, 10);
    EXPECT_EQ(rotation.fill, "hold");
    EXPECT_EQ(rotation.lateWarp, condition::LateWarp::Rotation);
    EXPECT_EQ(p.conditionTable.at("base60").description, "60 Hz, no added delay");
    EXPECT_FALSE(p.conditionTable.at("lag60x5-depth").lagFrames.has_value());
    EXPECT_EQ(p.conditionTable.at("conv120").renderHz, 120);  // presets stay
    EXPECT_EQ(p.conditions.back(), "conv120");
}

TEST(ProtocolConditions, TheCanonicalCopyReadsBackTheSame) {
    const ShooterProtocol p = parseShooterProtocol(kim().dump(), "p.json");
    const std::string text = toJson(p);
    const ShooterProtocol again = parseShooterProtocol(text, "copy");
    EXPECT_TRUE(again.conditionTable == p.conditionTable);
    EXPECT_EQ(toJson(again), text);
    // Right after the header, before the game's sections.
    EXPECT_LT(text.find("\"conditions\": {"), text.find("\"display\""));
    // A file without conditions is written without them: a format 2 copy stays format 2.
    Json old = kim();
    old.erase("conditions");
    old["format_version"] = 2;
    old["acclimation"]["mode"] = "conv120";
    old["training"] = Json::object();
    old["test"]["conditions"] = {"conv15", "conv120"};
    const std::string oldText = toJson(parseShooterProtocol(old.dump(), "old"));
    EXPECT_EQ(oldText.find("conditions\": {"), std::string::npos);
    EXPECT_NE(oldText.find("\"format_version\": 2"), std::string::npos);
}

TEST(ProtocolConditions, BadDefinitionsNameTheirPath) {
    struct Case {
        const char* pointer;
        Json value;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {"/conditions/lag60x5/fill", "smear",
         "conditions.lag60x5.fill must be \"hold\", \"warp-full\", \"warp-nofix\", \"warp-sparse4\", "
         "\"warp-sparse8\", \"warp-sparse16\", \"warp-splat\", \"bireproj\" or \"blend\", got string \"smear\""},
        {"/conditions/lag60x5/late_warp", "inpaint",
         "conditions.lag60x5.late_warp must be \"none\", \"rotation\" or \"depth\", got string \"inpaint\""},
        {"/conditions/lag60x5/lag_frames", -2,
         "conditions.lag60x5.lag_frames must be an integer between 0 and 480, got -2"},
        {"/conditions/lag60x5/lag_frames", 481,
         "conditions.lag60x5.lag_frames must be an integer between 0 and 480, got 481"},
        // A hair off a rate that fits is not that rate, though the display would run it as that.
        {"/conditions/lag60x5/render_hz", 59.999999999,
         "conditions.lag60x5.render_hz is 59.999999999 Hz, which a 120 Hz display can only run as 60 Hz (every 2nd "
         "display frame); write 60"},
        {"/conditions/base60/description", std::string(201, 'x'),
         "conditions.base60.description must be a single line of at most 200 bytes, got string \"" +
             std::string(56, 'x') + "..."},
        {"/conditions/lag60x5/render_hz", 240,
         "conditions.lag60x5.render_hz is 240 Hz, above the refresh (120 Hz): a display shows at most one new render "
         "per refresh; allowed: up to 120 Hz"},
        {"/conditions/lag60x5/speed", 1,
         "conditions.lag60x5.speed is not a known field (conditions.lag60x5 may have description, render_hz, "
         "lag_frames, lag_ms, fill, fill_hz, late_warp, frame_time_jitter, hitches, frame_times)"},
        {"/conditions/lag60x5-depth/fill", "bireproj",
         "conditions.lag60x5-depth.late_warp must be \"none\" with fill \"bireproj\": a late warp re-projects one "
         "frame, and bireproj shows two (allowed with it: none)"},
        {"/conditions/conv60", Json{{"render_hz", 30}},
         "conditions.conv60 shadows the preset conv60 with other parts (the preset's: render_hz 60, lag_ms 0, fill "
         "hold, late_warp none); give the condition another name"},
        {"/conditions/spare", Json{{"render_hz", 30}},
         "conditions.spare is defined but no field names it (a condition list or condition field); remove it or use "
         "it"},
        {"/conditions/bad name", Json{{"render_hz", 30}},
         "conditions.bad name is not a condition name: 1 to 40 letters, digits and - _ . + (it appears in CSVs and "
         "file names)"},
        {"/conditions/lag60x5/lag_ms", 50,
         "conditions.lag60x5.lag_ms and lag_frames are two ways to give the added latency; give one"},
        {"/conditions/base60/render_hz", "sixty",
         "conditions.base60.render_hz must be a number greater than 0 and at most 1000, got string \"sixty\""},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.pointer);
        Json document = kim();
        document[Json::json_pointer(c.pointer)] = c.value;
        EXPECT_EQ(errorOf(document), "protocol 'p.json': " + c.expected);
    }
    // A lag in ms that is not whole frames at this refresh names the nearest two that are.
    Json document = kim();
    document["conditions"]["lag60x5-depth"]["lag_ms"] = 60;
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': conditions.lag60x5-depth.lag_ms is 60 ms, which is 7.2 frames at 120 Hz, not a "
              "whole number; the nearest that are: 58.3333 ms (7 frames) and 66.6667 ms (8 frames), or give "
              "lag_frames");
    // render_hz has no default.
    document = kim();
    document["conditions"]["lag60x5"].erase("render_hz");
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': conditions.lag60x5.render_hz is required: conventional renders "
              "per second");
    // Older formats have no conditions: refused naming the version, not read as another study.
    document = kim();
    document["format_version"] = 2;
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': conditions is new in format_version 3, but this file is format_version 2");
    // A name no preset or definition has lists both.
    document = kim();
    document["test"]["conditions"][0] = "base61";
    const std::string message = errorOf(document);
    EXPECT_NE(message.find("test.conditions[0] is \"base61\": unknown condition 'base61' (known: conv15"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("lag60x5-depth)"), std::string::npos) << message;
    // Repeating a preset's parts under its name is the preset.
    document = kim();
    document["conditions"]["conv60"] = Json{{"render_hz", 60}, {"lag_ms", 0}};
    document["test"]["conditions"][4] = "conv60";
    EXPECT_EQ(errorOf(document), "");
}

// What docs/protocol.md allows a definition: the default description written out, the longest
// one, the longest lag_frames (each refused once).
TEST(ProtocolConditions, TheDocumentedLimitsAreAccepted) {
    Json document = kim();
    document["conditions"]["base60"]["description"] = "";
    document["conditions"]["lag60x5"]["description"] = std::string(200, 'x');
    document["conditions"]["lag60x5"]["lag_frames"] = 480;
    ASSERT_EQ(errorOf(document), "");
    const ShooterProtocol p = parseShooterProtocol(document.dump(), "p.json");
    EXPECT_EQ(p.conditionTable.at("base60").description, "");
    EXPECT_EQ(p.conditionTable.at("lag60x5").description.size(), 200u);
    EXPECT_EQ(p.conditionTable.at("lag60x5").lagFrames, 480);
    EXPECT_TRUE(parseShooterProtocol(toJson(p), "copy").conditionTable == p.conditionTable);
}

TEST(ProtocolConditions, TheClickGameDefinesThemToo) {
    Json document = Json::parse(R"({
      "format_version": 2, "name": "c", "game": "click",
      "conditions": {"lag3": {"render_hz": 60, "lag_frames": 3, "description": "three frames late"}},
      "matches": {"modes": ["conv60", "lag3"]}
    })");
    const ClickProtocol p = parseClickProtocol(document.dump(), "c.json");
    EXPECT_EQ(p.conditionTable.at("lag3").lagFrames, 3);
    EXPECT_TRUE(parseClickProtocol(toJson(p), "copy").conditionTable == p.conditionTable);
    document["format_version"] = 1;
    try {
        parseClickProtocol(document.dump(), "c.json");
        ADD_FAILURE() << "a format 1 file with conditions was read";
    } catch (const ProtocolError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "protocol 'c.json': conditions is new in format_version 2, but this file is format_version 1");
    }
}

}  // namespace
}  // namespace warplab::protocol
