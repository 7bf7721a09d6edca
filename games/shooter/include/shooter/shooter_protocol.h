// The bouncing-target shooter study's protocol file (seed 004 sections 5.3.3-5.3.4 and
// Appendix B): what a session runs, as plain data. Every field is documented, with its JSON
// key, unit, range and source, in docs/protocol.md. The defaults are the study as published,
// so an unset field in a file means "as in the thesis".
#pragma once

#include <string>
#include <vector>

#include "condition/condition.h"
#include "protocol/questions.h"
#include "protocol/study_protocol.h"

namespace warplab::protocol {

// The newest protocol format this build reads. 2 added test.click_timing and fixed the timeout
// and training rules (docs/protocol.md, "Format versions"); version 1 files are still read and
// replay under the rules they were recorded with. 3 added the protocol's own "conditions", 4
// each phase's "instructions" screen, 5 the questions after each block of the test, 6
// display.photon_marker, 7 the view re-centred where training and the test begin and the
// question screens' cursor starting clear of every answer, 8 a condition's frame_time_jitter and
// hitches, 9 named the keys that name a condition for it (acclimation.condition,
// training.high_condition and low_condition, formerly mode, high_mode and low_mode).
inline constexpr int kShooterFormatVersion = 9;
inline constexpr int kShooterConditionsSince = 3;
// A condition's frame_time_jitter and hitches (docs/frame-pacing.md).
inline constexpr int kShooterPacingSince = 8;
inline constexpr int kShooterInstructionsSince = 4;
inline constexpr int kShooterQuestionsSince = 5;  // test.questions
inline constexpr int kShooterPhotonMarkerSince = 6;  // display.photon_marker
inline constexpr int kShooterRecentresSince = 7;  // a rule of the game: older files replay without it
inline constexpr int kShooterConditionKeysSince = 9;  // acclimation.condition, formerly acclimation.mode

// training.base_speed_m_per_s at most, the target's speed at level 0; render's --speed too.
inline constexpr double kMaxBaseSpeedMPerS = 100;

// The training staircase (seed 004 section 5.3.3, figure 31).
struct StaircaseSettings {
    double baseSpeed = 1.0;  // v0 in m/s, speed at difficulty 0 (v_d = v0 * 2^(d/6), eq. 12)
    int startLevel = 0;
    int maxLevel = 60;
    int shotsPerLevelEasy = 4;  // shots evaluated per level while everything is hit
    int shotsPerLevelHard = 16;  // ... once hit rates drop ("progressively more shots")
    std::string highCondition = "conv120";  // stop when highCondition's miss rate > lowCondition's hit rate
    std::string lowCondition = "conv15";
    double timeLimitS = 720;  // then the test starts at the level reached
};

struct ShooterProtocol {
    std::string name;
    std::string description;
    int formatVersion = kShooterFormatVersion;
    std::string game = "shooter";
    double refreshHz = 120;
    double verticalFovDeg = 60;
    // A live session on a display whose refresh is known to differ: refuse to start, or warn
    // and pace frames by timer (quick protocols, so they run anywhere).
    RefreshMismatch refreshMismatch = RefreshMismatch::Refuse;
    RenderSettings rendering;  // display.guard_band, display.supersampling, display.photon_marker
    double targetRadius = 0.35;  // metres
    double mouseRadiansPerCount = 0.0022;  // camera turn per mouse count
    double acclimationS = 300;
    int acclimationLevel = 0;
    std::string acclimationCondition = "conv120";
    // Each phase opens with a screen of its instructions, read and continued with Enter; ""
    // for none (and none at all in files older than format 4).
    std::string acclimationInstructions =
        "Practice. A ball bounces across the hallway: aim at it with the mouse and press the left "
        "button to shoot it. You have one shot for each ball. Nothing you do in the practice counts.";
    std::string trainingInstructions =
        "Training. Aim at the ball with the mouse and press the left button to shoot it, one shot "
        "for each ball. The balls get faster as you go.";
    std::string testInstructions =
        "The test. Aim at the ball with the mouse and press the left button to shoot it, one shot "
        "for each ball, before it disappears. Be as quick and as accurate as you can.";
    StaircaseSettings training;
    // The conditions the file defines beside the presets ("conditions"); the condition fields and
    // test.conditions name presets or these.
    condition::ConditionTable conditionTable;
    std::vector<std::string> conditions{"conv15", "conv120", "warp15to120"};
    int targetsPerCondition = 225;
    // test.questions (format 5 and later): asked after each block of the test: after each
    // condition's trials where conditions are not interleaved, else once after the whole test.
    // None by default (the thesis asked none).
    std::vector<Question> questions;
    bool interleaveConditions = true;  // random order drawn from the session seed
    double timeoutS = 3;
    double pauseS = 1;
    Scoring scoring = Scoring::Displayed;  // or World (DESIGN.md "Scoring")
    bool supervisorStartsTest = true;  // the supervisor's Enter starts the recorded part
    // Display: a click counts at the display frame where the button goes down; InputReads:
    // only at frames where the condition reads input (conv15/30/60 read it only at their renders),
    // so a press counts at the next such frame. Format 2 and later.
    ClickTiming clickTiming = ClickTiming::Display;
    // Not in the JSON: true for a format_version 1 file, whose sessions were recorded under the
    // old trial-timeout and training-evaluation rules and must replay under them. toJson writes
    // the form of formatVersion, so keep the two together in a hand-built struct.
    bool legacyRules = false;
};

// sourceName is what messages call the file (its path). Every condition id must name a preset or a
// condition the file defines, runnable at its refresh. Reads format_version 1 to 6. Throws
// ProtocolError.
ShooterProtocol parseShooterProtocol(const std::string& jsonText, const std::string& sourceName);
// Every key a shooter protocol may have, as JSON paths ("display.refresh_hz"), in file order:
// the parser's table, which docs/protocol.md must document.
std::vector<std::string> shooterProtocolKeys();
// A missing or unreadable file is a ProtocolError naming the path.
ShooterProtocol loadShooterProtocol(const std::string& path);
// Canonical form: every field, in a fixed order, 2-space indent, trailing newline. Parsing it
// gives back the same struct bit for bit, so the session stores this copy as the protocol it
// ran. Writes the form of protocol.formatVersion: a version 1 struct (a stored v1 session)
// comes out as version 1, without click_timing, and so reads back with legacyRules. Does not
// validate; parse what it writes to check a hand-built struct.
std::string toJson(const ShooterProtocol& protocol);

}  // namespace warplab::protocol
