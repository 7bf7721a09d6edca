#include "shooter/shooter_protocol.h"

#include "protocol/fields.h"
#include "protocol/questions_json.h"

namespace warplab::protocol {
namespace {

using fields::Json;
using fields::kCommitStretchLimitS;
using fields::kRefreshLimitHz;
using fields::NumberRange;

// Bounds that no study needs to exceed (protocol/fields.h says why they exist).
constexpr int kLevelLimit = 120;  // v0 * 2^20: far beyond any hittable speed
constexpr int kTargetsLimit = 100000;
constexpr int kShotsLimit = 10000;
constexpr double kMousePerCountLimit = 0.1;
constexpr double kRadiusLimit = 3;  // well under half the 8 m high clear cross-section
// Positive is not enough where a tiny value breaks later maths. 1e-6 rad a count is 6.3
// million counts a turn, 160 cm of hand travel even at 100000 CPI (the thesis: 800 CPI at
// 0.0022); below it the bot's and the live gain's division by it overflow, and 1e-310 ended
// a session in "dir: must be non-zero and finite".
constexpr double kMousePerCountMin = 1e-6;
// 1 cm is 0.08 degrees at the target plane's 7.3 m, about a pixel and a half of a 1080-line
// display; a subnormal radius became a float 0, an invisible target no shot can hit.
constexpr double kRadiusMin = 0.01;

// Durations (docs/protocol.md, "Limits that keep a session's data safe"). A trial is committed
// when it ends, so the frames held between two commit points are at most a feedback pause
// and the next trial up to its timeout, in every phase.
constexpr double kTimeoutLimitS = 120;  // 40 times the thesis' 3 s
constexpr double kPauseLimitS = 60;  // 60 times the thesis' 1 s
static_assert(kTimeoutLimitS + kPauseLimitS <= kCommitStretchLimitS);
// Whole phases, committed trial by trial: bounds on how long a session can be, not on memory.
constexpr double kAcclimationLimitS = 1800;  // 6 times the thesis' 5 minutes
constexpr double kTrainingLimitS = 3600;  // 5 times the thesis' 12 minutes

using P = ShooterProtocol;
using K = fields::Keys<P>;
using fields::at;

// Every key of a shooter protocol below the top level, once (docs/protocol.md lists each).
const std::vector<fields::Section<P>>& sections() {
    static const std::vector<fields::Section<P>> list = [] {
        std::vector<fields::Key<P>> display = {
            K::number("refresh_hz", at(&P::refreshHz), {1, false, kRefreshLimitHz, false}),
            K::number("vertical_fov_deg", at(&P::verticalFovDeg),
                      {kMinVerticalFovDeg, false, kMaxVerticalFovDeg, false}),
            K::choice("refresh_mismatch", at(&P::refreshMismatch)).since(2),
        };
        for (auto& k : fields::renderKeys<P>(kShooterPhotonMarkerSince)) display.push_back(k);
        using S = StaircaseSettings;
        return std::vector<fields::Section<P>>{
            {"display", display},
            {"target", {K::number("radius_m", at(&P::targetRadius), {kRadiusMin, false, kRadiusLimit, true})}},
            {"input",
             {K::number("mouse_radians_per_count", at(&P::mouseRadiansPerCount),
                        {kMousePerCountMin, false, kMousePerCountLimit, false})}},
            {"acclimation",
             {K::number("duration_s", at(&P::acclimationS), {0, true, kAcclimationLimitS, false}),
              K::integer("level", at(&P::acclimationLevel), 0, kLevelLimit),
              K::conditionId("mode", at(&P::acclimationCondition)).renamed(kShooterConditionKeysSince, "condition"),
              K::conditionId("condition", at(&P::acclimationCondition)).renames(kShooterConditionKeysSince),
              fields::instructionsKey<P>(at(&P::acclimationInstructions), kShooterInstructionsSince)}},
            {"training",
             {K::number("base_speed_m_per_s", at(&P::training, &S::baseSpeed), {0, true, kMaxBaseSpeedMPerS, false}),
              K::integer("start_level", at(&P::training, &S::startLevel), 0, kLevelLimit),
              K::integer("max_level", at(&P::training, &S::maxLevel), 0, kLevelLimit),
              K::integer("shots_per_level_easy", at(&P::training, &S::shotsPerLevelEasy), 1, kShotsLimit),
              K::integer("shots_per_level_hard", at(&P::training, &S::shotsPerLevelHard), 1, kShotsLimit),
              K::conditionId("high_mode", at(&P::training, &S::highCondition))
                  .renamed(kShooterConditionKeysSince, "high_condition"),
              K::conditionId("high_condition", at(&P::training, &S::highCondition)).renames(kShooterConditionKeysSince),
              K::conditionId("low_mode", at(&P::training, &S::lowCondition))
                  .renamed(kShooterConditionKeysSince, "low_condition"),
              K::conditionId("low_condition", at(&P::training, &S::lowCondition)).renames(kShooterConditionKeysSince),
              K::number("time_limit_s", at(&P::training, &S::timeLimitS), {0, true, kTrainingLimitS, false}),
              fields::instructionsKey<P>(at(&P::trainingInstructions), kShooterInstructionsSince)}},
            {"test",
             {K::conditionList("conditions", at(&P::conditions)),
              K::integer("targets_per_condition", at(&P::targetsPerCondition), 1, kTargetsLimit),
              K::boolean("interleave", at(&P::interleaveConditions)),
              K::number("timeout_s", at(&P::timeoutS), {0, true, kTimeoutLimitS, false}),
              K::number("pause_s", at(&P::pauseS), {0, true, kPauseLimitS, false}),
              K::choice("scoring", at(&P::scoring)), K::boolean("supervisor_starts", at(&P::supervisorStartsTest)),
              // Version 1 has no click_timing and means "display". A struct that says otherwise
              // is written anyway, so that parsing the copy refuses it instead of quietly
              // replaying it differently.
              K::choice("click_timing", at(&P::clickTiming)).since(2, true),
              fields::instructionsKey<P>(at(&P::testInstructions), kShooterInstructionsSince),
              fields::questionsKey<P>(at(&P::questions), kShooterQuestionsSince)}},
        };
    }();
    return list;
}

}  // namespace

std::vector<std::string> shooterProtocolKeys() {
    return fields::keyPaths(sections(), {{"test.questions", fields::questionKeyNames()}});
}

ShooterProtocol parseShooterProtocol(const std::string& jsonText, const std::string& sourceName) {
    fields::Reader r(sourceName);
    const Json document = r.parseObject(jsonText);
    ShooterProtocol p;
    r.requireGame(document, "shooter");
    p.formatVersion = r.formatVersion(document, kShooterFormatVersion);
    p.legacyRules = p.formatVersion == 1;

    r.requireKnownKeys(document, "", fields::topLevelKeys(sections()));
    r.nameAndDescription(document, p.name, p.description);
    p.conditionTable = condition::ConditionTable(
        r.conditions(document, p.formatVersion, kShooterConditionsSince, kShooterPacingSince));
    fields::readSections(r, document, sections(), p.formatVersion, p);
    if (p.formatVersion < kShooterInstructionsSince)
        for (std::string* text : {&p.acclimationInstructions, &p.trainingInstructions, &p.testInstructions})
            text->clear();
    const StaircaseSettings& s = p.training;

    // Relations between fields, checked once every field holds its final value.
    if (s.startLevel > s.maxLevel)
        r.fail("training.start_level",
               "must be at most training.max_level (" + std::to_string(s.maxLevel) + "), got " +
                   std::to_string(s.startLevel));
    if (p.acclimationLevel > s.maxLevel)
        r.fail("acclimation.level",
               "must be at most training.max_level (" + std::to_string(s.maxLevel) + "), got " +
                   std::to_string(p.acclimationLevel));
    if (s.shotsPerLevelHard < s.shotsPerLevelEasy)
        r.fail("training.shots_per_level_hard",
               "must be at least training.shots_per_level_easy (" + std::to_string(s.shotsPerLevelEasy) + "), got " +
                   std::to_string(s.shotsPerLevelHard));
    // Named as the file names them (acclimation.mode before format 9).
    const auto named = [&](const char* section, const char* key) {
        return fields::keyPathIn(sections(), section, key, p.formatVersion);
    };
    if (s.highCondition == s.lowCondition)
        r.fail(named("training", "low_condition"),
               "must differ from " + named("training", "high_condition") + ", both are \"" + s.lowCondition + "\"");
    // Defaults included: a file that only changes the refresh must still fit every condition.
    r.requireConditionsRun(p.refreshHz);
    r.requireCondition(named("acclimation", "condition"), p.acclimationCondition, p.refreshHz);
    r.requireCondition(named("training", "high_condition"), s.highCondition, p.refreshHz);
    r.requireCondition(named("training", "low_condition"), s.lowCondition, p.refreshHz);
    r.requireConditions("test.conditions", p.conditions, p.refreshHz);
    r.requireConditionsUsed();
    return p;
}

ShooterProtocol loadShooterProtocol(const std::string& path) {
    return parseShooterProtocol(readProtocolFile(path), path);
}

std::string toJson(const ShooterProtocol& p) { return fields::protocolText(p, sections()); }

}  // namespace warplab::protocol
