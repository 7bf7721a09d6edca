#include "protocol/click_protocol.h"

#include "protocol/json_fields.h"

namespace warplab::protocol {
namespace {

using detail::elementPath;
using detail::formatNumber;
using detail::joinPath;
using detail::Json;
using detail::kCommitStretchLimitS;
using detail::kRefreshLimitHz;
using detail::NumberRange;

// Bounds that no study needs to exceed (json_fields.h says why they exist).
constexpr double kGravityLimit = 100;       // about 10 g
constexpr double kRadiusLimit = 2;          // m; the box is a few metres across
constexpr int kStepRateLimit = 100000;      // Hz
constexpr int kSphereLimit = 40;
constexpr double kSpeedLimit = 100;         // m/s
constexpr double kCursorPerCountLimit = 100;
constexpr int kMatchesPerModeLimit = 100;
constexpr int kRatingLimit = 100;           // either end of the scale, in magnitude
// Positive is not enough where a tiny value breaks later maths. 1 cm, a 45th of the default
// radius, is still drawn; a subnormal radius became a float 0, spheres no click could hit.
constexpr double kRadiusMin = 0.01;
// 0.001 pixels a count still crosses a 1920-pixel screen in 49 cm of hand travel at 100000
// CPI; at 1e-310 the cursor could not move and the bot, dividing by it, never finished.
constexpr double kCursorPerCountMin = 0.001;
// Durations (docs/protocol.md, "Limits that keep a session's data safe"). A match is committed
// when it starts and when it ends, so one match is the longest stretch of frames held.
constexpr double kMatchLimitS = kCommitStretchLimitS;  // 5 minutes, 6.7 times the paper's 45 s
constexpr double kSpawnDelayLimitS = 60;               // 120 times the default 0.5 s

void readRounds(const detail::Reader& r, const Json* matches, std::vector<ClickRound>& out) {
    const Json* rounds = r.array(matches, "matches", "rounds", "rounds");
    if (!rounds) return;
    std::vector<ClickRound> read;
    std::vector<std::string> names;
    for (std::size_t i = 0; i < rounds->size(); ++i) {
        const Json& item = (*rounds)[i];
        const std::string where = elementPath("matches.rounds", i);
        if (!item.is_object()) r.fail(where, "must be an object, got " + detail::describe(item));
        r.requireKnownKeys(item, where, {"name", "scored", "matches_per_mode"});
        if (!item.contains("name")) r.fail(joinPath(where, "name"), "is required but missing");
        ClickRound round;
        round.name = r.line(item.at("name"), joinPath(where, "name"));
        r.boolean(&item, where, "scored", round.scored);
        r.integer(&item, where, "matches_per_mode", 1, kMatchesPerModeLimit, round.matchesPerMode);
        names.push_back(round.name);
        read.push_back(round);
    }
    r.requireDistinct(names,
                      [](std::size_t i) { return elementPath("matches.rounds", i) + ".name"; });
    out = std::move(read);
}

void readStatements(const detail::Reader& r, const Json* ratings, std::vector<std::string>& out) {
    // May be empty, but only with ratings off (checked once both are final).
    const Json* statements = r.array(ratings, "ratings", "statements", "statements", true);
    if (!statements) return;
    std::vector<std::string> read;
    for (std::size_t i = 0; i < statements->size(); ++i)
        read.push_back(r.line((*statements)[i], elementPath("ratings.statements", i)));
    r.requireDistinct(read, [](std::size_t i) { return elementPath("ratings.statements", i); });
    out = std::move(read);
}

}  // namespace

ClickProtocol parseClickProtocol(const std::string& jsonText, const std::string& sourceName,
                                 const ModeCheck& modes) {
    const detail::Reader r(sourceName, modes);
    const Json document = r.parseObject(jsonText);
    ClickProtocol p;
    r.requireGame(document, "click");
    p.formatVersion = r.formatVersion(document, kClickFormatVersion);
    r.requireKnownKeys(document, "",
                       {"format_version", "name", "description", "game", "display", "physics",
                        "input", "matches", "ratings"});
    r.nameAndDescription(document, p.name, p.description);

    if (const Json* display = r.object(document, "", "display")) {
        r.requireKnownKeys(*display, "display",
                           {"refresh_hz", "vertical_fov_deg", "camera_pitch_deg", "refresh_mismatch", "guard_band",
                            "supersampling"});
        r.number(display, "display", "refresh_hz", {1, false, kRefreshLimitHz, false}, p.refreshHz);
        r.number(display, "display", "vertical_fov_deg",
                 {kMinVerticalFovDeg, false, kMaxVerticalFovDeg, false}, p.verticalFovDeg);
        r.number(display, "display", "camera_pitch_deg",
                 {-kMaxCameraPitchDeg, false, kMaxCameraPitchDeg, false}, p.cameraPitchDeg);
        r.choice(display, "display", "refresh_mismatch", p.refreshMismatch);
        detail::readRenderSettings(r, display, p.rendering);
    }
    if (const Json* physics = r.object(document, "", "physics")) {
        const char* const path = "physics";
        r.requireKnownKeys(*physics, path,
                           {"gravity_m_per_s2", "sphere_radius_m", "restitution", "step_rate_hz",
                            "sphere_count", "green_share", "spawn_delay_s", "spawn_speed_m_per_s"});
        r.number(physics, path, "gravity_m_per_s2", {0, false, kGravityLimit, false}, p.gravity);
        r.number(physics, path, "sphere_radius_m", {kRadiusMin, false, kRadiusLimit, false},
                 p.sphereRadius);
        r.number(physics, path, "restitution", {0, false, 1, false}, p.restitution);
        r.integer(physics, path, "step_rate_hz", 1, kStepRateLimit, p.stepRateHz);
        r.integer(physics, path, "sphere_count", 1, kSphereLimit, p.sphereCount);
        r.number(physics, path, "green_share", {0, false, 1, false}, p.greenShare);
        r.number(physics, path, "spawn_delay_s", {0, false, kSpawnDelayLimitS, false},
                 p.spawnDelayS);
        r.number(physics, path, "spawn_speed_m_per_s", {0, false, kSpeedLimit, false},
                 p.spawnSpeedMPerS);
    }
    if (const Json* input = r.object(document, "", "input")) {
        r.requireKnownKeys(*input, "input", {"cursor_pixels_per_count", "click_timing"});
        r.number(input, "input", "cursor_pixels_per_count",
                 {kCursorPerCountMin, false, kCursorPerCountLimit, false}, p.cursorPixelsPerCount);
        r.choice(input, "input", "click_timing", p.clickTiming);
    }
    if (const Json* matches = r.object(document, "", "matches")) {
        r.requireKnownKeys(*matches, "matches",
                           {"match_s", "modes", "rounds", "shuffle", "scoring"});
        r.number(matches, "matches", "match_s", {0, true, kMatchLimitS, false}, p.matchS);
        r.modeList(matches, "matches", "modes", p.modes);
        readRounds(r, matches, p.rounds);
        r.boolean(matches, "matches", "shuffle", p.shuffle);
        r.choice(matches, "matches", "scoring", p.scoring);
    }
    if (const Json* ratings = r.object(document, "", "ratings")) {
        r.requireKnownKeys(*ratings, "ratings", {"enabled", "statements", "min", "max"});
        r.boolean(ratings, "ratings", "enabled", p.ratingsEnabled);
        readStatements(r, ratings, p.ratingStatements);
        r.integer(ratings, "ratings", "min", -kRatingLimit, kRatingLimit, p.ratingMin);
        r.integer(ratings, "ratings", "max", -kRatingLimit, kRatingLimit, p.ratingMax);
    }

    // Relations between fields, checked once every field holds its final value.
    if (!detail::wholeMultiple(p.stepRateHz, p.refreshHz))
        r.fail("physics.step_rate_hz", "must be a whole multiple of display.refresh_hz (" +
                                           formatNumber(p.refreshHz) + "), got " +
                                           std::to_string(p.stepRateHz));
    bool anyScored = false;
    for (const ClickRound& round : p.rounds) anyScored = anyScored || round.scored;
    if (!anyScored)
        r.fail("matches.rounds", "must have at least one round with \"scored\": true, or the "
                                 "session measures nothing");
    if (p.ratingsEnabled && p.ratingStatements.empty())
        r.fail("ratings.statements",
               "must list at least one statement while ratings.enabled is true");
    if (p.ratingMin >= p.ratingMax)
        r.fail("ratings.min", "must be less than ratings.max (" + std::to_string(p.ratingMax) +
                                  "), got " + std::to_string(p.ratingMin));
    r.requireModes("matches.modes", p.modes, p.refreshHz);
    return p;
}

ClickProtocol loadClickProtocol(const std::string& path, const ModeCheck& modes) {
    return parseClickProtocol(readProtocolFile(path), path, modes);
}

std::string toJson(const ClickProtocol& p) {
    Json document = detail::headerJson(p.formatVersion, p.name, p.description, p.game);
    Json& display = document["display"];
    display["refresh_hz"] = p.refreshHz;
    display["vertical_fov_deg"] = p.verticalFovDeg;
    display["camera_pitch_deg"] = p.cameraPitchDeg;
    display["refresh_mismatch"] = nameOf(p.refreshMismatch);
    detail::writeRenderSettings(display, p.rendering, p.formatVersion);
    Json& physics = document["physics"];
    physics["gravity_m_per_s2"] = p.gravity;
    physics["sphere_radius_m"] = p.sphereRadius;
    physics["restitution"] = p.restitution;
    physics["step_rate_hz"] = p.stepRateHz;
    physics["sphere_count"] = p.sphereCount;
    physics["green_share"] = p.greenShare;
    physics["spawn_delay_s"] = p.spawnDelayS;
    physics["spawn_speed_m_per_s"] = p.spawnSpeedMPerS;
    document["input"]["cursor_pixels_per_count"] = p.cursorPixelsPerCount;
    document["input"]["click_timing"] = nameOf(p.clickTiming);
    Json& matches = document["matches"];
    matches["match_s"] = p.matchS;
    matches["modes"] = p.modes;
    matches["rounds"] = Json::array();
    for (const ClickRound& round : p.rounds)
        matches["rounds"].push_back(Json{{"name", round.name},
                                         {"scored", round.scored},
                                         {"matches_per_mode", round.matchesPerMode}});
    matches["shuffle"] = p.shuffle;
    matches["scoring"] = nameOf(p.scoring);
    Json& ratings = document["ratings"];
    ratings["enabled"] = p.ratingsEnabled;
    ratings["statements"] = p.ratingStatements;
    ratings["min"] = p.ratingMin;
    ratings["max"] = p.ratingMax;
    return detail::canonicalText(document);
}

}  // namespace warplab::protocol
