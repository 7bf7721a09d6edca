#include "click/click_protocol.h"

#include "protocol/fields.h"
#include "protocol/questions_json.h"

namespace warplab::protocol {
namespace {

using fields::elementPath;
using fields::formatNumber;
using fields::joinPath;
using fields::Json;
using fields::kCommitStretchLimitS;
using fields::kRefreshLimitHz;
using fields::NumberRange;

// Bounds that no study needs to exceed (protocol/fields.h says why they exist).
constexpr double kGravityLimit = 100;  // about 10 g
// m: below half the smallest side of the physics box (physics::SphereBox, 3.8 m deep), which
// refused every radius from 1.9 up whatever the other fields said.
constexpr double kRadiusLimit = 1.8;
constexpr int kStepRateLimit = 100000;  // Hz
constexpr int kSphereLimit = 40;
constexpr double kSpeedLimit = 100;  // m/s
constexpr double kCursorPerCountLimit = 100;
constexpr int kMatchesPerConditionLimit = 100;
// Positive is not enough where a tiny value breaks later maths. 1 cm, a 45th of the default
// radius, is still drawn; a subnormal radius became a float 0, spheres no click could hit.
constexpr double kRadiusMin = 0.01;
// 0.001 pixels a count still crosses a 1920-pixel screen in 49 cm of hand travel at 100000
// CPI; at 1e-310 the cursor could not move and the bot, dividing by it, never finished.
constexpr double kCursorPerCountMin = 0.001;
// Durations (docs/protocol.md, "Limits that keep a session's data safe"). A match is committed
// when it starts and when it ends, so one match is the longest stretch of frames held.
constexpr double kMatchLimitS = kCommitStretchLimitS;  // 5 minutes, 6.7 times the paper's 45 s
constexpr double kSpawnDelayLimitS = 60;  // 120 times the default 0.5 s

using P = ClickProtocol;
using K = fields::Keys<P>;
using fields::at;

// The keys of each element of matches.rounds. "name" is required.
const std::vector<fields::Key<ClickRound>>& roundKeys() {
    using R = ClickRound;
    static const std::vector<fields::Key<R>> keys = [] {
        fields::Key<R> name = fields::Keys<R>::make(
            "name", at(&R::name), [](const fields::Reader& r, const Json* item, const std::string& where, R& round) {
                if (!item->contains("name")) r.fail(joinPath(where, "name"), "is required but missing");
                round.name = r.line(item->at("name"), joinPath(where, "name"));
            });
        return std::vector<fields::Key<R>>{
            name,
            fields::Keys<R>::boolean("scored", at(&R::scored)),
            fields::Keys<R>::integer("matches_per_mode", at(&R::matchesPerCondition), 1, kMatchesPerConditionLimit)
                .renamed(kClickConditionKeysSince, "matches_per_condition"),
            fields::Keys<R>::integer("matches_per_condition", at(&R::matchesPerCondition), 1, kMatchesPerConditionLimit)
                .renames(kClickConditionKeysSince),
            fields::instructionsKey<R>(at(&R::instructions), kClickInstructionsSince),
        };
    }();
    return keys;
}

void readRounds(const fields::Reader& r, const Json* matches, const std::string& path, P& p) {
    const Json* rounds = r.array(matches, path, "rounds", "rounds");
    if (!rounds) return;
    std::vector<ClickRound> read;
    std::vector<std::string> names;
    for (std::size_t i = 0; i < rounds->size(); ++i) {
        const Json& item = (*rounds)[i];
        const std::string where = elementPath("matches.rounds", i);
        if (!item.is_object()) r.fail(where, "must be an object, got " + fields::describe(item));
        ClickRound round;
        fields::readKeys(r, item, where, roundKeys(), p.formatVersion, round);
        names.push_back(round.name);
        read.push_back(round);
    }
    r.requireDistinct(names, [](std::size_t i) { return elementPath("matches.rounds", i) + ".name"; });
    p.rounds = std::move(read);
}

void writeRounds(Json& matches, const P& p) {
    matches["rounds"] = Json::array();
    for (const ClickRound& round : p.rounds) {
        Json item = Json::object();
        fields::writeKeys(item, roundKeys(), p.formatVersion, round);
        matches["rounds"].push_back(item);
    }
}

void readStatements(const fields::Reader& r, const Json* ratings, const std::string& path, P& p) {
    // May be empty, but only with ratings off (checked once both are final).
    const Json* statements = r.array(ratings, path, "statements", "statements", true);
    if (!statements) return;
    std::vector<std::string> read;
    for (std::size_t i = 0; i < statements->size(); ++i)
        read.push_back(r.line((*statements)[i], elementPath("ratings.statements", i)));
    r.requireDistinct(read, [](std::size_t i) { return elementPath("ratings.statements", i); });
    p.ratingStatements = std::move(read);
}

// What a file older than format 4 asks after each match: its ratings section's statements as
// Likert questions on its one scale, without ids (those files had none), nothing while disabled.
std::vector<Question> ratingsAsQuestions(const P& p) {
    std::vector<Question> questions;
    if (p.ratingsEnabled)
        for (const std::string& statement : p.ratingStatements) {
            Question q;
            q.prompt = statement;
            q.min = p.ratingMin;
            q.max = p.ratingMax;
            questions.push_back(q);
        }
    return questions;
}

// matches.questions, new in format 4. An older struct's questions are its ratings', which the
// ratings section already writes; where they are not, the key is written so that parsing the
// copy refuses it rather than asking what the ratings say.
fields::Key<P> matchQuestionsKey() {
    fields::Key<P> k = fields::questionsKey<P>(at(&P::questions), kClickQuestionsSince);
    k.isDefault = [](const P& p) { return p.questions == ratingsAsQuestions(p); };
    return k;
}

// Every key of a click protocol below the top level, once (docs/protocol.md lists each).
const std::vector<fields::Section<P>>& sections() {
    static const std::vector<fields::Section<P>> list = [] {
        std::vector<fields::Key<P>> display = {
            K::number("refresh_hz", at(&P::refreshHz), {1, false, kRefreshLimitHz, false}),
            K::number("vertical_fov_deg", at(&P::verticalFovDeg),
                      {kMinVerticalFovDeg, false, kMaxVerticalFovDeg, false}),
            K::number("camera_pitch_deg", at(&P::cameraPitchDeg),
                      {-kMaxCameraPitchDeg, false, kMaxCameraPitchDeg, false}),
            K::choice("refresh_mismatch", at(&P::refreshMismatch)),
        };
        for (auto& k : fields::renderKeys<P>(kClickPhotonMarkerSince)) display.push_back(k);
        return std::vector<fields::Section<P>>{
            {"display", display},
            {"physics",
             {K::number("gravity_m_per_s2", at(&P::gravity), {0, false, kGravityLimit, false}),
              K::number("sphere_radius_m", at(&P::sphereRadius), {kRadiusMin, false, kRadiusLimit, false}),
              K::number("restitution", at(&P::restitution), {0, false, 1, false}),
              K::integer("step_rate_hz", at(&P::stepRateHz), 1, kStepRateLimit),
              K::integer("sphere_count", at(&P::sphereCount), 1, kSphereLimit),
              K::number("green_share", at(&P::greenShare), {0, false, 1, false}),
              K::number("spawn_delay_s", at(&P::spawnDelayS), {0, false, kSpawnDelayLimitS, false}),
              K::number("spawn_speed_m_per_s", at(&P::spawnSpeedMPerS), {0, false, kSpeedLimit, false})}},
            {"input",
             {K::number("cursor_pixels_per_count", at(&P::cursorPixelsPerCount),
                        {kCursorPerCountMin, false, kCursorPerCountLimit, false}),
              K::choice("click_timing", at(&P::clickTiming))}},
            {"matches",
             {K::number("match_s", at(&P::matchS), {0, true, kMatchLimitS, false}),
              K::conditionList("modes", at(&P::conditions)).renamed(kClickConditionKeysSince, "conditions"),
              K::conditionList("conditions", at(&P::conditions)).renames(kClickConditionKeysSince),
              K::custom("rounds", readRounds, writeRounds), K::boolean("shuffle", at(&P::shuffle)),
              K::choice("scoring", at(&P::scoring)), matchQuestionsKey()}},
            fields::Section<P>{"ratings",
                               {K::boolean("enabled", at(&P::ratingsEnabled)),
                                K::custom("statements", readStatements,
                                          [](Json& o, const P& p) { o["statements"] = p.ratingStatements; }),
                                K::integer("min", at(&P::ratingMin), -kScaleLimit, kScaleLimit),
                                K::integer("max", at(&P::ratingMax), -kScaleLimit, kScaleLimit)}}
                .replaced(kClickQuestionsSince, "matches.questions"),
        };
    }();
    return list;
}

}  // namespace

std::vector<std::string> clickProtocolKeys() {
    return fields::keyPaths(
        sections(),
        {{"matches.rounds", fields::keyNames(roundKeys())}, {"matches.questions", fields::questionKeyNames()}});
}

ClickProtocol parseClickProtocol(const std::string& jsonText, const std::string& sourceName) {
    fields::Reader r(sourceName);
    const Json document = r.parseObject(jsonText);
    ClickProtocol p;
    r.requireGame(document, "click");
    p.formatVersion = r.formatVersion(document, kClickFormatVersion);
    r.requireKnownKeys(document, "", fields::topLevelKeys(sections()));
    r.nameAndDescription(document, p.name, p.description);
    p.conditionTable =
        condition::ConditionTable(r.conditions(document, p.formatVersion, kClickConditionsSince, kClickPacingSince));
    fields::readSections(r, document, sections(), p.formatVersion, p);
    if (p.formatVersion < kClickInstructionsSince)
        for (ClickRound& round : p.rounds) round.instructions.clear();
    if (p.formatVersion < kClickQuestionsSince) p.questions = ratingsAsQuestions(p);

    // Relations between fields, checked once every field holds its final value.
    if (!condition::wholeRatio(p.stepRateHz, p.refreshHz))
        r.fail("physics.step_rate_hz",
               "must be a whole multiple of display.refresh_hz (" + formatNumber(p.refreshHz) + "), got " +
                   formatNumber(p.stepRateHz));
    bool anyScored = false;
    for (const ClickRound& round : p.rounds) anyScored = anyScored || round.scored;
    if (!anyScored)
        r.fail("matches.rounds",
               "must have at least one round with \"scored\": true, or the "
               "session measures nothing");
    if (p.ratingsEnabled && p.ratingStatements.empty())
        r.fail("ratings.statements", "must list at least one statement while ratings.enabled is true");
    if (p.ratingMin >= p.ratingMax)
        r.fail(
            "ratings.min",
            "must be less than ratings.max (" + std::to_string(p.ratingMax) + "), got " + std::to_string(p.ratingMin));
    r.requireConditionsRun(p.refreshHz);
    r.requireConditions(joinPath("matches", conditionListKey(p.formatVersion)), p.conditions, p.refreshHz);
    r.requireConditionsUsed();
    return p;
}

std::string conditionListKey(int formatVersion) {
    for (const auto& s : sections())
        if (std::string(s.name) == "matches") return fields::keyNameIn(s.keys, "conditions", formatVersion);
    return "conditions";
}

ClickProtocol loadClickProtocol(const std::string& path) { return parseClickProtocol(readProtocolFile(path), path); }

std::string toJson(const ClickProtocol& p) { return fields::protocolText(p, sections()); }

}  // namespace warplab::protocol
