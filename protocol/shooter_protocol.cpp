#include "protocol/shooter_protocol.h"

#include "protocol/json_fields.h"

namespace warplab::protocol {
namespace {

using detail::Json;
using detail::kCommitStretchLimitS;
using detail::kRefreshLimitHz;
using detail::NumberRange;

// Bounds that no study needs to exceed (json_fields.h says why they exist).
constexpr int kLevelLimit = 120;           // v0 * 2^20: far beyond any hittable speed
constexpr int kTargetsLimit = 100000;
constexpr int kShotsLimit = 10000;
constexpr double kMousePerCountLimit = 0.1;
constexpr double kRadiusLimit = 3;         // well under half the 8 m high clear cross-section
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
constexpr double kTimeoutLimitS = 120;        // 40 times the thesis' 3 s
constexpr double kPauseLimitS = 60;           // 60 times the thesis' 1 s
static_assert(kTimeoutLimitS + kPauseLimitS <= kCommitStretchLimitS);
// Whole phases, committed trial by trial: bounds on how long a session can be, not on memory.
constexpr double kAcclimationLimitS = 1800;   // 6 times the thesis' 5 minutes
constexpr double kTrainingLimitS = 3600;      // 5 times the thesis' 12 minutes

}  // namespace

ShooterProtocol parseShooterProtocol(const std::string& jsonText, const std::string& sourceName,
                                     const ModeCheck& modes) {
    const detail::Reader r(sourceName, modes);
    const Json document = r.parseObject(jsonText);
    ShooterProtocol p;
    r.requireGame(document, "shooter");
    p.formatVersion = r.formatVersion(document, kShooterFormatVersion);
    p.legacyRules = p.formatVersion == 1;

    r.requireKnownKeys(document, "",
                       {"format_version", "name", "description", "game", "display", "target",
                        "input", "acclimation", "training", "test"});
    r.nameAndDescription(document, p.name, p.description);

    if (const Json* display = r.object(document, "", "display")) {
        r.requireKnownKeys(*display, "display",
                           {"refresh_hz", "vertical_fov_deg", "refresh_mismatch", "guard_band", "supersampling"});
        r.number(display, "display", "refresh_hz", {1, false, kRefreshLimitHz, false}, p.refreshHz);
        r.number(display, "display", "vertical_fov_deg",
                 {kMinVerticalFovDeg, false, kMaxVerticalFovDeg, false}, p.verticalFovDeg);
        r.choice(display, "display", "refresh_mismatch", p.refreshMismatch);
        detail::readRenderSettings(r, display, p.rendering);
    }
    if (const Json* target = r.object(document, "", "target")) {
        r.requireKnownKeys(*target, "target", {"radius_m"});
        r.number(target, "target", "radius_m", {kRadiusMin, false, kRadiusLimit, true},
                 p.targetRadius);
    }
    if (const Json* input = r.object(document, "", "input")) {
        r.requireKnownKeys(*input, "input", {"mouse_radians_per_count"});
        r.number(input, "input", "mouse_radians_per_count",
                 {kMousePerCountMin, false, kMousePerCountLimit, false}, p.mouseRadiansPerCount);
    }
    if (const Json* acclimation = r.object(document, "", "acclimation")) {
        r.requireKnownKeys(*acclimation, "acclimation", {"duration_s", "level", "mode"});
        r.number(acclimation, "acclimation", "duration_s", {0, true, kAcclimationLimitS, false},
                 p.acclimationS);
        r.integer(acclimation, "acclimation", "level", 0, kLevelLimit, p.acclimationLevel);
        r.modeId(acclimation, "acclimation", "mode", p.acclimationMode);
    }
    StaircaseSettings& s = p.training;
    if (const Json* training = r.object(document, "", "training")) {
        r.requireKnownKeys(*training, "training",
                           {"base_speed_m_per_s", "start_level", "max_level", "shots_per_level_easy",
                            "shots_per_level_hard", "high_mode", "low_mode", "time_limit_s"});
        r.number(training, "training", "base_speed_m_per_s", {0, true, kMaxBaseSpeedMPerS, false},
                 s.baseSpeed);
        r.integer(training, "training", "start_level", 0, kLevelLimit, s.startLevel);
        r.integer(training, "training", "max_level", 0, kLevelLimit, s.maxLevel);
        r.integer(training, "training", "shots_per_level_easy", 1, kShotsLimit, s.shotsPerLevelEasy);
        r.integer(training, "training", "shots_per_level_hard", 1, kShotsLimit, s.shotsPerLevelHard);
        r.modeId(training, "training", "high_mode", s.highMode);
        r.modeId(training, "training", "low_mode", s.lowMode);
        r.number(training, "training", "time_limit_s", {0, true, kTrainingLimitS, false},
                 s.timeLimitS);
    }
    if (const Json* test = r.object(document, "", "test")) {
        r.requireKnownKeys(*test, "test",
                           {"conditions", "targets_per_condition", "interleave", "timeout_s",
                            "pause_s", "scoring", "supervisor_starts", "click_timing"});
        if (p.formatVersion < 2 && test->contains("click_timing"))
            r.fail("test.click_timing",
                   "is new in format_version 2, but this file is format_version " +
                       std::to_string(p.formatVersion));
        r.modeList(test, "test", "conditions", p.conditions);
        r.integer(test, "test", "targets_per_condition", 1, kTargetsLimit, p.targetsPerCondition);
        r.boolean(test, "test", "interleave", p.interleaveConditions);
        r.number(test, "test", "timeout_s", {0, true, kTimeoutLimitS, false}, p.timeoutS);
        r.number(test, "test", "pause_s", {0, true, kPauseLimitS, false}, p.pauseS);
        r.choice(test, "test", "scoring", p.scoring);
        r.boolean(test, "test", "supervisor_starts", p.supervisorStartsTest);
        r.choice(test, "test", "click_timing", p.clickTiming);
    }

    // Relations between fields, checked once every field holds its final value.
    if (s.startLevel > s.maxLevel)
        r.fail("training.start_level", "must be at most training.max_level (" +
                                           std::to_string(s.maxLevel) + "), got " +
                                           std::to_string(s.startLevel));
    if (p.acclimationLevel > s.maxLevel)
        r.fail("acclimation.level", "must be at most training.max_level (" +
                                        std::to_string(s.maxLevel) + "), got " +
                                        std::to_string(p.acclimationLevel));
    if (s.shotsPerLevelHard < s.shotsPerLevelEasy)
        r.fail("training.shots_per_level_hard",
               "must be at least training.shots_per_level_easy (" +
                   std::to_string(s.shotsPerLevelEasy) + "), got " +
                   std::to_string(s.shotsPerLevelHard));
    if (s.highMode == s.lowMode)
        r.fail("training.low_mode", "must differ from training.high_mode, both are \"" +
                                        s.lowMode + "\"");
    // Defaults included: a file that only changes the refresh must still fit every mode.
    r.requireMode("acclimation.mode", p.acclimationMode, p.refreshHz);
    r.requireMode("training.high_mode", s.highMode, p.refreshHz);
    r.requireMode("training.low_mode", s.lowMode, p.refreshHz);
    r.requireModes("test.conditions", p.conditions, p.refreshHz);
    return p;
}

ShooterProtocol loadShooterProtocol(const std::string& path, const ModeCheck& modes) {
    return parseShooterProtocol(readProtocolFile(path), path, modes);
}

std::string toJson(const ShooterProtocol& p) {
    const StaircaseSettings& s = p.training;
    Json document = detail::headerJson(p.formatVersion, p.name, p.description, p.game);
    document["display"]["refresh_hz"] = p.refreshHz;
    document["display"]["vertical_fov_deg"] = p.verticalFovDeg;
    // Like click_timing below: new with format 2, written for version 1 only when it says more.
    if (p.formatVersion >= 2 || p.refreshMismatch != RefreshMismatch::Refuse)
        document["display"]["refresh_mismatch"] = nameOf(p.refreshMismatch);
    detail::writeRenderSettings(document["display"], p.rendering, p.formatVersion);
    document["target"]["radius_m"] = p.targetRadius;
    document["input"]["mouse_radians_per_count"] = p.mouseRadiansPerCount;
    document["acclimation"]["duration_s"] = p.acclimationS;
    document["acclimation"]["level"] = p.acclimationLevel;
    document["acclimation"]["mode"] = p.acclimationMode;
    Json& training = document["training"];
    training["base_speed_m_per_s"] = s.baseSpeed;
    training["start_level"] = s.startLevel;
    training["max_level"] = s.maxLevel;
    training["shots_per_level_easy"] = s.shotsPerLevelEasy;
    training["shots_per_level_hard"] = s.shotsPerLevelHard;
    training["high_mode"] = s.highMode;
    training["low_mode"] = s.lowMode;
    training["time_limit_s"] = s.timeLimitS;
    Json& test = document["test"];
    test["conditions"] = p.conditions;
    test["targets_per_condition"] = p.targetsPerCondition;
    test["interleave"] = p.interleaveConditions;
    test["timeout_s"] = p.timeoutS;
    test["pause_s"] = p.pauseS;
    test["scoring"] = nameOf(p.scoring);
    test["supervisor_starts"] = p.supervisorStartsTest;
    // Version 1 has no click_timing and means "display". Any other value is written anyway, so
    // that parsing the copy refuses the struct instead of quietly replaying it differently.
    if (p.formatVersion >= 2 || p.clickTiming != ClickTiming::Display) test["click_timing"] = nameOf(p.clickTiming);
    return detail::canonicalText(document);
}

}  // namespace warplab::protocol
