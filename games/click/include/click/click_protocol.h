// The falling-sphere click game's protocol file (Yang et al. 2011, seed 000 section 8): red and
// green spheres fall and bounce in a box, the player clicks the green ones and avoids the red
// ones, in 45 s matches played in each condition, each followed by questions (the paper's four 1-7
// ratings unless the file lists its own). Every field is documented, with its JSON key, unit,
// range and source, in docs/protocol.md. The defaults are the published study, so an unset
// field in a file means "as in the paper".
#pragma once

#include <string>
#include <vector>

#include "condition/condition.h"
#include "protocol/questions.h"
#include "protocol/study_protocol.h"

namespace warplab::protocol {

// The newest click protocol format this build reads and the one toJson writes.
// 2 added the protocol's own "conditions" (docs/protocol.md, "Format versions"), 3 each
// round's "instructions" screen, 4 matches.questions in place of the ratings section, 5
// display.photon_marker, 6 a condition's frame_time_jitter and hitches, 7 named the keys that
// name conditions for them (matches.conditions and a round's matches_per_condition, formerly
// matches.modes and matches_per_mode).
inline constexpr int kClickFormatVersion = 7;
inline constexpr int kClickConditionsSince = 2;
// A condition's frame_time_jitter and hitches (docs/frame-pacing.md).
inline constexpr int kClickPacingSince = 6;
inline constexpr int kClickInstructionsSince = 3;
// From 4 the questions after each match are matches.questions (any kind), and a file may no
// longer have a ratings section; older files rate the ratings section's statements, and their
// sessions log those answers as "rating" events.
inline constexpr int kClickQuestionsSince = 4;
inline constexpr int kClickPhotonMarkerSince = 5;
inline constexpr int kClickConditionKeysSince = 7;  // matches.conditions, formerly matches.modes

// What a round's instructions say unless the protocol says otherwise: the task in plain words.
inline constexpr const char* kClickTaskInstructions =
    "Red and green spheres fall and bounce. Click the green ones with the mouse to make them "
    "vanish; never click a red one, nor empty space.";

// One round: every condition of the study played matchesPerCondition times. Yang et al. played an
// unscored round of one match per condition, then a scored round of two per condition.
struct ClickRound {
    std::string name;  // written into every match event of the round
    bool scored = true;  // false: played for practice, outcomes logged but not analysed
    int matchesPerCondition = 1;
    // The screen that opens the round, read and continued with Enter; "" for none (and none at
    // all in files older than format 3).
    std::string instructions = kClickTaskInstructions;
};

struct ClickProtocol {
    std::string name;
    std::string description;
    int formatVersion = kClickFormatVersion;
    std::string game = "click";
    double refreshHz = 60;  // display.refresh_hz
    double verticalFovDeg = 60;  // display.vertical_fov_deg
    double cameraPitchDeg = -10;  // display.camera_pitch_deg, looks down at the box floor
    RefreshMismatch refreshMismatch = RefreshMismatch::Refuse;  // display.refresh_mismatch, as the shooter's
    RenderSettings rendering;  // display.guard_band, display.supersampling, display.photon_marker
    // physics.* (the game maps these onto physics::FallingSphereSettings; keep the same defaults)
    double gravity = 9.81;  // m/s^2, >= 0
    double sphereRadius = 0.45;  // m, (0, 2]
    double restitution = 0.9;  // [0, 1]; bouncy enough that spheres keep moving through a 45 s match
    int stepRateHz = 960;  // internal physics steps per second; refresh must divide it
    int sphereCount = 10;  // [1, 40]
    double greenShare = 0.5;  // [0, 1]
    double spawnDelayS = 0.5;  // >= 0
    double spawnSpeedMPerS = 2.0;  // >= 0
    // input.*
    double cursorPixelsPerCount = 1.0;  // cursor movement per mouse count on the session's display, (0, 100]
    ClickTiming clickTiming = ClickTiming::Display;  // or InputReads, as for the shooter
    // matches.*
    double matchS = 45;  // > 0
    // The conditions the file defines beside the presets ("conditions"); matches.conditions names
    // presets or these.
    condition::ConditionTable conditionTable;
    std::vector<std::string> conditions{"conv60", "conv30", "conv15", "lag50", "lag100", "lag200", "bireproj15to60"};
    std::vector<ClickRound> rounds{
        {"practice", false, 1, std::string("Practice. ") + kClickTaskInstructions + " Nothing in the practice counts."},
        {"scored", true, 2,
         std::string(kClickTaskInstructions) + " From now on every match counts. After each one, say how it felt."}};
    bool shuffle = true;  // random condition order per round, from the session seed
    // matches.questions: what is asked after every match, in order; empty for nothing. Files
    // older than format 4 give it as the ratings section below (their statements as Likert
    // questions on one scale, with no ids); the game asks this list whatever the version.
    std::vector<Question> questions = yangRatingQuestions();
    // ratings.* (format 3 and older; the parser turns them into `questions`)
    bool ratingsEnabled = true;
    std::vector<std::string> ratingStatements{"I enjoyed playing this game", "This game was difficult to play",
                                              "This game was responsive to my input", "The animation was smooth"};
    int ratingMin = 1, ratingMax = 7;  // 1 = strongly disagree, 7 = strongly agree
    Scoring scoring = Scoring::World;  // matches.scoring: or Displayed (DESIGN.md "Scoring")
};

// sourceName is what messages call the file (its path). Every condition id must name a preset or a
// condition the file defines, runnable at its refresh. Throws ProtocolError.
ClickProtocol parseClickProtocol(const std::string& jsonText, const std::string& sourceName);
// Every key a click protocol may have, as JSON paths ("display.refresh_hz", and
// "matches.rounds[].name" for a round's), in file order: the parser's table, which
// docs/protocol.md must document.
std::vector<std::string> clickProtocolKeys();
// A missing or unreadable file is a ProtocolError naming the path.
ClickProtocol loadClickProtocol(const std::string& path);

// The key of matches' condition list in a file of `formatVersion`: "conditions", or "modes"
// before format 7 (a study plan writes a participant's order there).
std::string conditionListKey(int formatVersion);
// Canonical form: every field, in a fixed order, 2-space indent, trailing newline. Parsing it
// gives back the same struct bit for bit, so the session stores this copy as the protocol it
// ran. Does not validate; parse what it writes to check a hand-built struct.
std::string toJson(const ClickProtocol& protocol);

}  // namespace warplab::protocol
