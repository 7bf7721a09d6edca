// The shooter protocol file: the shipped files say what the thesis says, the writer and the
// reader are exact inverses, and every class of bad input is refused with a sentence that
// names the file, the JSON path and the reason (sokol style: tests pin the messages).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "condition/schedule.h"
#include "shooter/shooter_protocol.h"
#include "protocol/questions_text.h"

namespace warplab::protocol {
namespace {

using Json = nlohmann::ordered_json;

const std::string kSource = "p.json";

std::string shippedPath(const std::string& name) { return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name; }

// Parsing as the app does: condition ids name presets or the file's own conditions.
ShooterProtocol parse(const std::string& text, const std::string& source = kSource) {
    return parseShooterProtocol(text, source);
}
ShooterProtocol load(const std::string& path) { return loadShooterProtocol(path); }

// The smallest valid file: only the required fields.
Json minimal() { return Json{{"format_version", 2}, {"name", "t"}, {"game", "shooter"}}; }

// The keys format 9 renamed: section, name, name before.
struct RenamedKey {
    const char* section;
    const char* now;
    const char* before;
};
const RenamedKey kRenamedKeys[] = {{"acclimation", "condition", "mode"},
                                   {"training", "high_condition", "high_mode"},
                                   {"training", "low_condition", "low_mode"}};

// The full canonical thesis document with one value replaced (pointer like "/test/timeout_s").
Json thesisWith(const std::string& pointer, const Json& value) {
    ShooterProtocol p;
    p.name = "t";
    Json document = Json::parse(toJson(p));
    document[Json::json_pointer(pointer)] = value;
    // An older version's document, as such files are: without the phases' instructions, and
    // without the test's questions.
    if (pointer == "/format_version" && value.is_number_integer() && value.get<int>() < kShooterInstructionsSince)
        for (const char* phase : {"acclimation", "training", "test"}) document[phase].erase("instructions");
    if (pointer == "/format_version" && value.is_number_integer() && value.get<int>() < kShooterQuestionsSince)
        document["test"].erase("questions");
    if (pointer == "/format_version" && value.is_number_integer() && value.get<int>() < kShooterPhotonMarkerSince)
        document["display"].erase("photon_marker"), document["display"].erase("max_late_share");
    // ... and with the older names of the keys that name a condition.
    if (pointer == "/format_version" && value.is_number_integer() && value.get<int>() < kShooterConditionKeysSince)
        for (const auto& [section, now, before] : kRenamedKeys) {
            Json renamed = Json::object();  // in place, as the canonical text has it
            for (const auto& [key, v] : document[section].items()) renamed[key == now ? before : key] = v;
            document[section] = renamed;
        }
    return document;
}

// The message of the ProtocolError that parsing gives, or a test failure if it parses.
std::string errorOfText(const std::string& text) {
    try {
        parse(text);
    } catch (const ProtocolError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a ProtocolError for:\n" << text;
    return "";
}
std::string errorOf(const Json& document) { return errorOfText(document.dump()); }

void expectContains(const std::string& message, const std::vector<std::string>& needles) {
    for (const std::string& needle : needles)
        EXPECT_NE(message.find(needle), std::string::npos)
            << "message '" << message << "' does not contain '" << needle << "'";
    // One sentence, one line: what a researcher reads on the console before a session.
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("protocol 'p.json': ", 0), 0u) << message;
}

void expectSame(const ShooterProtocol& a, const ShooterProtocol& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.description, b.description);
    EXPECT_EQ(a.formatVersion, b.formatVersion);
    EXPECT_EQ(a.game, b.game);
    // Doubles compared with ==: the round trip promises the same bits, not nearly.
    EXPECT_EQ(a.refreshHz, b.refreshHz);
    EXPECT_EQ(a.verticalFovDeg, b.verticalFovDeg);
    EXPECT_EQ(a.rendering.guardBand, b.rendering.guardBand);
    EXPECT_EQ(a.rendering.supersampling, b.rendering.supersampling);
    EXPECT_EQ(a.rendering.photonMarker, b.rendering.photonMarker);
    EXPECT_EQ(a.targetRadius, b.targetRadius);
    EXPECT_EQ(a.mouseRadiansPerCount, b.mouseRadiansPerCount);
    EXPECT_EQ(a.acclimationS, b.acclimationS);
    EXPECT_EQ(a.acclimationLevel, b.acclimationLevel);
    EXPECT_EQ(a.acclimationCondition, b.acclimationCondition);
    EXPECT_EQ(a.acclimationInstructions, b.acclimationInstructions);
    EXPECT_EQ(a.trainingInstructions, b.trainingInstructions);
    EXPECT_EQ(a.testInstructions, b.testInstructions);
    EXPECT_EQ(a.training.baseSpeed, b.training.baseSpeed);
    EXPECT_EQ(a.training.startLevel, b.training.startLevel);
    EXPECT_EQ(a.training.maxLevel, b.training.maxLevel);
    EXPECT_EQ(a.training.shotsPerLevelEasy, b.training.shotsPerLevelEasy);
    EXPECT_EQ(a.training.shotsPerLevelHard, b.training.shotsPerLevelHard);
    EXPECT_EQ(a.training.highCondition, b.training.highCondition);
    EXPECT_EQ(a.training.lowCondition, b.training.lowCondition);
    EXPECT_EQ(a.training.timeLimitS, b.training.timeLimitS);
    EXPECT_EQ(a.conditions, b.conditions);
    EXPECT_EQ(a.targetsPerCondition, b.targetsPerCondition);
    EXPECT_EQ(a.interleaveConditions, b.interleaveConditions);
    EXPECT_EQ(a.timeoutS, b.timeoutS);
    EXPECT_EQ(a.pauseS, b.pauseS);
    EXPECT_EQ(a.scoring, b.scoring);
    EXPECT_EQ(a.supervisorStartsTest, b.supervisorStartsTest);
    EXPECT_EQ(a.clickTiming, b.clickTiming);
    EXPECT_EQ(a.legacyRules, b.legacyRules);
    EXPECT_EQ(test::questionsText(a.questions), test::questionsText(b.questions));
}

// What a file older than format 4 means: no instruction screens.
ShooterProtocol withoutInstructions(ShooterProtocol p) {
    for (std::string* text : {&p.acclimationInstructions, &p.trainingInstructions, &p.testInstructions}) text->clear();
    return p;
}

// Every field different from its default, so a field the writer forgets comes back as its
// default and fails the comparison.
ShooterProtocol everyFieldChanged() {
    ShooterProtocol p;
    p.name = "all \"changed\" \xc3\xa9";  // quotes and UTF-8 must survive
    p.description = "line one\nline two\t\\";
    p.refreshHz = 240;
    p.verticalFovDeg = 0.1 + 0.2 + 70;  // not a short decimal
    p.rendering.guardBand = 0.1 + 0.2;  // not a short decimal
    p.rendering.supersampling = 2;
    p.rendering.photonMarker = PhotonMarker::BottomLeft;
    p.targetRadius = 1.0 / 3.0;
    p.mouseRadiansPerCount = std::nextafter(0.0022, 1.0);
    p.acclimationS = 12.5;
    p.acclimationLevel = 3;
    p.acclimationCondition = "conv60";
    p.acclimationInstructions = "Two\nlines";
    p.trainingInstructions = "";
    p.testInstructions = "T \"quoted\"";
    p.training.baseSpeed = 0.7;
    p.training.startLevel = 5;
    p.training.maxLevel = 40;
    p.training.shotsPerLevelEasy = 3;
    p.training.shotsPerLevelHard = 9;
    p.training.highCondition = "conv60";
    p.training.lowCondition = "conv30";
    p.training.timeLimitS = 1e-3;
    p.conditions = {"bireproj15to60", "lag200", "conv30", "warp15to120"};
    p.targetsPerCondition = 17;
    p.interleaveConditions = false;
    p.timeoutS = 2.25;
    p.pauseS = 0.1;
    p.scoring = Scoring::World;
    p.supervisorStartsTest = false;
    p.clickTiming = ClickTiming::InputReads;
    Question choice;
    choice.id = "which";
    choice.kind = QuestionKind::Choice;
    choice.prompt = "Which block felt the most responsive?";
    choice.options = {"this one", "the one before", "no difference"};
    Question likert;
    likert.id = "hard";
    likert.prompt = "Hitting the ball was hard";
    likert.min = 0;
    likert.max = 10;
    likert.minLabel = "not at all";
    likert.maxLabel = "";
    p.questions = {choice, likert};
    return p;
}

// ---------------------------------------------------------------------------------------
// The shipped files

TEST(ProtocolFiles, ThesisIsTheStudyAsPublished) {
    const ShooterProtocol p = load(shippedPath("shooter-thesis.json"));
    EXPECT_EQ(p.name, "shooter-thesis");
    EXPECT_EQ(p.game, "shooter");
    EXPECT_EQ(p.formatVersion, 2);
    EXPECT_FALSE(p.legacyRules);
    EXPECT_EQ(p.clickTiming, ClickTiming::Display);  // a click counts where the button goes down
    EXPECT_EQ(p.refreshHz, 120.0);  // App. B step 4
    EXPECT_EQ(p.acclimationS, 300.0);  // 5.3.4: 5 minutes
    EXPECT_EQ(p.acclimationLevel, 0);  // "with the easiest difficulty"
    EXPECT_EQ(p.training.timeLimitS, 720.0);  // 5.3.4: 12 minutes
    EXPECT_EQ(p.training.highCondition, "conv120");  // 5.3.3: stop when 120 Hz misses...
    EXPECT_EQ(p.training.lowCondition, "conv15");  // ... exceed 15 Hz hits
    EXPECT_LT(p.training.shotsPerLevelEasy, p.training.shotsPerLevelHard);
    EXPECT_EQ(p.conditions, (std::vector<std::string>{"conv15", "conv120", "warp15to120"}));
    EXPECT_EQ(p.targetsPerCondition, 225);  // 5.3.4: 675 targets in all
    EXPECT_TRUE(p.interleaveConditions);  // "in random order"
    EXPECT_EQ(p.timeoutS, 3.0);
    EXPECT_EQ(p.pauseS, 1.0);
    EXPECT_TRUE(p.supervisorStartsTest);  // App. B step 16
    // 5.3.4: "the maximum length of the phase is exactly 45 minutes".
    EXPECT_EQ(p.conditions.size() * p.targetsPerCondition * (p.timeoutS + p.pauseS), 45 * 60.0);
}

TEST(ProtocolFiles, ThesisIsWhatTheStructDefaultsSay) {
    ShooterProtocol defaults = withoutInstructions({});
    const ShooterProtocol p = load(shippedPath("shooter-thesis.json"));
    defaults.name = p.name;
    defaults.description = p.description;
    // The shipped file is format 2: it defines no conditions of its own, so it reads as before.
    EXPECT_EQ(p.formatVersion, 2);
    defaults.formatVersion = p.formatVersion;
    expectSame(p, defaults);
}

TEST(ProtocolFiles, QuickPlaysInWellUnderAMinute) {
    const ShooterProtocol p = load(shippedPath("shooter-quick.json"));
    EXPECT_EQ(p.name, "shooter-quick");
    EXPECT_FALSE(p.supervisorStartsTest);  // tests and demos run unattended
    EXPECT_EQ(p.conditions, ShooterProtocol{}.conditions);
    EXPECT_GE(p.targetsPerCondition, 2);
    const double longest =
        p.acclimationS + p.training.timeLimitS + p.conditions.size() * p.targetsPerCondition * (p.timeoutS + p.pauseS);
    EXPECT_LE(longest, 50.0);
}

TEST(ProtocolFiles, ShippedFilesAreInCanonicalForm) {
    // So each file lists every field explicitly and is byte for byte the copy a session stores.
    for (const char* name : {"shooter-thesis.json", "shooter-quick.json"}) {
        SCOPED_TRACE(name);
        const std::string text = readProtocolFile(shippedPath(name));
        EXPECT_EQ(toJson(parse(text, name)), text);
    }
}

// ---------------------------------------------------------------------------------------
// Defaults and the round trip

TEST(ProtocolDefaults, UnsetFieldsTakeTheThesisValues) {
    ShooterProtocol expected = withoutInstructions({});
    expected.name = "t";
    expected.formatVersion = minimal()["format_version"];
    expectSame(parse(minimal().dump()), expected);
    // An empty nested object is the same as an absent one.
    Json document = minimal();
    for (const char* section : {"display", "target", "input", "acclimation", "training", "test"})
        document[section] = Json::object();
    expectSame(parse(document.dump()), expected);
}

TEST(ProtocolDefaults, IntegersAreAcceptedForRealFields) {
    const ShooterProtocol p = parse(thesisWith("/display/refresh_hz", 240).dump());
    EXPECT_EQ(p.refreshHz, 240.0);
}

TEST(ProtocolRoundTrip, EveryFieldSurvivesBitForBit) {
    const ShooterProtocol p = everyFieldChanged();
    expectSame(parse(toJson(p)), p);
}

TEST(ProtocolRoundTrip, DefaultsSurvive) {
    ShooterProtocol p;
    p.name = "d";
    expectSame(parse(toJson(p)), p);
}

TEST(ProtocolRoundTrip, WriterIsStable) {
    const ShooterProtocol p = everyFieldChanged();
    const std::string once = toJson(p);
    EXPECT_EQ(toJson(parse(once)), once);
    EXPECT_EQ(toJson(p), once);  // no hidden state between calls
    EXPECT_EQ(once.back(), '\n');
}

TEST(ProtocolRoundTrip, WriterUsesTheDocumentedLayout) {
    const Json document = Json::parse(toJson(everyFieldChanged()));
    std::vector<std::string> keys;
    for (auto it = document.begin(); it != document.end(); ++it) keys.push_back(it.key());
    EXPECT_EQ(keys,
              (std::vector<std::string>{"format_version", "name", "description", "game", "display", "target", "input",
                                        "acclimation", "training", "test"}));
    EXPECT_EQ(document.at("test").at("scoring"), "world");
    EXPECT_EQ(document.at("training").at("base_speed_m_per_s"), 0.7);
    EXPECT_EQ(document.at("target").at("radius_m"), 1.0 / 3.0);
    EXPECT_EQ(document.at("acclimation").at("duration_s"), 12.5);
}

// ---------------------------------------------------------------------------------------
// Bad input: one sentence naming file, path and reason

TEST(ProtocolErrors, MalformedJsonGivesLineAndColumn) {
    const std::string message = errorOfText("{\n  \"format_version\": 1,\n  \"name\": \"t\",\n}\n");
    expectContains(message, {"malformed JSON", "line 4, column 1", "expected string literal"});
    EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
    expectContains(errorOfText(""), {"malformed JSON", "line 1, column 1"});
    expectContains(errorOfText("{\"format_version\": 1} trailing"), {"malformed JSON", "line 1"});
}

TEST(ProtocolErrors, TopLevelMustBeAnObject) {
    EXPECT_EQ(errorOfText("[1, 2]"), "protocol 'p.json': the top level must be a JSON object, got array [1,2]");
}

TEST(ProtocolErrors, RequiredFieldsAreNamed) {
    for (const char* field : {"format_version", "name", "game"}) {
        SCOPED_TRACE(field);
        Json document = minimal();
        document.erase(field);
        EXPECT_EQ(errorOf(document), std::string("protocol 'p.json': ") + field + " is required but missing");
    }
}

TEST(ProtocolErrors, NewerFormatVersionNamesBothVersions) {
    Json document = minimal();
    document["format_version"] = 10;
    EXPECT_EQ(errorOf(document), "protocol 'p.json': format_version 10 is newer than this warplab supports (9)");
    // A newer file may have fields this build does not know; the version is the real reason.
    document["test"] = Json{{"new_thing", 1}};
    document["shiny"] = true;
    EXPECT_EQ(errorOf(document), "protocol 'p.json': format_version 10 is newer than this warplab supports (9)");
    document = minimal();
    document["format_version"] = 0;
    EXPECT_EQ(errorOf(document), "protocol 'p.json': format_version must be at least 1, got 0");
    document["format_version"] = "1";
    EXPECT_EQ(errorOf(document), "protocol 'p.json': format_version must be an integer, got string \"1\"");
}

TEST(ProtocolErrors, UnknownTopLevelFieldIsNamed) {
    Json document = minimal();
    document["refresh_hz"] = 120;  // belongs in "display"
    const std::string message = errorOf(document);
    expectContains(message, {"refresh_hz is not a known field", "the top level may have", "display", "test"});
}

TEST(ProtocolErrors, UnknownNestedFieldIsNamedWithItsPath) {
    const std::string message = errorOf(thesisWith("/test/timout_s", 3));
    EXPECT_EQ(message,
              "protocol 'p.json': test.timout_s is not a known field (test may have conditions, "
              "targets_per_condition, interleave, timeout_s, pause_s, scoring, supervisor_starts, "
              "click_timing, instructions, questions)");
    expectContains(errorOf(thesisWith("/training/max_levle", 3)), {"training.max_levle is not a known field"});
    expectContains(errorOf(thesisWith("/display/refresh", 3)), {"display.refresh is not a known field"});
}

TEST(ProtocolErrors, DuplicateKeyIsNamedWithItsPath) {
    EXPECT_EQ(errorOfText(R"({"format_version":1,"name":"t","game":"shooter",
                         "test":{"timeout_s":3,"conditions":["conv15"],"timeout_s":4}})"),
              "protocol 'p.json': test.timeout_s appears more than once");
    EXPECT_EQ(errorOfText(R"({"format_version":1,"name":"t","name":"u","game":"shooter"})"),
              "protocol 'p.json': name appears more than once");
    // Equal keys in different objects are not repeats.
    EXPECT_NO_THROW(parse(
        R"({"format_version":1,"name":"t","game":"shooter","display":{},"target":{},
            "acclimation":{"level":0},"training":{"start_level":0}})"));
}

TEST(ProtocolErrors, WrongTypesAreNamed) {
    EXPECT_EQ(errorOf(thesisWith("/display/refresh_hz", "120")),
              "protocol 'p.json': display.refresh_hz must be a number between 1 and 1000, got "
              "string \"120\"");
    EXPECT_EQ(errorOf(thesisWith("/test/targets_per_condition", 2.5)),
              "protocol 'p.json': test.targets_per_condition must be an integer between 1 and "
              "100000, got 2.5");
    EXPECT_EQ(errorOf(thesisWith("/test/interleave", 1)),
              "protocol 'p.json': test.interleave must be true or false, got 1");
    EXPECT_EQ(errorOf(thesisWith("/test/supervisor_starts", nullptr)),
              "protocol 'p.json': test.supervisor_starts must be true or false, got null");
    EXPECT_EQ(errorOf(thesisWith("/description", 5)), "protocol 'p.json': description must be a string, got 5");
    EXPECT_EQ(errorOf(thesisWith("/display", 120)), "protocol 'p.json': display must be an object, got 120");
    EXPECT_EQ(errorOf(thesisWith("/test/conditions", "conv15")),
              "protocol 'p.json': test.conditions must be a non-empty array of condition ids, got "
              "string \"conv15\"");
    EXPECT_EQ(errorOf(thesisWith("/test/conditions", Json::array())),
              "protocol 'p.json': test.conditions must be a non-empty array of condition ids, got "
              "array []");
    EXPECT_EQ(errorOf(thesisWith("/training/start_level", true)),
              "protocol 'p.json': training.start_level must be an integer between 0 and 120, got "
              "boolean true");
}

TEST(ProtocolErrors, GameAndNameAreChecked) {
    EXPECT_EQ(errorOf(thesisWith("/game", "click")),
              "protocol 'p.json': game must be \"shooter\" for a shooter protocol, got string "
              "\"click\"");
    expectContains(errorOf(thesisWith("/name", "")), {"name must be a non-empty single line"});
    expectContains(errorOf(thesisWith("/name", "a\nb")), {"name must be a non-empty single line"});
}

TEST(ProtocolErrors, OutOfRangeValuesNameTheRange) {
    struct Case {
        const char* pointer;
        Json value;
        const char* expected;  // after "protocol 'p.json': "
    };
    const std::vector<Case> cases{
        {"/test/targets_per_condition", -3,
         "test.targets_per_condition must be an integer between 1 and 100000, got -3"},
        {"/test/targets_per_condition", 0, "test.targets_per_condition must be an integer between 1 and 100000, got 0"},
        {"/test/targets_per_condition", 18446744073709551615u,
         "test.targets_per_condition must be an integer between 1 and 100000, got "
         "18446744073709551615"},
        {"/display/refresh_hz", 0, "display.refresh_hz must be a number between 1 and 1000, got 0"},
        {"/display/refresh_hz", 1200, "display.refresh_hz must be a number between 1 and 1000, got 1200"},
        {"/display/vertical_fov_deg", 180, "display.vertical_fov_deg must be a number between 1 and 179, got 180"},
        {"/target/radius_m", 0, "target.radius_m must be a number at least 0.01 and less than 3, got 0"},
        {"/target/radius_m", 3.0, "target.radius_m must be a number at least 0.01 and less than 3, got 3.0"},
        {"/input/mouse_radians_per_count", -0.0022,
         "input.mouse_radians_per_count must be a number between 1e-06 and 0.1, got -0.0022"},
        {"/acclimation/duration_s", 0,
         "acclimation.duration_s must be a number greater than 0 and at most 1800, got 0"},
        {"/acclimation/level", -1, "acclimation.level must be an integer between 0 and 120, got -1"},
        {"/training/base_speed_m_per_s", -1.0,
         "training.base_speed_m_per_s must be a number greater than 0 and at most 100, got -1.0"},
        {"/training/max_level", 121, "training.max_level must be an integer between 0 and 120, got 121"},
        {"/training/shots_per_level_easy", 0,
         "training.shots_per_level_easy must be an integer between 1 and 10000, got 0"},
        {"/training/shots_per_level_hard", 0,
         "training.shots_per_level_hard must be an integer between 1 and 10000, got 0"},
        {"/training/time_limit_s", -720,
         "training.time_limit_s must be a number greater than 0 and at most 3600, got -720"},
        {"/test/timeout_s", 0, "test.timeout_s must be a number greater than 0 and at most 120, got 0"},
        {"/test/pause_s", -1, "test.pause_s must be a number greater than 0 and at most 60, got -1"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.pointer);
        EXPECT_EQ(errorOf(thesisWith(c.pointer, c.value)), std::string("protocol 'p.json': ") + c.expected);
    }
    // The bounds themselves are allowed where the range is closed.
    EXPECT_NO_THROW(parse(thesisWith("/display/vertical_fov_deg", 179).dump()));
    EXPECT_NO_THROW(parse(thesisWith("/test/targets_per_condition", 100000).dump()));
}

// ---------------------------------------------------------------------------------------
// Limits that keep a session's data safe (docs/protocol.md): each bound itself is accepted,
// the next double past it is refused with the exact sentence.

struct Bound {
    const char* pointer;
    double bound;  // allowed
    double past;  // the next double beyond it: refused
    const char* expected;  // after "protocol 'p.json': "
};

void expectBounds(const std::vector<Bound>& bounds) {
    for (const Bound& b : bounds) {
        SCOPED_TRACE(b.pointer);
        EXPECT_NO_THROW(parse(thesisWith(b.pointer, b.bound).dump()));
        EXPECT_EQ(errorOf(thesisWith(b.pointer, b.past)), std::string("protocol 'p.json': ") + b.expected);
    }
}

double above(double bound) { return std::nextafter(bound, INFINITY); }
double below(double bound) { return std::nextafter(bound, -INFINITY); }

TEST(ProtocolLimits, NoTrialPauseOrPhaseRunsPastItsBound) {
    // A trial is committed when it ends, so a pause and the next trial up to its timeout
    // (at most 60 + 120 s, 180000 frames at the 1000 Hz ceiling) is the most a session holds
    // in memory. The phases are committed trial by trial; their bounds bound the session.
    expectBounds({
        {"/test/timeout_s", 120, above(120),
         "test.timeout_s must be a number greater than 0 and at most 120, got 120.00000000000001"},
        {"/test/pause_s", 60, above(60),
         "test.pause_s must be a number greater than 0 and at most 60, got 60.00000000000001"},
        {"/acclimation/duration_s", 1800, above(1800),
         "acclimation.duration_s must be a number greater than 0 and at most 1800, got "
         "1800.0000000000002"},
        {"/training/time_limit_s", 3600, above(3600),
         "training.time_limit_s must be a number greater than 0 and at most 3600, got "
         "3600.0000000000005"},
    });
    // The case that set the limit: a day-long feedback pause at 1000 Hz, 86.4 million frames uncommitted.
    EXPECT_EQ(errorOf(thesisWith("/test/pause_s", 86400)),
              "protocol 'p.json': test.pause_s must be a number greater than 0 and at most 60, "
              "got 86400");
}

TEST(ProtocolLimits, TinyPositiveValuesThatBreakLaterMathsAreRefused) {
    // 1e-310 rad a count was accepted and ended the session in "dir: must be non-zero and
    // finite", naming neither the file nor the field.
    EXPECT_EQ(errorOf(thesisWith("/input/mouse_radians_per_count", 1e-310)),
              "protocol 'p.json': input.mouse_radians_per_count must be a number between 1e-06 "
              "and 0.1, got 1e-310");
    // A subnormal radius was a float 0 on screen: a target no one could see or hit.
    EXPECT_EQ(errorOf(thesisWith("/target/radius_m", 1e-310)),
              "protocol 'p.json': target.radius_m must be a number at least 0.01 and less than 3, "
              "got 1e-310");
    expectBounds({
        {"/input/mouse_radians_per_count", 1e-6, below(1e-6),
         "input.mouse_radians_per_count must be a number between 1e-06 and 0.1, got "
         "9.999999999999997e-07"},
        {"/target/radius_m", 0.01, below(0.01),
         "target.radius_m must be a number at least 0.01 and less than 3, got "
         "0.009999999999999998"},
    });
}

TEST(ProtocolLimits, TheFieldOfViewRangeIsTheOneRenderUses) {
    // Shared with `warplab render --fov` and the click protocol (shooter_protocol.h), both ends in.
    expectBounds({
        {"/display/vertical_fov_deg", kMaxVerticalFovDeg, above(kMaxVerticalFovDeg),
         "display.vertical_fov_deg must be a number between 1 and 179, got 179.00000000000003"},
        {"/display/vertical_fov_deg", kMinVerticalFovDeg, below(kMinVerticalFovDeg),
         "display.vertical_fov_deg must be a number between 1 and 179, got 0.9999999999999999"},
    });
}

TEST(ProtocolErrors, HugeNumbersAreRefusedNotWrapped) {
    // 1e400 is valid JSON but overflows a double.
    EXPECT_EQ(errorOfText(R"({"format_version":1,"name":"t","game":"shooter","test":{"timeout_s":1e400}})"),
              "protocol 'p.json': unreadable JSON at line 1, number overflow parsing '1e400' (beyond what a double "
              "holds)");
    // Its line, in a file of several.
    EXPECT_EQ(errorOfText("{\"format_version\": 2,\n\"name\": \"t\",\n\"game\": \"shooter\",\n\"target\": "
                          "{\"radius_m\": 1e999}}"),
              "protocol 'p.json': unreadable JSON at line 4, number overflow parsing '1e999' (beyond what a double "
              "holds)");
    // An integer too big for 64 bits becomes a double: not an integer.
    expectContains(errorOfText(R"({"format_version":1,"name":"t","game":"shooter",
                              "test":{"targets_per_condition":100000000000000000000000}})"),
                   {"test.targets_per_condition must be an integer between 1 and 100000"});
}

TEST(ProtocolErrors, LevelsAndShotsMustBeOrdered) {
    Json document = thesisWith("/training/start_level", 30);
    document["training"]["max_level"] = 20;
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': training.start_level must be at most training.max_level (20), "
              "got 30");
    document = thesisWith("/acclimation/level", 61);
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': acclimation.level must be at most training.max_level (60), got 61");
    document = thesisWith("/training/shots_per_level_hard", 3);
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': training.shots_per_level_hard must be at least "
              "training.shots_per_level_easy (4), got 3");
    document = thesisWith("/training/low_condition", "conv120");
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': training.low_condition must differ from training.high_condition, both are "
              "\"conv120\"");
    // Equal is fine: a fixed-difficulty "staircase" and fixed shots per level.
    document = thesisWith("/training/start_level", 60);
    document["training"]["shots_per_level_hard"] = 4;
    EXPECT_NO_THROW(parse(document.dump()));
}

// The reason after the path is the condition table's own: the presets have one home.
std::string conditionError(const std::string& where, const std::string& id, double refreshHz) {
    return "protocol 'p.json': " + where + " is \"" + id + "\": " + condition::ConditionTable().check(id, refreshHz);
}

TEST(ProtocolErrors, UnknownConditionsListTheKnownOnes) {
    const std::string message = errorOf(thesisWith("/test/conditions/1", "conv25"));
    EXPECT_EQ(message, conditionError("test.conditions[1]", "conv25", 120));
    expectContains(message, {"test.conditions[1] is \"conv25\": unknown condition 'conv25'"});
    for (const std::string& id : condition::presetNames()) expectContains(message, {id});
    EXPECT_EQ(errorOf(thesisWith("/acclimation/condition", "CONV120")),
              conditionError("acclimation.condition", "CONV120", 120));
    EXPECT_EQ(errorOf(thesisWith("/training/high_condition", "warp")),
              conditionError("training.high_condition", "warp", 120));
    // Not a string at all: a type error, before any condition is looked up.
    EXPECT_EQ(errorOf(thesisWith("/training/low_condition", 15)),
              "protocol 'p.json': training.low_condition must be a condition id (a string), got 15");
    EXPECT_EQ(errorOf(thesisWith("/test/conditions/0", Json::array({"conv15"}))),
              "protocol 'p.json': test.conditions[0] must be a condition id (a string), got array "
              "[\"conv15\"]");
}

TEST(ProtocolErrors, DuplicateConditionsAreNamed) {
    EXPECT_EQ(errorOf(thesisWith("/test/conditions", {"conv15", "conv120", "conv15"})),
              "protocol 'p.json': test.conditions[2] repeats \"conv15\", already test.conditions[0]");
}

TEST(ProtocolErrors, ScoringIsDisplayedOrWorld) {
    EXPECT_EQ(errorOf(thesisWith("/test/scoring", "both")),
              "protocol 'p.json': test.scoring must be \"displayed\" or \"world\", got string "
              "\"both\"");
    EXPECT_EQ(errorOf(thesisWith("/test/scoring", "Displayed")),
              "protocol 'p.json': test.scoring must be \"displayed\" or \"world\", got string "
              "\"Displayed\"");
    EXPECT_EQ(parse(thesisWith("/test/scoring", "world").dump()).scoring, Scoring::World);
}

TEST(ProtocolErrors, ConditionsMustFitTheRefreshRate) {
    // The thesis defaults at 100 Hz: the first condition read, acclimation's, is the culprit.
    EXPECT_EQ(errorOf(thesisWith("/display/refresh_hz", 100)), conditionError("acclimation.condition", "conv120", 100));
    expectContains(errorOf(thesisWith("/display/refresh_hz", 100)),
                   {"acclimation.condition is \"conv120\"", "above the refresh (100 Hz)"});
    // Defaults are checked too, not just the conditions a file spells out.
    Json document = minimal();
    document["display"] = Json{{"refresh_hz", 60}};
    EXPECT_EQ(errorOf(document), conditionError("acclimation.mode", "conv120", 60));

    document = thesisWith("/display/refresh_hz", 100);
    // 60 on 100 Hz runs, unevenly (renders 1 or 2 refreshes apart): the next condition read is the culprit.
    document["acclimation"]["condition"] = "conv60";
    expectContains(errorOf(document), {"training.high_condition is \"conv120\"", "above the refresh (100 Hz)"});

    // 60 Hz: conv15/30/60, the lag conditions and bireproj fit; 120 Hz and warp do not.
    document = thesisWith("/display/refresh_hz", 60);
    document["acclimation"]["condition"] = "conv60";
    document["training"]["high_condition"] = "conv60";
    document["test"]["conditions"] = {"conv15", "conv30", "conv60",         "lag50",
                                      "lag100", "lag200", "bireproj15to60", "warp15to120"};
    EXPECT_EQ(errorOf(document), conditionError("test.conditions[7]", "warp15to120", 60));
    document["test"]["conditions"].erase(7);
    EXPECT_NO_THROW(parse(document.dump()));

    // 90 Hz: the lag conditions' 60 Hz renders run unevenly and 100 ms is 9 whole frames; a fill at
    // 60 Hz makes its frames 1 or 2 refreshes apart; but 50 ms is not whole frames.
    document = thesisWith("/display/refresh_hz", 90);
    document["acclimation"]["condition"] = "conv30";
    document["training"]["high_condition"] = "conv30";
    document["test"]["conditions"] = {"conv15", "lag100", "bireproj15to60"};
    EXPECT_NO_THROW(parse(document.dump()));
    document["test"]["conditions"] = {"lag50"};
    expectContains(errorOf(document), {"test.conditions[0] is \"lag50\"", "4.5 frames at 90 Hz"});

    // The training pair is checked like any other condition.
    document = thesisWith("/display/refresh_hz", 45);
    document["acclimation"]["condition"] = "conv15";
    document["training"]["high_condition"] = "conv15";
    document["training"]["low_condition"] = "conv30";
    document["test"]["conditions"] = {"conv15"};
    EXPECT_NO_THROW(parse(document.dump()));  // 30 on 45 Hz: renders 1 or 2 refreshes apart
    document["training"]["low_condition"] = "conv60";
    EXPECT_EQ(errorOf(document), conditionError("training.low_condition", "conv60", 45));

    // A non-integral refresh fits nothing, 240 Hz fits everything.
    expectContains(errorOf(thesisWith("/display/refresh_hz", 119.88)), {"acclimation.condition is \"conv120\""});
    document = thesisWith("/display/refresh_hz", 240);
    document["test"]["conditions"] = condition::presetNames();
    EXPECT_EQ(parse(document.dump()).conditions, condition::presetNames());
}

// ---------------------------------------------------------------------------------------
// Format versions: 1 is still read, and means the rules it was recorded under

// The thesis study as a version 1 file: no click_timing.
Json thesisVersion1() {
    Json document = thesisWith("/format_version", 1);
    document["test"].erase("click_timing");
    document["display"].erase("refresh_mismatch");  // also new with format 2
    document["display"].erase("guard_band");  // new since, and written for format 2 only
    document["display"].erase("supersampling");
    return document;
}

TEST(ProtocolVersions, NewStructsAreVersion9WithNewRules) {
    const ShooterProtocol p;
    EXPECT_EQ(p.formatVersion, kShooterFormatVersion);
    EXPECT_EQ(kShooterFormatVersion, 9);
    EXPECT_FALSE(p.legacyRules);
    EXPECT_EQ(p.clickTiming, ClickTiming::Display);
    EXPECT_FALSE(parse(minimal().dump()).legacyRules);
}

// Format 9 renamed the keys that name a condition for it (acclimation.mode is
// acclimation.condition); older files keep their names, so that their sessions replay.
TEST(ProtocolVersions, Format9NamesTheKeysThatNameACondition) {
    Json before = thesisWith("/format_version", 8);
    before["acclimation"]["mode"] = "conv60";
    before["training"]["high_mode"] = "conv60";
    before["training"]["low_mode"] = "conv30";
    const ShooterProtocol old = parse(before.dump());
    EXPECT_EQ(old.acclimationCondition, "conv60");
    EXPECT_EQ(old.training.highCondition, "conv60");
    EXPECT_EQ(old.training.lowCondition, "conv30");
    // Written back under the names of its version, and read back the same.
    const Json written = Json::parse(toJson(old));
    EXPECT_EQ(written["acclimation"]["mode"], "conv60");
    EXPECT_EQ(written["training"]["low_mode"], "conv30");
    for (const auto& [section, now, name] : kRenamedKeys) EXPECT_FALSE(written[section].contains(now)) << now;
    EXPECT_EQ(toJson(parse(toJson(old))), toJson(old));

    // The same protocol in format 9 under the new names.
    Json after = thesisWith("/acclimation/condition", "conv60");
    after["training"]["high_condition"] = "conv60";
    after["training"]["low_condition"] = "conv30";
    const ShooterProtocol now = parse(after.dump());
    EXPECT_EQ(now.acclimationCondition, "conv60");
    EXPECT_EQ(now.training.highCondition, "conv60");
    EXPECT_EQ(now.training.lowCondition, "conv30");
    for (const auto& [section, name, before] : kRenamedKeys)
        EXPECT_FALSE(Json::parse(toJson(now))[section].contains(before)) << before;

    // A format 9 file that keeps an old name is refused naming the new one; an older file may
    // not use a new name.
    Json stale = after;
    stale["training"]["low_mode"] = "conv30";
    stale["training"].erase("low_condition");
    EXPECT_EQ(errorOf(stale),
              "protocol 'p.json': training.low_mode was renamed low_condition in format_version 9, "
              "and this file is format_version 9: use training.low_condition instead");
    Json early = before;
    early["acclimation"]["condition"] = "conv60";
    early["acclimation"].erase("mode");
    EXPECT_EQ(errorOf(early),
              "protocol 'p.json': acclimation.condition is new in format_version 9, but this file is format_version 8");

    // A message about an older file's value names the key the file has.
    before["training"]["low_mode"] = "conv60";
    EXPECT_EQ(errorOf(before),
              "protocol 'p.json': training.low_mode must differ from training.high_mode, both are "
              "\"conv60\"");
}

TEST(ProtocolInstructions, EachPhaseOpensWithTheTaskInPlainWordsFromFormat4) {
    Json document = minimal();
    document["format_version"] = 4;
    const ShooterProtocol p = parse(document.dump());
    for (const std::string* text : {&p.acclimationInstructions, &p.trainingInstructions, &p.testInstructions}) {
        EXPECT_NE(text->find("with the mouse"), std::string::npos) << *text;
        EXPECT_NE(text->find("press the left button to shoot it"), std::string::npos) << *text;
    }
    document["test"]["instructions"] = "";
    EXPECT_EQ(parse(document.dump()).testInstructions, "");
    for (int version : {1, 2, 3}) {
        document = minimal();
        document["format_version"] = version;
        expectSame(parse(document.dump()), [&] {
            ShooterProtocol none = withoutInstructions({});
            none.name = "t";
            none.formatVersion = version;
            none.legacyRules = version == 1;
            return none;
        }());
    }
}

TEST(ProtocolInstructions, OlderFilesMayNotSetThemAndBadTextIsNamed) {
    Json document = minimal();
    document["format_version"] = 3;
    document["training"]["instructions"] = "Go";
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': training.instructions is new in format_version 4, but this file is format_version 3");
    document["format_version"] = 4;
    document["training"]["instructions"] = Json::array();
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': training.instructions must be a text of at most 1000 bytes without control "
              "characters other than line breaks, got array []");
    // A struct of an older version that has some cannot be written as that version quietly.
    ShooterProtocol old = parse(minimal().dump());
    old.testInstructions = "Go";
    expectContains(errorOfText(toJson(old)), {"test.instructions is new in format_version 4"});
}

// ---------------------------------------------------------------------------------------
// Questions after each block of the test (format 5), read by the reader every game shares

// A format 5 file asking `questions` after each block of the test.
Json withTestQuestions(const Json& questions) {
    Json document = minimal();
    document["format_version"] = 5;
    document["test"]["questions"] = questions;
    return document;
}

TEST(ProtocolQuestions, NoneByDefaultAndEachKindParses) {
    Json document = minimal();
    document["format_version"] = 5;
    EXPECT_TRUE(parse(document.dump()).questions.empty());  // the thesis asked none
    EXPECT_TRUE(ShooterProtocol{}.questions.empty());
    EXPECT_TRUE(parse(withTestQuestions(Json::array()).dump()).questions.empty());
    const ShooterProtocol p = parse(
        withTestQuestions({Json{{"id", "smooth"}, {"prompt", "The motion was smooth"}, {"max", 5}},
                           Json{{"id", "which"}, {"kind", "choice"}, {"prompt", "Better?"}, {"options", {"a", "b"}}},
                           Json{{"id", "notes"}, {"kind", "text"}, {"prompt", "Notes"}, {"max_length", 50}}})
            .dump());
    ASSERT_EQ(p.questions.size(), 3u);
    EXPECT_EQ(p.questions[0].kind, QuestionKind::Likert);
    EXPECT_EQ(p.questions[0].min, 1);
    EXPECT_EQ(p.questions[0].max, 5);
    EXPECT_EQ(p.questions[1].kind, QuestionKind::Choice);
    EXPECT_EQ(p.questions[1].options, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(p.questions[2].kind, QuestionKind::Text);
    EXPECT_EQ(p.questions[2].maxLength, 50);
}

TEST(ProtocolQuestions, TheCanonicalCopyReadsBackTheSame) {
    const ShooterProtocol p = everyFieldChanged();
    const Json written = Json::parse(toJson(p));
    EXPECT_EQ(written.at("test").at("questions").size(), 2u);
    expectSame(parse(written.dump()), p);
    // None is written as [] in format 5 and not at all in older files, which had none.
    ShooterProtocol none;
    none.name = "n";
    EXPECT_EQ(Json::parse(toJson(none)).at("test").at("questions"), Json::array());
    Json older = minimal();
    older["format_version"] = 4;
    EXPECT_EQ(Json::parse(toJson(parse(older.dump()))).at("test").count("questions"), 0u);
}

TEST(ProtocolQuestions, OlderFilesMayNotAskAny) {
    Json document = withTestQuestions(Json::array({Json{{"id", "a"}, {"prompt", "A"}}}));
    document["format_version"] = 4;
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': test.questions is new in format_version 5, but this file is format_version 4");
    // Nor can a struct of an older version quietly lose them: the copy lists them and is refused.
    ShooterProtocol p = parse(minimal().dump());
    p.questions = everyFieldChanged().questions;
    expectContains(errorOfText(toJson(p)), {"test.questions is new in format_version 5"});
}

TEST(ProtocolQuestions, BadQuestionsAreNamedByTheirPathInTheTest) {
    // The same reader as the click game's (tests/games/click/test_click_protocol.cpp has every
    // case): here each message names test.questions.
    EXPECT_EQ(errorOf(withTestQuestions(Json::array({Json{{"id", "a"}, {"prompt", "A"}, {"max_length", 9}}}))),
              "protocol 'p.json': test.questions[0].max_length is only for a text question; this one is likert");
    EXPECT_EQ(errorOf(withTestQuestions({Json{{"id", "a"}, {"prompt", "A"}}, Json{{"id", "a"}, {"prompt", "B"}}})),
              "protocol 'p.json': test.questions[1].id repeats \"a\", already test.questions[0].id");
    EXPECT_EQ(errorOf(withTestQuestions(Json::array({Json{{"prompt", "A"}}}))),
              "protocol 'p.json': test.questions[0].id is required but missing");
    EXPECT_EQ(errorOf(withTestQuestions(
                  Json::array({Json{{"id", "c"}, {"kind", "choice"}, {"prompt", "C"}, {"options", {"x", "x"}}}}))),
              "protocol 'p.json': test.questions[0].options[1] repeats \"x\", already test.questions[0].options[0]");
}

TEST(ProtocolVersions, Version1MeansLegacyRules) {
    const ShooterProtocol p = parse(thesisVersion1().dump());
    EXPECT_EQ(p.formatVersion, 1);
    EXPECT_TRUE(p.legacyRules);
    EXPECT_EQ(p.clickTiming, ClickTiming::Display);
    Json document = minimal();
    document["format_version"] = 1;
    EXPECT_TRUE(parse(document.dump()).legacyRules);
}

TEST(ProtocolVersions, Version1CannotHaveClickTiming) {
    EXPECT_EQ(errorOf(thesisWith("/format_version", 1)),
              "protocol 'p.json': test.click_timing is new in format_version 2, but this file is "
              "format_version 1");
    Json document = thesisVersion1();
    document["test"]["click_timing"] = "input_reads";
    expectContains(errorOf(document), {"test.click_timing", "format_version 1"});
}

TEST(ProtocolVersions, Version1RoundTripsAsVersion1) {
    // A version 1 session stores this copy; replaying it must give legacy rules again.
    const std::string text = thesisVersion1().dump(2) + "\n";  // canonical layout
    const ShooterProtocol p = parse(text);
    const std::string written = toJson(p);
    EXPECT_EQ(written, text);
    EXPECT_EQ(Json::parse(written).at("test").count("click_timing"), 0u);
    expectSame(parse(written), p);
    EXPECT_TRUE(parse(written).legacyRules);
}

TEST(ProtocolVersions, Version1StructCannotQuietlyLoseClickTiming) {
    ShooterProtocol p = parse(thesisVersion1().dump());
    p.clickTiming = ClickTiming::InputReads;  // a value version 1 cannot say
    expectContains(errorOfText(toJson(p)), {"test.click_timing is new in format_version 2"});
}

// A live session on a display at another refresh: refuse (the published studies) or warn
// (the quick protocols, so they run anywhere).
TEST(ProtocolVersions, RefreshMismatchIsRefuseOrWarn) {
    EXPECT_EQ(parse(thesisWith("/display/refresh_mismatch", "warn").dump()).refreshMismatch, RefreshMismatch::Warn);
    EXPECT_EQ(ShooterProtocol{}.refreshMismatch, RefreshMismatch::Refuse);
    expectContains(errorOf(thesisWith("/display/refresh_mismatch", "ignore")), {"display.refresh_mismatch"});
}

// How frames are rendered: a guard band for warp conditions' sources and supersampling.
TEST(ProtocolRendering, GuardBandAndSupersamplingAreReadAndBounded) {
    EXPECT_EQ(ShooterProtocol{}.rendering.guardBand, 0.1);
    EXPECT_EQ(ShooterProtocol{}.rendering.supersampling, 1);
    EXPECT_EQ(parse(thesisWith("/display/guard_band", 0).dump()).rendering.guardBand, 0.0);
    EXPECT_EQ(parse(thesisWith("/display/guard_band", 0.25).dump()).rendering.guardBand, 0.25);
    EXPECT_EQ(parse(thesisWith("/display/supersampling", 4).dump()).rendering.supersampling, 4);
    EXPECT_EQ(errorOf(thesisWith("/display/guard_band", 0.6)),
              "protocol 'p.json': display.guard_band must be a number between 0 and 0.5, got 0.6");
    expectContains(errorOf(thesisWith("/display/guard_band", -0.1)), {"display.guard_band"});
    EXPECT_EQ(errorOf(thesisWith("/display/supersampling", 5)),
              "protocol 'p.json': display.supersampling must be an integer between 1 and 4, got 5");
    expectContains(errorOf(thesisWith("/display/supersampling", 1.5)), {"display.supersampling"});
}

// A version 1 file said nothing of either and meant the defaults; its canonical copy stays
// as it was unless a value differs.
TEST(ProtocolRendering, Version1CopiesNameThemOnlyWhenNotDefault) {
    ShooterProtocol p = parse(thesisVersion1().dump());
    EXPECT_EQ(Json::parse(toJson(p)).at("display").count("guard_band"), 0u);
    p.rendering.supersampling = 2;
    const Json written = Json::parse(toJson(p));
    EXPECT_EQ(written.at("display").at("supersampling"), 2);
    EXPECT_EQ(parse(written.dump()).rendering.supersampling, 2);
    EXPECT_EQ(Json::parse(toJson(ShooterProtocol{})).at("display").at("guard_band"), 0.1);
}

// The photodiode marker (format 6): off unless a corner is named; a file of an older format
// may not name one, since its sessions ran without it.
TEST(ProtocolRendering, PhotonMarkerIsACornerOrOffFromFormat6) {
    EXPECT_EQ(ShooterProtocol{}.rendering.photonMarker, PhotonMarker::Off);
    EXPECT_EQ(parse(minimal().dump()).rendering.photonMarker, PhotonMarker::Off);
    for (const auto& [name, corner] :
         std::vector<std::pair<const char*, PhotonMarker>>{{"off", PhotonMarker::Off},
                                                           {"top_left", PhotonMarker::TopLeft},
                                                           {"top_right", PhotonMarker::TopRight},
                                                           {"bottom_left", PhotonMarker::BottomLeft},
                                                           {"bottom_right", PhotonMarker::BottomRight}})
        EXPECT_EQ(parse(thesisWith("/display/photon_marker", name).dump()).rendering.photonMarker, corner) << name;
    EXPECT_EQ(errorOf(thesisWith("/display/photon_marker", "centre")),
              "protocol 'p.json': display.photon_marker must be \"off\", \"top_left\", \"top_right\", "
              "\"bottom_left\" or \"bottom_right\", got string \"centre\"");
    Json document = thesisWith("/format_version", 5);
    document["display"]["photon_marker"] = "top_left";
    EXPECT_EQ(errorOf(document),
              "protocol 'p.json': display.photon_marker is new in format_version 6, but this file is format_version 5");
    // An older struct that has one is written with it, so that its copy is refused, not run without.
    ShooterProtocol old = parse(thesisWith("/format_version", 5).dump());
    EXPECT_EQ(Json::parse(toJson(old)).at("display").count("photon_marker"), 0u);
    old.rendering.photonMarker = PhotonMarker::TopLeft;
    expectContains(errorOfText(toJson(old)), {"display.photon_marker is new in format_version 6"});
}

TEST(ProtocolVersions, ClickTimingIsDisplayOrInputReads) {
    EXPECT_EQ(parse(thesisWith("/test/click_timing", "input_reads").dump()).clickTiming, ClickTiming::InputReads);
    Json document = thesisWith("/format_version", 2);
    document["test"].erase("click_timing");
    EXPECT_EQ(parse(document.dump()).clickTiming, ClickTiming::Display);
    EXPECT_EQ(errorOf(thesisWith("/test/click_timing", "frame")),
              "protocol 'p.json': test.click_timing must be \"display\" or \"input_reads\", got "
              "string \"frame\"");
    EXPECT_EQ(errorOf(thesisWith("/test/click_timing", true)),
              "protocol 'p.json': test.click_timing must be \"display\" or \"input_reads\", got "
              "boolean true");
}

// ---------------------------------------------------------------------------------------
// Files

TEST(ProtocolLoad, MissingFileNamesThePath) {
    const std::string path = std::string(WARPLAB_BINARY_DIR) + "/no-such-dir/missing.json";
    try {
        load(path);
        FAIL() << "expected a ProtocolError";
    } catch (const ProtocolError& e) {
        EXPECT_EQ(std::string(e.what()), "protocol '" + path + "': no such file");
    }
}

TEST(ProtocolLoad, DirectoryIsNotAFile) {
    const std::string path = std::string(WARPLAB_SOURCE_DIR) + "/protocol";
    try {
        load(path);
        FAIL() << "expected a ProtocolError";
    } catch (const ProtocolError& e) {
        EXPECT_EQ(std::string(e.what()), "protocol '" + path + "': is a directory, not a file");
    }
}

TEST(ProtocolLoad, ErrorsInAFileNameItsPath) {
    const std::filesystem::path dir = std::filesystem::path(WARPLAB_BINARY_DIR) / "test-output" / "protocol";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "bad.json").string();
    {
        std::ofstream file(path, std::ios::binary | std::ios::trunc);
        file << thesisWith("/test/timeout_s", 0).dump(2);
    }
    try {
        load(path);
        FAIL() << "expected a ProtocolError";
    } catch (const ProtocolError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "protocol '" + path + "': test.timeout_s must be a number greater than 0 and at most 120, got 0");
    }
}

// The share of late or skipped display frames that flags a live session (format 6): 1 % unless
// the file says otherwise, a share from 0 to 1, and not in an older file.
TEST(ProtocolRendering, MaxLateShareIsAShareFromFormat6) {
    EXPECT_EQ(ShooterProtocol{}.rendering.maxLateShare, 0.01);
    EXPECT_EQ(parse(thesisWith("/display/max_late_share", 0.05).dump()).rendering.maxLateShare, 0.05);
    expectContains(errorOf(thesisWith("/display/max_late_share", 1.5)), {"display.max_late_share", "between 0 and 1"});
    Json document = thesisWith("/format_version", 5);
    document["display"]["max_late_share"] = 0.05;
    EXPECT_EQ(
        errorOf(document),
        "protocol 'p.json': display.max_late_share is new in format_version 6, but this file is format_version 5");
}

}  // namespace
}  // namespace warplab::protocol

namespace warplab::protocol {
namespace {

// docs/protocol.md's shooter layout is a protocol a lab can copy: it loads, in the newest format,
// and shows the questions after a block that a lab adds first.
TEST(ProtocolDocs, TheShooterLayoutExampleLoadsWithItsQuestions) {
    std::ifstream doc(std::string(WARPLAB_SOURCE_DIR) + "/docs/protocol.md");
    const std::string text((std::istreambuf_iterator<char>(doc)), std::istreambuf_iterator<char>());
    const std::size_t heading = text.find("\n## Layout\n");
    ASSERT_NE(heading, std::string::npos);
    const std::size_t open = text.find("```json\n", heading), close = text.find("\n```", open);
    ASSERT_NE(close, std::string::npos);
    const std::string example = text.substr(open + 8, close - open - 8);
    const ShooterProtocol p = parseShooterProtocol(example, "docs/protocol.md");
    EXPECT_EQ(p.formatVersion, kShooterFormatVersion);
    EXPECT_EQ(p.questions.size(), 2u);
    EXPECT_FALSE(p.interleaveConditions);
}

}  // namespace
}  // namespace warplab::protocol
