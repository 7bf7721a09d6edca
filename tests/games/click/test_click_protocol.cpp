// The click game's protocol file and the loader every protocol shares: the shipped files say
// what Yang et al. 2011 section 8 says, the writer and the reader are exact inverses, and each
// bad input is refused with one sentence naming the file and the field (tests pin the words).
#include <fstream>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "condition/schedule.h"
#include "game/registry.h"
#include "click/click_protocol.h"
#include "shooter/shooter_protocol.h"
#include "protocol/documented_keys.h"
#include "protocol/questions_text.h"

namespace warplab::protocol {
namespace {

using Json = nlohmann::ordered_json;

const std::string kSource = "p.json";
const std::string kPrefix = "protocol 'p.json': ";

std::string protocolDir() { return std::string(WARPLAB_SOURCE_DIR) + "/protocol"; }

ClickProtocol parse(const std::string& text, const std::string& source = kSource) {
    return parseClickProtocol(text, source);
}

// The ProtocolError's message, or "" when the document parses.
std::string messageFor(const Json& document) {
    try {
        parse(document.dump());
    } catch (const ProtocolError& e) {
        return e.what();
    }
    return "";
}

// The full canonical published study with one value replaced (pointer like "/physics/restitution").
Json yangWith(const std::string& pointer, const Json& value) {
    ClickProtocol p;
    p.name = "t";
    Json document = Json::parse(toJson(p));
    document[Json::json_pointer(pointer)] = value;
    return document;
}

Json minimal() { return Json{{"format_version", 1}, {"name", "t"}, {"game", "click"}}; }

using test::questionsText;

void expectSame(const ClickProtocol& a, const ClickProtocol& b) {
    EXPECT_EQ(a.rendering.guardBand, b.rendering.guardBand);
    EXPECT_EQ(a.rendering.supersampling, b.rendering.supersampling);
    EXPECT_EQ(a.rendering.photonMarker, b.rendering.photonMarker);
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.description, b.description);
    EXPECT_EQ(a.formatVersion, b.formatVersion);
    EXPECT_EQ(a.game, b.game);
    // Doubles compared with ==: the round trip promises the same bits, not nearly.
    EXPECT_EQ(a.refreshHz, b.refreshHz);
    EXPECT_EQ(a.verticalFovDeg, b.verticalFovDeg);
    EXPECT_EQ(a.cameraPitchDeg, b.cameraPitchDeg);
    EXPECT_EQ(a.gravity, b.gravity);
    EXPECT_EQ(a.sphereRadius, b.sphereRadius);
    EXPECT_EQ(a.restitution, b.restitution);
    EXPECT_EQ(a.stepRateHz, b.stepRateHz);
    EXPECT_EQ(a.sphereCount, b.sphereCount);
    EXPECT_EQ(a.greenShare, b.greenShare);
    EXPECT_EQ(a.spawnDelayS, b.spawnDelayS);
    EXPECT_EQ(a.spawnSpeedMPerS, b.spawnSpeedMPerS);
    EXPECT_EQ(a.cursorPixelsPerCount, b.cursorPixelsPerCount);
    EXPECT_EQ(a.clickTiming, b.clickTiming);
    EXPECT_EQ(a.matchS, b.matchS);
    EXPECT_EQ(a.conditions, b.conditions);
    ASSERT_EQ(a.rounds.size(), b.rounds.size());
    for (std::size_t i = 0; i < a.rounds.size(); ++i) {
        SCOPED_TRACE("round " + std::to_string(i));
        EXPECT_EQ(a.rounds[i].name, b.rounds[i].name);
        EXPECT_EQ(a.rounds[i].scored, b.rounds[i].scored);
        EXPECT_EQ(a.rounds[i].matchesPerCondition, b.rounds[i].matchesPerCondition);
        EXPECT_EQ(a.rounds[i].instructions, b.rounds[i].instructions);
    }
    EXPECT_EQ(a.shuffle, b.shuffle);
    EXPECT_EQ(questionsText(a.questions), questionsText(b.questions));
    EXPECT_EQ(a.ratingsEnabled, b.ratingsEnabled);
    EXPECT_EQ(a.ratingStatements, b.ratingStatements);
    EXPECT_EQ(a.ratingMin, b.ratingMin);
    EXPECT_EQ(a.ratingMax, b.ratingMax);
    EXPECT_EQ(a.scoring, b.scoring);
}

// What a file of an older format means: before 3 no instruction screens; before 4 the ratings
// section's statements, asked as Likert questions on its one scale, with no ids (docs/protocol.md,
// "Questions").
ClickProtocol asFormat(ClickProtocol p, int version) {
    p.formatVersion = version;
    if (version < kClickPhotonMarkerSince) p.rendering.photonMarker = PhotonMarker::Off;
    if (version < 3)
        for (auto& round : p.rounds) round.instructions.clear();
    if (version < 4) {
        p.questions.clear();
        if (p.ratingsEnabled)
            for (const std::string& statement : p.ratingStatements) {
                Question q;
                q.prompt = statement;
                q.min = p.ratingMin;
                q.max = p.ratingMax;
                p.questions.push_back(q);
            }
    }
    return p;
}

// The same full document as a format 3 file, whose questions are its ratings section.
Json yang3With(const std::string& pointer, const Json& value) {
    ClickProtocol p = asFormat({}, 3);
    p.name = "t";
    Json document = Json::parse(toJson(p));
    document[Json::json_pointer(pointer)] = value;
    return document;
}

// Every field different from its default, so a field the writer forgets comes back as its
// default and fails the comparison.
ClickProtocol everyFieldChanged() {
    ClickProtocol p;
    p.rendering.guardBand = 0.1 + 0.2;  // not a short decimal
    p.rendering.supersampling = 3;
    p.rendering.photonMarker = PhotonMarker::TopRight;
    p.name = "all \"changed\" \xc3\xa9";
    p.description = "two\nlines";
    p.refreshHz = 120;
    p.verticalFovDeg = 0.1 + 0.2 + 50;  // not a short decimal
    p.cameraPitchDeg = -1.0 / 3.0;
    p.gravity = 1.62;
    p.sphereRadius = 0.3;
    p.restitution = 0.95;
    p.stepRateHz = 1200;
    p.sphereCount = 17;
    p.greenShare = 0.25;
    p.spawnDelayS = 0;
    p.spawnSpeedMPerS = 3.5;
    p.cursorPixelsPerCount = 2.5;
    p.clickTiming = ClickTiming::InputReads;
    p.matchS = 30.5;
    p.conditions = {"conv120", "warp15to120"};
    p.rounds = {{"warm-up", false, 3, "Two\nlines \"quoted\""}, {"a", true, 1, ""}, {"b", true, 4, "B"}};
    p.shuffle = false;
    Question likert;
    likert.id = "calm_1";
    likert.prompt = "I felt \"calm\" \xc3\xa9";
    likert.min = -3;
    likert.max = 3;
    likert.minLabel = "";  // no label under that end
    likert.maxLabel = "very";
    Question choice;
    choice.id = "Best";
    choice.kind = QuestionKind::Choice;
    choice.prompt = "Which looked smoothest?";
    choice.options = {"the first", "the second", "no difference"};
    Question text;
    text.id = "notes";
    text.kind = QuestionKind::Text;
    text.prompt = "Anything else?";
    text.maxLength = 1;
    p.questions = {likert, choice, text};
    p.scoring = Scoring::Displayed;
    return p;
}

// The same as a format 3 struct: its ratings section changed, and its questions what that says.
ClickProtocol everyFieldChangedFormat3() {
    ClickProtocol p = everyFieldChanged();
    p.ratingStatements = {"Only one", "And two"};
    p.ratingMin = 0;
    p.ratingMax = 10;
    return asFormat(p, 3);
}

// ---------------------------------------------------------------------------------------
// The shipped files

TEST(ClickFiles, YangIsTheStudyAsPublished) {
    const ClickProtocol p = loadClickProtocol(protocolDir() + "/click-yang.json");
    EXPECT_EQ(p.name, "click-yang");
    EXPECT_EQ(p.game, "click");
    EXPECT_EQ(p.refreshHz, 60.0);  // the fastest condition is 60 fps
    EXPECT_EQ(p.matchS, 45.0);  // "Each game match lasts for 45 seconds"
    // "60, 30, and 15fps", "60fps ... 50ms, 100ms, and 200ms" of lag, bireproj "15 to 60fps".
    EXPECT_EQ(p.conditions,
              (std::vector<std::string>{"conv60", "conv30", "conv15", "lag50", "lag100", "lag200", "bireproj15to60"}));
    // "21 matches, divided into two rounds": 7 unscored (one per condition), 14 scored (two per condition).
    ASSERT_EQ(p.rounds.size(), 2u);
    EXPECT_FALSE(p.rounds[0].scored);
    EXPECT_EQ(p.rounds[0].matchesPerCondition, 1);
    EXPECT_TRUE(p.rounds[1].scored);
    EXPECT_EQ(p.rounds[1].matchesPerCondition, 2);
    EXPECT_EQ(p.conditions.size() * (p.rounds[0].matchesPerCondition + p.rounds[1].matchesPerCondition), 21u);
    EXPECT_TRUE(p.shuffle);  // "presented in random order"
    EXPECT_TRUE(p.ratingsEnabled);
    EXPECT_EQ(p.ratingStatements,
              (std::vector<std::string>{"I enjoyed playing this game", "This game was difficult to play",
                                        "This game was responsive to my input", "The animation was smooth"}));
    EXPECT_EQ(p.ratingMin, 1);  // "from 1 (strongly disagree) to 7 (strongly agree)"
    EXPECT_EQ(p.ratingMax, 7);
}

TEST(ClickFiles, YangIsWhatTheStructDefaultsSay) {
    const ClickProtocol p = loadClickProtocol(protocolDir() + "/click-yang.json");
    // The shipped file is format 1: it defines no conditions of its own, so it reads as before,
    // without instruction screens, rating its ratings section's statements.
    EXPECT_EQ(p.formatVersion, 1);
    ClickProtocol defaults = asFormat({}, p.formatVersion);
    defaults.name = p.name;
    defaults.description = p.description;
    expectSame(p, defaults);
}

TEST(ClickFiles, QuickIsTheSameStudyInSeconds) {
    const ClickProtocol p = loadClickProtocol(protocolDir() + "/click-quick.json");
    EXPECT_EQ(p.name, "click-quick");
    EXPECT_EQ(p.refreshHz, 60.0);
    EXPECT_EQ(p.conditions, ClickProtocol{}.conditions);
    EXPECT_EQ(p.matchS, 3.0);
    ASSERT_EQ(p.rounds.size(), 2u);
    EXPECT_EQ(p.rounds[0].name, "practice");
    EXPECT_FALSE(p.rounds[0].scored);
    EXPECT_EQ(p.rounds[0].matchesPerCondition, 1);
    EXPECT_EQ(p.rounds[1].name, "scored");
    EXPECT_TRUE(p.rounds[1].scored);
    EXPECT_EQ(p.rounds[1].matchesPerCondition, 1);
    EXPECT_EQ(p.conditions.size() * 2 * p.matchS, 42.0);  // seconds of play, ratings aside
}

TEST(ClickFiles, ShippedFilesAreInCanonicalForm) {
    for (const char* name : {"click-yang.json", "click-quick.json"}) {
        SCOPED_TRACE(name);
        const std::string text = readProtocolFile(protocolDir() + "/" + name);
        EXPECT_EQ(toJson(parse(text, name)), text);
    }
}

// Every protocol that ships, whichever game, goes through the shared loader: "game" picks the
// parser, and each parser checks every condition id the file names against the conditions it can run.
TEST(ClickFiles, EveryShippedProtocolLoadsThroughTheSharedLoader) {
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(protocolDir())) {
        if (entry.path().extension() != ".json") continue;
        const std::string path = entry.path().string();
        SCOPED_TRACE(path);
        const std::string text = readProtocolFile(path);
        const std::string game = protocolGame(text, path);
        const auto names = game::gameNames();
        EXPECT_NE(std::find(names.begin(), names.end(), game), names.end()) << "no parser for game " << game;
        EXPECT_NO_THROW(game::parseStudy(text, path));
        ++count;
    }
    EXPECT_GE(count, 4);
}

// ---------------------------------------------------------------------------------------
// Defaults and the round trip

TEST(ClickDefaults, UnsetFieldsTakeThePublishedValues) {
    ClickProtocol expected = asFormat({}, minimal()["format_version"]);
    expected.name = "t";
    expectSame(parse(minimal().dump()), expected);
    Json document = minimal();
    for (const char* section : {"display", "physics", "input", "matches", "ratings"})
        document[section] = Json::object();
    expectSame(parse(document.dump()), expected);
    // A round with only its name is one scored match per condition.
    document["matches"]["rounds"] = Json::array({Json{{"name", "only"}}});
    const ClickProtocol p = parse(document.dump());
    ASSERT_EQ(p.rounds.size(), 1u);
    EXPECT_TRUE(p.rounds[0].scored);
    EXPECT_EQ(p.rounds[0].matchesPerCondition, 1);
}

TEST(ClickRoundTrip, EveryFieldSurvivesBitForBit) {
    for (const ClickProtocol& p : {everyFieldChanged(), everyFieldChangedFormat3()}) {
        SCOPED_TRACE(p.formatVersion);
        expectSame(parse(toJson(p)), p);
    }
}

TEST(ClickRoundTrip, WriterIsStable) {
    for (const ClickProtocol& p : {everyFieldChanged(), everyFieldChangedFormat3()}) {
        SCOPED_TRACE(p.formatVersion);
        const std::string once = toJson(p);
        EXPECT_EQ(toJson(parse(once)), once);
        EXPECT_EQ(once.back(), '\n');
    }
}

TEST(ClickRoundTrip, WriterUsesTheDocumentedLayout) {
    const Json document = Json::parse(toJson(everyFieldChanged()));
    std::vector<std::string> keys;
    for (auto it = document.begin(); it != document.end(); ++it) keys.push_back(it.key());
    // Format 4 asks matches.questions and has no ratings section.
    EXPECT_EQ(keys,
              (std::vector<std::string>{"format_version", "name", "description", "game", "display", "physics", "input",
                                        "matches"}));
    // Each question with every key of its kind, and only those, in the documented order.
    const Json& questions = document.at("matches").at("questions");
    ASSERT_EQ(questions.size(), 3u);
    EXPECT_EQ(questions[0].dump(),
              Json({{"id", "calm_1"},
                    {"kind", "likert"},
                    {"prompt", "I felt \"calm\" \xc3\xa9"},
                    {"min", -3},
                    {"max", 3},
                    {"min_label", ""},
                    {"max_label", "very"}})
                  .dump());
    EXPECT_EQ(questions[1].dump(),
              Json({{"id", "Best"},
                    {"kind", "choice"},
                    {"prompt", "Which looked smoothest?"},
                    {"options", {"the first", "the second", "no difference"}}})
                  .dump());
    EXPECT_EQ(questions[2].dump(),
              Json({{"id", "notes"}, {"kind", "text"}, {"prompt", "Anything else?"}, {"max_length", 1}}).dump());
    EXPECT_EQ(document.at("matches").at("rounds").at(0),
              (Json{{"name", "warm-up"},
                    {"scored", false},
                    {"matches_per_condition", 3},
                    {"instructions", "Two\nlines \"quoted\""}}));
    EXPECT_EQ(document.at("matches").at("scoring"), "displayed");
    EXPECT_EQ(document.at("physics").at("gravity_m_per_s2"), 1.62);
}

// The photodiode marker (format 5): off unless a corner is named, the shooter's spellings; a
// file of an older format may not name one.
TEST(ClickRendering, PhotonMarkerIsACornerOrOffFromFormat5) {
    EXPECT_EQ(ClickProtocol{}.rendering.photonMarker, PhotonMarker::Off);
    EXPECT_EQ(parse(yangWith("/display/photon_marker", "bottom_right").dump()).rendering.photonMarker,
              PhotonMarker::BottomRight);
    EXPECT_EQ(messageFor(yangWith("/display/photon_marker", "middle")),
              kPrefix +
                  "display.photon_marker must be \"off\", \"top_left\", \"top_right\", \"bottom_left\" or "
                  "\"bottom_right\", got string \"middle\"");
    Json document = minimal();
    document["format_version"] = 4;
    document["display"] = Json{{"photon_marker", "top_left"}};
    EXPECT_EQ(messageFor(document),
              kPrefix + "display.photon_marker is new in format_version 5, but this file is format_version 4");
    document["format_version"] = 5;
    EXPECT_EQ(parse(document.dump()).rendering.photonMarker, PhotonMarker::TopLeft);
}

// ---------------------------------------------------------------------------------------
// Bad input: one sentence naming file, path and reason

// ---------------------------------------------------------------------------------------
// Instructions (format 3)

TEST(ClickInstructions, RoundsOpenWithTheTaskInPlainWordsFromFormat3) {
    Json document = minimal();
    document["format_version"] = 3;
    const ClickProtocol p = parse(document.dump());
    ASSERT_EQ(p.rounds.size(), 2u);
    for (const auto& round : p.rounds) {
        EXPECT_NE(round.instructions.find("Click the green ones"), std::string::npos) << round.instructions;
        EXPECT_NE(round.instructions.find("never click a red one"), std::string::npos) << round.instructions;
    }
    // A round the file lists gets the task alone unless it says otherwise; "" shows none.
    document["matches"]["rounds"] = Json::array({Json{{"name", "a"}}, Json{{"name", "b"}, {"instructions", ""}}});
    const ClickProtocol listed = parse(document.dump());
    EXPECT_EQ(listed.rounds[0].instructions, kClickTaskInstructions);
    EXPECT_EQ(listed.rounds[1].instructions, "");
    // Older files have no screens, whatever their rounds.
    for (int version : {1, 2}) {
        document = minimal();
        document["format_version"] = version;
        for (const auto& round : parse(document.dump()).rounds) EXPECT_EQ(round.instructions, "") << version;
    }
}

TEST(ClickInstructions, OlderFilesMayNotSetThemAndBadTextIsNamed) {
    Json document = minimal();
    document["format_version"] = 2;
    document["matches"]["rounds"] = Json::array({Json{{"name", "a"}, {"instructions", "Go"}}});
    EXPECT_EQ(messageFor(document),
              kPrefix + "matches.rounds[0].instructions is new in format_version 3, but this file is format_version 2");
    document["format_version"] = 3;
    document["matches"]["rounds"][0]["instructions"] = 5;
    EXPECT_EQ(messageFor(document),
              kPrefix +
                  "matches.rounds[0].instructions must be a text of at most 1000 bytes without control characters "
                  "other than line breaks, got 5");
    document["matches"]["rounds"][0]["instructions"] = std::string(1001, 'x');
    EXPECT_NE(messageFor(document).find("matches.rounds[0].instructions must be a text"), std::string::npos);
    document["matches"]["rounds"][0]["instructions"] = "tab\there";
    EXPECT_NE(messageFor(document).find("matches.rounds[0].instructions must be a text"), std::string::npos);
}

TEST(ClickInstructions, AnOlderFileRoundTripsWithoutThem) {
    Json document = minimal();
    document["format_version"] = 2;
    const ClickProtocol p = parse(document.dump());
    const std::string written = toJson(p);
    EXPECT_EQ(written.find("instructions"), std::string::npos) << written;
    expectSame(parse(written), p);
}

// ---------------------------------------------------------------------------------------
// Questions after each match (format 4): the list every game reads the same way

Json likertQuestion() {
    return {{"id", "calm"}, {"kind", "likert"},          {"prompt", "I felt calm"}, {"min", 0},
            {"max", 10},    {"min_label", "not at all"}, {"max_label", "very"}};
}
Json choiceQuestion() {
    return {{"id", "best"},
            {"kind", "choice"},
            {"prompt", "Which looked smoothest?"},
            {"options", {"the first", "the second", "no difference"}}};
}
Json textQuestion() { return {{"id", "notes"}, {"kind", "text"}, {"prompt", "Anything else?"}, {"max_length", 80}}; }

// A format 4 file asking `questions` after each match.
Json withQuestions(const Json& questions) {
    Json document = minimal();
    document["format_version"] = 4;
    document["matches"]["questions"] = questions;
    return document;
}

TEST(ClickQuestions, EachKindParses) {
    const ClickProtocol p = parse(withQuestions({likertQuestion(), choiceQuestion(), textQuestion()}).dump());
    ASSERT_EQ(p.questions.size(), 3u);
    const Question &likert = p.questions[0], &choice = p.questions[1], &text = p.questions[2];
    EXPECT_EQ(likert.id, "calm");
    EXPECT_EQ(likert.kind, QuestionKind::Likert);
    EXPECT_EQ(likert.prompt, "I felt calm");
    EXPECT_EQ(likert.min, 0);
    EXPECT_EQ(likert.max, 10);
    EXPECT_EQ(likert.minLabel, "not at all");
    EXPECT_EQ(likert.maxLabel, "very");
    EXPECT_EQ(choice.id, "best");
    EXPECT_EQ(choice.kind, QuestionKind::Choice);
    EXPECT_EQ(choice.options, (std::vector<std::string>{"the first", "the second", "no difference"}));
    EXPECT_EQ(text.id, "notes");
    EXPECT_EQ(text.kind, QuestionKind::Text);
    EXPECT_EQ(text.maxLength, 80);
}

TEST(ClickQuestions, UnsetKeysTakeTheirDefaults) {
    // A question with only an id and a prompt is a 1-7 Likert statement with the agreement
    // labels; a text question takes a line of up to 200 bytes. Keys may come in any order.
    const ClickProtocol p = parse(
        withQuestions({Json{{"prompt", "Fun"}, {"id", "fun"}},
                       Json{{"options", {"yes", "no"}}, {"prompt", "Again?"}, {"kind", "choice"}, {"id", "again"}},
                       Json{{"id", "why"}, {"kind", "text"}, {"prompt", "Why?"}}})
            .dump());
    ASSERT_EQ(p.questions.size(), 3u);
    EXPECT_EQ(p.questions[0].kind, QuestionKind::Likert);
    EXPECT_EQ(p.questions[0].min, 1);
    EXPECT_EQ(p.questions[0].max, 7);
    EXPECT_EQ(p.questions[0].minLabel, "strongly disagree");
    EXPECT_EQ(p.questions[0].maxLabel, "strongly agree");
    EXPECT_EQ(p.questions[1].options, (std::vector<std::string>{"yes", "no"}));
    EXPECT_EQ(p.questions[2].maxLength, kMaxTextAnswerBytes);
    EXPECT_EQ(kMaxTextAnswerBytes, 200);
    // A label may be left blank: no words under that end of the scale.
    Json blank = likertQuestion();
    blank["min_label"] = "";
    EXPECT_EQ(parse(withQuestions(Json::array({blank})).dump()).questions[0].minLabel, "");
}

TEST(ClickQuestions, TheDefaultIsYangsFourStatementsAndAnEmptyListAsksNothing) {
    Json document = minimal();
    document["format_version"] = 4;
    const ClickProtocol p = parse(document.dump());
    // Yang et al. section 8: four statements rated "from 1 (strongly disagree) to 7 (strongly agree)".
    const std::vector<std::pair<std::string, std::string>> paper{{"enjoyed", "I enjoyed playing this game"},
                                                                 {"difficult", "This game was difficult to play"},
                                                                 {"responsive", "This game was responsive to my input"},
                                                                 {"smooth", "The animation was smooth"}};
    ASSERT_EQ(p.questions.size(), paper.size());
    for (std::size_t i = 0; i < paper.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(p.questions[i].id, paper[i].first);
        EXPECT_EQ(p.questions[i].prompt, paper[i].second);
        EXPECT_EQ(p.questions[i].kind, QuestionKind::Likert);
        EXPECT_EQ(p.questions[i].min, 1);
        EXPECT_EQ(p.questions[i].max, 7);
        EXPECT_EQ(p.questions[i].minLabel, "strongly disagree");
        EXPECT_EQ(p.questions[i].maxLabel, "strongly agree");
    }
    EXPECT_EQ(questionsText(ClickProtocol{}.questions), questionsText(p.questions));
    EXPECT_TRUE(parse(withQuestions(Json::array()).dump()).questions.empty());
}

TEST(ClickQuestions, OlderFilesAskTheirRatingsAsLikertQuestions) {
    Json document = yang3With("/ratings/statements", {"Smooth?", "Quick?"});
    document["ratings"]["min"] = 0;
    document["ratings"]["max"] = 4;
    const ClickProtocol p = parse(document.dump());
    ASSERT_EQ(p.questions.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(p.questions[i].id, "");  // those files named none
        EXPECT_EQ(p.questions[i].kind, QuestionKind::Likert);
        EXPECT_EQ(p.questions[i].prompt, i == 0 ? "Smooth?" : "Quick?");
        EXPECT_EQ(p.questions[i].min, 0);
        EXPECT_EQ(p.questions[i].max, 4);
    }
    // Ratings off: nothing is asked.
    document["ratings"]["enabled"] = false;
    EXPECT_TRUE(parse(document.dump()).questions.empty());
}

TEST(ClickQuestions, AFormat3FileRoundTripsWithItsRatingsAsTheyWere) {
    Json document = yang3With("/ratings/statements", {"Smooth?", "Quick?"});
    document["ratings"]["min"] = -2;
    document["ratings"]["max"] = 2;
    const ClickProtocol p = parse(document.dump());
    const Json written = Json::parse(toJson(p));
    EXPECT_EQ(written.at("format_version"), 3);
    EXPECT_EQ(written.at("ratings"), document.at("ratings"));
    EXPECT_FALSE(written.at("matches").contains("questions")) << written.dump();
    expectSame(parse(written.dump()), p);
}

TEST(ClickQuestions, AFormat4FileRoundTrips) {
    ClickProtocol p = parse(withQuestions({likertQuestion(), choiceQuestion(), textQuestion()}).dump());
    expectSame(parse(toJson(p)), p);
    p.questions.clear();
    const std::string written = toJson(p);
    EXPECT_EQ(Json::parse(written).at("matches").at("questions"), Json::array()) << written;
    expectSame(parse(written), p);
}

TEST(ClickQuestions, EachVersionHasOneOfTheTwo) {
    // matches.questions is new in format 4; the ratings section is gone from it.
    Json document = withQuestions(Json::array({likertQuestion()}));
    document["format_version"] = 3;
    EXPECT_EQ(messageFor(document),
              kPrefix + "matches.questions is new in format_version 4, but this file is format_version 3");
    document = minimal();
    document["format_version"] = 4;
    document["ratings"] = Json{{"enabled", false}};
    EXPECT_EQ(messageFor(document),
              kPrefix +
                  "ratings was replaced by matches.questions in format_version 4, and this file is format_version 4: "
                  "use matches.questions instead");
    // Whatever the section holds, even nothing: it would be read and ignored.
    document["ratings"] = Json::object();
    EXPECT_NE(messageFor(document).find("ratings was replaced by matches.questions"), std::string::npos);
    // A format 3 struct whose questions are not its ratings' cannot be written as format 3:
    // the copy lists them, and reading it back refuses them instead of asking the ratings.
    ClickProtocol p = asFormat({}, 3);
    p.name = "t";
    p.questions.pop_back();
    EXPECT_EQ(messageFor(Json::parse(toJson(p))),
              kPrefix + "matches.questions is new in format_version 4, but this file is format_version 3");
}

TEST(ClickQuestions, BadQuestionsAreNamedByTheirPath) {
    struct Case {
        const char* what;
        std::function<void(Json& questions)> edit;
        const char* expected;  // after the prefix
    };
    const std::vector<Case> cases{
        {"missing id", [](Json& q) { q[1].erase("id"); }, "matches.questions[1].id is required but missing"},
        {"id with a space", [](Json& q) { q[0]["id"] = "no spaces"; },
         "matches.questions[0].id must be 1 to 40 letters, digits and underscores (it names the answers in "
         "answers.csv), got string \"no spaces\""},
        {"empty id", [](Json& q) { q[0]["id"] = ""; },
         "matches.questions[0].id must be 1 to 40 letters, digits and underscores (it names the answers in "
         "answers.csv), got string \"\""},
        {"id of 41", [](Json& q) { q[2]["id"] = std::string(41, 'a'); },
         "matches.questions[2].id must be 1 to 40 letters, digits and underscores (it names the answers in "
         "answers.csv), got string \"aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\""},
        {"id a number", [](Json& q) { q[0]["id"] = 7; },
         "matches.questions[0].id must be 1 to 40 letters, digits and underscores (it names the answers in "
         "answers.csv), got 7"},
        {"duplicate id", [](Json& q) { q[2]["id"] = "calm"; },
         "matches.questions[2].id repeats \"calm\", already matches.questions[0].id"},
        {"unknown kind", [](Json& q) { q[0]["kind"] = "scale"; },
         "matches.questions[0].kind must be \"likert\", \"choice\" or \"text\", got string \"scale\""},
        {"missing prompt", [](Json& q) { q[0].erase("prompt"); },
         "matches.questions[0].prompt is required but missing"},
        {"prompt of two lines", [](Json& q) { q[1]["prompt"] = "a\nb"; },
         "matches.questions[1].prompt must be a non-empty single line of at most 200 bytes, got string \"a\\nb\""},
        {"min = max", [](Json& q) { q[0]["min"] = 10; },
         "matches.questions[0].min must be less than matches.questions[0].max (10), got 10"},
        {"min > max", [](Json& q) { q[0]["min"] = 3, q[0]["max"] = 1; },
         "matches.questions[0].min must be less than matches.questions[0].max (1), got 3"},
        {"too many points", [](Json& q) { q[0]["max"] = 11; },
         "matches.questions[0].max gives the scale 12 answers (0 to 11), more than a scale may offer (11)"},
        {"an end past the limit", [](Json& q) { q[0]["min"] = -101; },
         "matches.questions[0].min must be an integer between -100 and 100, got -101"},
        {"label of two lines", [](Json& q) { q[0]["max_label"] = "a\nb"; },
         "matches.questions[0].max_label must be a single line of at most 200 bytes, got string \"a\\nb\""},
        {"one option", [](Json& q) { q[1]["options"] = Json::array({"only"}); },
         "matches.questions[1].options must list 2 to 9 options (one is no choice; each is answered by its digit "
         "key), got 1"},
        {"no options", [](Json& q) { q[1]["options"] = Json::array(); },
         "matches.questions[1].options must list 2 to 9 options (one is no choice; each is answered by its digit "
         "key), got 0"},
        {"ten options", [](Json& q) { q[1]["options"] = {"1", "2", "3", "4", "5", "6", "7", "8", "9", "10"}; },
         "matches.questions[1].options must list 2 to 9 options (one is no choice; each is answered by its digit "
         "key), got 10"},
        {"duplicate options", [](Json& q) { q[1]["options"][2] = "the first"; },
         "matches.questions[1].options[2] repeats \"the first\", already matches.questions[1].options[0]"},
        {"an empty option", [](Json& q) { q[1]["options"][1] = ""; },
         "matches.questions[1].options[1] must be a non-empty single line of at most 200 bytes, got string \"\""},
        {"a choice without options", [](Json& q) { q[1].erase("options"); },
         "matches.questions[1].options is required for a choice question but missing"},
        {"max_length 0", [](Json& q) { q[2]["max_length"] = 0; },
         "matches.questions[2].max_length must be an integer between 1 and 200, got 0"},
        {"max_length 201", [](Json& q) { q[2]["max_length"] = 201; },
         "matches.questions[2].max_length must be an integer between 1 and 200, got 201"},
        {"options in a Likert question",
         [](Json& q) {
             q[0]["options"] = {"a", "b"};
         },
         "matches.questions[0].options is only for a choice question; this one is likert"},
        {"options where the kind is left to its default",
         [](Json& q) {
             q[0].erase("kind");
             q[0]["options"] = {"a", "b"};
         },
         "matches.questions[0].options is only for a choice question; this one is likert"},
        {"a scale end in a text question", [](Json& q) { q[2]["min"] = 1; },
         "matches.questions[2].min is only for a likert question; this one is text"},
        {"max_length in a choice question", [](Json& q) { q[1]["max_length"] = 5; },
         "matches.questions[1].max_length is only for a text question; this one is choice"},
        {"a label in a choice question", [](Json& q) { q[1]["min_label"] = "no"; },
         "matches.questions[1].min_label is only for a likert question; this one is choice"},
        {"unknown key", [](Json& q) { q[0]["scale"] = 7; },
         "matches.questions[0].scale is not a known field (matches.questions[0] may have id, kind, prompt, min, max, "
         "min_label, max_label, options, max_length)"},
        {"not an object", [](Json& q) { q[1] = "best"; },
         "matches.questions[1] must be an object, got string \"best\""},
        {"not an array", [](Json& q) { q = "calm"; },
         "matches.questions must be an array of questions, got string \"calm\""},
        {"21 questions",
         [](Json& q) {
             q = Json::array();
             for (int i = 0; i < 21; ++i) q.push_back(Json{{"id", "q" + std::to_string(i)}, {"prompt", "P"}});
         },
         "matches.questions lists 21 questions, more than a list asked after every block may (20)"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        Json questions = {likertQuestion(), choiceQuestion(), textQuestion()};
        c.edit(questions);
        EXPECT_EQ(messageFor(withQuestions(questions)), kPrefix + c.expected);
    }
}

TEST(ClickQuestions, EachLimitItselfIsAllowed) {
    Json questions = Json::array();
    for (int i = 0; i < kMaxQuestions; ++i) questions.push_back(Json{{"id", "q" + std::to_string(i)}, {"prompt", "P"}});
    EXPECT_EQ(parse(withQuestions(questions).dump()).questions.size(), 20u);
    Json q = likertQuestion();
    q["min"] = 90, q["max"] = 100;  // 11 answers, at the limit of an end
    q["min_label"] = std::string(200, 'x');
    EXPECT_EQ(messageFor(withQuestions(Json::array({q}))), "");
    q = choiceQuestion();
    q["options"] = {"1", "2", "3", "4", "5", "6", "7", "8", "9"};
    q["id"] = std::string(40, '_');
    EXPECT_EQ(messageFor(withQuestions(Json::array({q}))), "");
    q = textQuestion();
    q["max_length"] = 200;
    EXPECT_EQ(messageFor(withQuestions(Json::array({q}))), "");
    q["max_length"] = 1;
    EXPECT_EQ(messageFor(withQuestions(Json::array({q}))), "");
}

TEST(ClickErrors, NegativeGravity) {
    EXPECT_EQ(messageFor(yangWith("/physics/gravity_m_per_s2", -9.81)),
              kPrefix + "physics.gravity_m_per_s2 must be a number between 0 and 100, got -9.81");
    EXPECT_EQ(parse(yangWith("/physics/gravity_m_per_s2", 0).dump()).gravity, 0.0);
}

TEST(ClickErrors, ZeroMatches) {
    EXPECT_EQ(messageFor(yangWith("/matches/rounds/1/matches_per_condition", 0)),
              kPrefix +
                  "matches.rounds[1].matches_per_condition must be an integer between 1 and 100, "
                  "got 0");
    EXPECT_EQ(messageFor(yangWith("/matches/rounds", Json::array())),
              kPrefix + "matches.rounds must be a non-empty array of rounds, got array []");
    // Rounds that are all practice record nothing to analyse.
    EXPECT_EQ(messageFor(yangWith("/matches/rounds/1/scored", false)),
              kPrefix +
                  "matches.rounds must have at least one round with \"scored\": true, or "
                  "the session measures nothing");
    EXPECT_EQ(messageFor(yangWith("/matches/match_s", 0)),
              kPrefix + "matches.match_s must be a number greater than 0 and at most 300, got 0");
}

// The reason after the path is the condition table's own: the presets have one home.
std::string conditionError(const std::string& where, const std::string& id, double refreshHz) {
    return kPrefix + where + " is \"" + id + "\": " + condition::ConditionTable().check(id, refreshHz);
}

TEST(ClickErrors, UnknownCondition) {
    const std::string message = messageFor(yangWith("/matches/conditions/2", "conv25"));
    EXPECT_EQ(message, conditionError("matches.conditions[2]", "conv25", 60));
    EXPECT_NE(message.find("unknown condition 'conv25'"), std::string::npos) << message;
    EXPECT_EQ(messageFor(yangWith("/matches/conditions/0", 60)),
              kPrefix + "matches.conditions[0] must be a condition id (a string), got 60");
    EXPECT_EQ(messageFor(yangWith("/matches/conditions", Json::array())),
              kPrefix + "matches.conditions must be a non-empty array of condition ids, got array []");
}

TEST(ClickErrors, ConditionThatCannotRunAtTheRefresh) {
    const std::string message = messageFor(yangWith("/matches/conditions/3", "conv120"));
    EXPECT_EQ(message, conditionError("matches.conditions[3]", "conv120", 60));
    EXPECT_NE(message.find("above the refresh (60 Hz)"), std::string::npos) << message;
    // The defaults are checked too: the published conditions need a multiple of 60 Hz.
    Json document = minimal();
    document["display"] = Json{{"refresh_hz", 50}};
    document["physics"] = Json{{"step_rate_hz", 1000}};
    EXPECT_EQ(messageFor(document), conditionError("matches.modes[0]", "conv60", 50));
    // 120 Hz runs everything the study names, and conv120 too.
    document = yangWith("/display/refresh_hz", 120);
    document["matches"]["conditions"].push_back("conv120");
    EXPECT_EQ(parse(document.dump()).conditions.size(), 8u);
}

// Format 7 renamed the keys that name conditions for them (matches.modes is matches.conditions);
// older files keep their names, so that their sessions replay, and a study plan writes a
// participant's order under the name the file has.
TEST(ClickVersions, Format7NamesTheKeysThatNameConditions) {
    ClickProtocol p;
    p.name = "t";
    p.conditions = {"conv30", "lag100"};
    p.rounds[0].matchesPerCondition = 3;
    p.formatVersion = 6;
    const Json before = Json::parse(toJson(p));
    EXPECT_EQ(before["matches"]["modes"], Json({"conv30", "lag100"}));
    EXPECT_EQ(before["matches"]["rounds"][0]["matches_per_mode"], 3);
    EXPECT_FALSE(before["matches"].contains("conditions"));
    EXPECT_FALSE(before["matches"]["rounds"][0].contains("matches_per_condition"));
    expectSame(parse(before.dump()), p);

    p.formatVersion = 7;
    const Json after = Json::parse(toJson(p));
    EXPECT_EQ(after["matches"]["conditions"], Json({"conv30", "lag100"}));
    EXPECT_EQ(after["matches"]["rounds"][0]["matches_per_condition"], 3);
    EXPECT_FALSE(after["matches"].contains("modes"));
    EXPECT_FALSE(after["matches"]["rounds"][0].contains("matches_per_mode"));
    expectSame(parse(after.dump()), p);

    // Each name in the other version's file is refused, naming what to write.
    Json stale = after;
    stale["matches"]["modes"] = stale["matches"]["conditions"];
    stale["matches"].erase("conditions");
    EXPECT_EQ(messageFor(stale),
              kPrefix +
                  "matches.modes was renamed conditions in format_version 7, and this file is "
                  "format_version 7: use matches.conditions instead");
    Json early = before;
    early["matches"]["rounds"][0]["matches_per_condition"] = 3;
    early["matches"]["rounds"][0].erase("matches_per_mode");
    EXPECT_EQ(messageFor(early),
              kPrefix +
                  "matches.rounds[0].matches_per_condition is new in format_version 7, but "
                  "this file is format_version 6");
    // A message about an older file's list names the file's key.
    early = before;
    early["matches"]["modes"][1] = "conv120";
    EXPECT_EQ(messageFor(early), conditionError("matches.modes[1]", "conv120", 60));

    // A participant's condition order goes where the file keeps its list.
    for (const Json& file : {before, after}) {
        const std::string key = file["format_version"] == 6 ? "modes" : "conditions";
        const auto study = game::parseStudy(file.dump(), kSource);
        const Json ordered = Json::parse(study->withConditionOrder(file.dump(), {"lag100", "conv30"}));
        EXPECT_EQ(ordered["matches"][key], Json({"lag100", "conv30"})) << key;
        EXPECT_EQ(parse(ordered.dump()).conditions, (std::vector<std::string>{"lag100", "conv30"})) << key;
    }
}

TEST(ClickErrors, DuplicateConditions) {
    EXPECT_EQ(messageFor(yangWith("/matches/conditions/3", "conv60")),
              kPrefix + "matches.conditions[3] repeats \"conv60\", already matches.conditions[0]");
}

// A format 3 file's ratings section, as its sessions were recorded with.
TEST(ClickErrors, MissingOrEmptyRatingText) {
    const std::string rule = " must be a non-empty single line of at most 200 bytes, got ";
    EXPECT_EQ(messageFor(yang3With("/ratings/statements/1", "")),
              kPrefix + "ratings.statements[1]" + rule + "string \"\"");
    EXPECT_EQ(messageFor(yang3With("/ratings/statements/0", nullptr)),
              kPrefix + "ratings.statements[0]" + rule + "null");
    EXPECT_EQ(messageFor(yang3With("/ratings/statements/2", "two\nlines")),
              kPrefix + "ratings.statements[2]" + rule + "string \"two\\nlines\"");
    EXPECT_EQ(messageFor(yang3With("/ratings/statements", Json::array())),
              kPrefix +
                  "ratings.statements must list at least one statement while "
                  "ratings.enabled is true");
    EXPECT_EQ(messageFor(yang3With("/ratings/statements", "I enjoyed playing this game")),
              kPrefix +
                  "ratings.statements must be an array of statements, got string \"I "
                  "enjoyed playing this game\"");
    EXPECT_EQ(messageFor(yang3With("/ratings/statements/3", "This game was difficult to play")),
              kPrefix +
                  "ratings.statements[3] repeats \"This game was difficult to play\", "
                  "already ratings.statements[1]");
    // No statements is fine when nothing is asked.
    Json document = yang3With("/ratings/statements", Json::array());
    document["ratings"]["enabled"] = false;
    EXPECT_TRUE(parse(document.dump()).ratingStatements.empty());
}

TEST(ClickErrors, RatingMinMustBeBelowMax) {
    Json document = yang3With("/ratings/min", 7);
    EXPECT_EQ(messageFor(document), kPrefix + "ratings.min must be less than ratings.max (7), got 7");
    document["ratings"]["max"] = 3;
    EXPECT_EQ(messageFor(document), kPrefix + "ratings.min must be less than ratings.max (3), got 7");
    EXPECT_EQ(messageFor(yang3With("/ratings/max", 101)),
              kPrefix + "ratings.max must be an integer between -100 and 100, got 101");
    document = yang3With("/ratings/min", -3);
    document["ratings"]["max"] = 3;
    EXPECT_EQ(parse(document.dump()).ratingMin, -3);
    EXPECT_EQ(messageFor(yang3With("/ratings/enabled", "yes")),
              kPrefix + "ratings.enabled must be true or false, got string \"yes\"");
}

TEST(ClickErrors, StepRateTheRefreshDoesNotDivide) {
    EXPECT_EQ(messageFor(yangWith("/physics/step_rate_hz", 1000)),
              kPrefix +
                  "physics.step_rate_hz must be a whole multiple of display.refresh_hz (60), "
                  "got 1000");
    EXPECT_EQ(messageFor(yangWith("/physics/step_rate_hz", 30)),
              kPrefix +
                  "physics.step_rate_hz must be a whole multiple of display.refresh_hz (60), "
                  "got 30");
    // 960 Hz divides into 60 and 120 Hz frames alike; 144 Hz needs its own step rate.
    EXPECT_NO_THROW(parse(yangWith("/display/refresh_hz", 120).dump()));
    Json document = yangWith("/display/refresh_hz", 144);
    EXPECT_EQ(messageFor(document),
              kPrefix +
                  "physics.step_rate_hz must be a whole multiple of display.refresh_hz "
                  "(144), got 960");
    EXPECT_EQ(messageFor(yangWith("/physics/step_rate_hz", 960.0)),
              kPrefix + "physics.step_rate_hz must be an integer between 1 and 100000, got 960.0");
}

TEST(ClickErrors, WrongGame) {
    EXPECT_EQ(messageFor(yangWith("/game", "shooter")),
              kPrefix + "game must be \"click\" for a click protocol, got string \"shooter\"");
    // And the other way round: a click file is refused by the shooter parser, not half-read.
    try {
        parseShooterProtocol(yangWith("/name", "c").dump(), kSource);
        ADD_FAILURE() << "expected a ProtocolError";
    } catch (const ProtocolError& e) {
        EXPECT_EQ(std::string(e.what()),
                  kPrefix + "game must be \"shooter\" for a shooter protocol, got string \"click\"");
    }
}

// The loader picks the parser by "game", so a file of one game carrying the other's name fails
// in a parser that blames a field or the format_version (a shooter file's format_version 3 is
// newer than any click protocol). The field that is wrong is "game", and the refusal says so.
TEST(ClickErrors, AFileOfTheOtherGameUnderThisNameBlamesTheGameField) {
    struct Case {
        const char* file;
        const char* named;  // the "game" written into it
        const char* expected;  // after the prefix
    };
    const std::vector<Case> cases{
        {"latewarp-kim.json", "click",
         "game is \"click\", but format_version 3 and the other fields are a shooter protocol's (the file reads "
         "as one with \"game\": \"shooter\")"},
        {"shooter-quick.json", "click",
         "game is \"click\", but format_version 2 and the other fields are a shooter protocol's (the file reads "
         "as one with \"game\": \"shooter\")"},
        {"click-yang.json", "shooter",
         "game is \"shooter\", but format_version 1 and the other fields are a click protocol's (the file reads "
         "as one with \"game\": \"click\")"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.file);
        Json document = Json::parse(readProtocolFile(protocolDir() + "/" + c.file));
        document["game"] = c.named;
        try {
            game::parseStudy(document.dump(), kSource);
            ADD_FAILURE() << "expected a ProtocolError";
        } catch (const ProtocolError& e) {
            EXPECT_EQ(std::string(e.what()), kPrefix + c.expected);
        }
    }
    // A click file newer than this build is still just that, with or without fields of its own:
    // a bare header is any game's, and a newer click file's sections are no shooter's.
    for (const Json& newer :
         {Json{{"format_version", 8}, {"name", "t"}, {"game", "click"}}, yangWith("/format_version", 8)}) {
        try {
            game::parseStudy(newer.dump(), kSource);
            ADD_FAILURE() << "expected a ProtocolError";
        } catch (const ProtocolError& e) {
            EXPECT_EQ(std::string(e.what()), kPrefix + "format_version 8 is newer than this warplab supports (7)");
        }
    }
}

TEST(ClickErrors, RoundsAreChecked) {
    EXPECT_EQ(messageFor(yangWith("/matches/rounds/1", "scored")),
              kPrefix + "matches.rounds[1] must be an object, got string \"scored\"");
    EXPECT_EQ(messageFor(yangWith("/matches/rounds/0", Json{{"scored", false}})),
              kPrefix + "matches.rounds[0].name is required but missing");
    EXPECT_EQ(messageFor(yangWith("/matches/rounds/0/matches", 1)),
              kPrefix +
                  "matches.rounds[0].matches is not a known field (matches.rounds[0] may "
                  "have name, scored, matches_per_condition, instructions)");
    EXPECT_EQ(messageFor(yangWith("/matches/rounds/1/name", "practice")),
              kPrefix + "matches.rounds[1].name repeats \"practice\", already matches.rounds[0].name");
    EXPECT_EQ(messageFor(yangWith("/matches/rounds/1/scored", "yes")),
              kPrefix + "matches.rounds[1].scored must be true or false, got string \"yes\"");
}

TEST(ClickErrors, OutOfRangeValuesNameTheRange) {
    struct Case {
        const char* pointer;
        Json value;
        const char* expected;  // after the prefix
    };
    const std::vector<Case> cases{
        {"/display/refresh_hz", 0, "display.refresh_hz must be a number between 1 and 1000, got 0"},
        {"/display/vertical_fov_deg", 180, "display.vertical_fov_deg must be a number between 1 and 179, got 180"},
        {"/display/camera_pitch_deg", -90, "display.camera_pitch_deg must be a number between -89 and 89, got -90"},
        {"/physics/sphere_radius_m", 0, "physics.sphere_radius_m must be a number between 0.01 and 1.8, got 0"},
        {"/physics/sphere_radius_m", 2.5, "physics.sphere_radius_m must be a number between 0.01 and 1.8, got 2.5"},
        // 1.9 and up never fit the 3.8 m deep box: refused here, not by the physics later.
        {"/physics/sphere_radius_m", 1.9, "physics.sphere_radius_m must be a number between 0.01 and 1.8, got 1.9"},
        {"/physics/restitution", 1.1, "physics.restitution must be a number between 0 and 1, got 1.1"},
        {"/physics/sphere_count", 0, "physics.sphere_count must be an integer between 1 and 40, got 0"},
        {"/physics/sphere_count", 41, "physics.sphere_count must be an integer between 1 and 40, got 41"},
        {"/physics/green_share", -0.1, "physics.green_share must be a number between 0 and 1, got -0.1"},
        {"/physics/spawn_delay_s", -1, "physics.spawn_delay_s must be a number between 0 and 60, got -1"},
        {"/physics/spawn_speed_m_per_s", -2.0,
         "physics.spawn_speed_m_per_s must be a number between 0 and 100, got -2.0"},
        {"/physics/step_rate_hz", 0, "physics.step_rate_hz must be an integer between 1 and 100000, got 0"},
        {"/input/cursor_pixels_per_count", 0,
         "input.cursor_pixels_per_count must be a number between 0.001 and 100, got 0"},
        {"/input/click_timing", "frame",
         "input.click_timing must be \"display\" or \"input_reads\", got string \"frame\""},
        {"/matches/scoring", "both", "matches.scoring must be \"world\" or \"displayed\", got string \"both\""},
        {"/matches/shuffle", 1, "matches.shuffle must be true or false, got 1"},
        {"/physics/gravity", 9.81,
         "physics.gravity is not a known field (physics may have gravity_m_per_s2, sphere_radius_m, "
         "restitution, step_rate_hz, sphere_count, green_share, spawn_delay_s, spawn_speed_m_per_s)"},
        {"/format_version", 8, "format_version 8 is newer than this warplab supports (7)"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.pointer);
        EXPECT_EQ(messageFor(yangWith(c.pointer, c.value)), kPrefix + c.expected);
    }
}

// ---------------------------------------------------------------------------------------
// Limits that keep a session's data safe (docs/protocol.md): each bound itself is accepted,
// the next double past it is refused with the exact sentence.

struct Bound {
    const char* pointer;
    double bound;  // allowed
    double past;  // the next double beyond it: refused
    const char* expected;  // after the prefix
};

void expectBounds(const std::vector<Bound>& bounds) {
    for (const Bound& b : bounds) {
        SCOPED_TRACE(b.pointer);
        EXPECT_EQ(messageFor(yangWith(b.pointer, b.bound)), "");
        EXPECT_EQ(messageFor(yangWith(b.pointer, b.past)), kPrefix + b.expected);
    }
}

double above(double bound) { return std::nextafter(bound, INFINITY); }
double below(double bound) { return std::nextafter(bound, -INFINITY); }

TEST(ClickLimits, NoMatchRunsPastItsBound) {
    // A match is committed when it starts and when it ends: one match is the longest stretch
    // of frames a session holds in memory, 300000 at the 1000 Hz ceiling.
    expectBounds({
        {"/matches/match_s", 300, above(300),
         "matches.match_s must be a number greater than 0 and at most 300, got 300.00000000000006"},
        {"/physics/spawn_delay_s", 60, above(60),
         "physics.spawn_delay_s must be a number between 0 and 60, got 60.00000000000001"},
    });
    // A day-long match, which the old limit allowed: 5.2 million frames uncommitted at 60 Hz.
    EXPECT_EQ(messageFor(yangWith("/matches/match_s", 86400)),
              kPrefix + "matches.match_s must be a number greater than 0 and at most 300, got 86400");
}

TEST(ClickLimits, TinyPositiveValuesThatBreakLaterMathsAreRefused) {
    // At 1e-310 pixels a count the cursor could not move and the bot never finished a session;
    // a subnormal radius was a float 0 on screen, spheres no click could hit.
    EXPECT_EQ(messageFor(yangWith("/input/cursor_pixels_per_count", 1e-310)),
              kPrefix + "input.cursor_pixels_per_count must be a number between 0.001 and 100, got 1e-310");
    EXPECT_EQ(messageFor(yangWith("/physics/sphere_radius_m", 1e-310)),
              kPrefix + "physics.sphere_radius_m must be a number between 0.01 and 1.8, got 1e-310");
    expectBounds({
        {"/input/cursor_pixels_per_count", 0.001, below(0.001),
         "input.cursor_pixels_per_count must be a number between 0.001 and 100, got "
         "0.0009999999999999998"},
        {"/physics/sphere_radius_m", 0.01, below(0.01),
         "physics.sphere_radius_m must be a number between 0.01 and 1.8, got 0.009999999999999998"},
    });
}

TEST(ClickLimits, CameraLimitsAreTheSharedOnes) {
    // The same field-of-view and pitch limits as the shooter and `warplab render`.
    expectBounds({
        {"/display/vertical_fov_deg", kMaxVerticalFovDeg, above(kMaxVerticalFovDeg),
         "display.vertical_fov_deg must be a number between 1 and 179, got 179.00000000000003"},
        {"/display/camera_pitch_deg", kMaxCameraPitchDeg, above(kMaxCameraPitchDeg),
         "display.camera_pitch_deg must be a number between -89 and 89, got 89.00000000000001"},
        {"/display/camera_pitch_deg", -kMaxCameraPitchDeg, below(-kMaxCameraPitchDeg),
         "display.camera_pitch_deg must be a number between -89 and 89, got -89.00000000000001"},
    });
}

// ---------------------------------------------------------------------------------------
// The shared loader

std::string gameError(const std::string& text) {
    try {
        protocolGame(text, kSource);
    } catch (const ProtocolError& e) {
        return e.what();
    }
    return "";
}

TEST(SharedLoader, GamePicksTheParser) {
    EXPECT_EQ(protocolGame(readProtocolFile(protocolDir() + "/click-yang.json"), kSource), "click");
    EXPECT_EQ(protocolGame(readProtocolFile(protocolDir() + "/shooter-thesis.json"), kSource), "shooter");
    // The loader only reads the field; which games exist is the caller's business.
    EXPECT_EQ(protocolGame(R"({"game": "pong", "anything": [1, 2]})", kSource), "pong");
}

TEST(SharedLoader, GameErrorsNameTheFile) {
    const std::string malformed = gameError("{\n  \"game\": \"click\",\n}\n");
    EXPECT_EQ(malformed.rfind(kPrefix + "malformed JSON at line 3, column 1", 0), 0u) << malformed;
    EXPECT_EQ(malformed.find('\n'), std::string::npos) << malformed;
    EXPECT_EQ(gameError("[\"click\"]"), kPrefix + "the top level must be a JSON object, got array [\"click\"]");
    EXPECT_EQ(gameError(R"({"format_version": 1})"), kPrefix + "game is required but missing");
    EXPECT_EQ(gameError(R"({"game": 2})"), kPrefix + "game must be a string, got 2");
    EXPECT_EQ(gameError(R"({"game": "click", "game": "shooter"})"), kPrefix + "game appears more than once");
}

TEST(SharedLoader, ReadingAFileNamesThePath) {
    const std::string missing = std::string(WARPLAB_BINARY_DIR) + "/no-such-dir/missing.json";
    try {
        readProtocolFile(missing);
        ADD_FAILURE() << "expected a ProtocolError";
    } catch (const ProtocolError& e) {
        EXPECT_EQ(std::string(e.what()), "protocol '" + missing + "': no such file");
    }
    try {
        loadClickProtocol(protocolDir());
        ADD_FAILURE() << "expected a ProtocolError";
    } catch (const ProtocolError& e) {
        EXPECT_EQ(std::string(e.what()), "protocol '" + protocolDir() + "': is a directory, not a file");
    }
}

// ============================ the documented keys ============================

// The page a researcher writes a protocol from is the contract: it documents exactly the keys
// the parsers' tables read, in the same order.
TEST(ProtocolDocs, EveryKeyOfEachGameIsDocumentedInOrder) {
    const std::string page = std::string(WARPLAB_SOURCE_DIR) + "/docs/protocol.md";
    EXPECT_EQ(documentedKeys(page, "# The bouncing-target shooter"), shooterProtocolKeys());
    EXPECT_EQ(documentedKeys(page, "# The falling-sphere click game"), clickProtocolKeys());
}

}  // namespace
}  // namespace warplab::protocol
