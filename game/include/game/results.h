// A session's results in the columns every game shares: what `warplab export` writes as
// shots.csv, matches.csv and ratings.csv (docs/export.md). Each game reads its own events
// (Study::results), so export merges sessions of any game without naming one.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace warplab::game {

inline constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();  // an empty CSV cell

// One shot (shooter) or click (click game): a row of shots.csv.
struct ShotResult {
    std::string phase;  // shooter: acclimation/training/test; click: the round's name
    bool scoredPhase = false;  // the phase the study analyses (shooter "test", a scored round)
    int trial = -1;  // shooter: trial index; click: match index
    std::string mode;
    std::string outcome;  // the one the protocol scores: hit/miss/timeout, green/red/miss
    std::string worldOutcome, displayedOutcome;
    bool hit = false;  // outcome counts as a hit (shooter "hit", click "green")
    bool timeout = false;
    double time = 0.0;  // display time of the shot, click or timeout, s
    // Game-specific; kNotApplicable where the game has no such quantity.
    double spawnTime = kNotApplicable;  // s, display clock
    double aimTime = kNotApplicable;  // shot time - spawn time, s
    double angularErrorDeg = kNotApplicable;  // aim ray to target centre
    double errorPx = kNotApplicable;  // click: cursor to the nearest green sphere's centre on screen
    double difficulty = kNotApplicable;  // staircase level
    double targetSpeed = kNotApplicable;  // m/s
};

// One answer on a rating screen after a match.
struct RatingResult {
    int statementIndex = 0;  // 0-based, in the protocol's order
    std::string statement;
    int value = 0;
    std::string answeredWith;  // "key" or "mouse"
    // The answers the screen offered, both included: the protocol's ratings.min and ratings.max,
    // which an analysis cannot know otherwise.
    int scaleMin = 1, scaleMax = 7;
};

// One answer to a question after a block (a click match, a block of the shooter's test): a row
// of answers.csv. Every kind of question, every game.
struct AnswerResult {
    std::string block;  // what the answer is about: the click round's name, the shooter's "test"
    bool scoredPhase = false;  // the block is in the part the study analyses
    int blockIndex = -1;  // click: the match index; shooter: the test block, 0-based
    std::string mode;  // the block's condition; "" where its trials mixed conditions
    int questionIndex = 0;  // 0-based, in the protocol's order
    std::string questionId;  // the protocol's id ("" in sessions of protocols that had none)
    std::string kind;  // "likert", "choice" or "text"
    std::string prompt;
    // Likert: the value; choice: the option's number, from 1; text: none.
    std::optional<int> value;
    // Choice: the option's text; text: what was typed; Likert: "".
    std::string text;
    std::string answeredWith;  // "key", "mouse" or "typed"
    int scaleMin = 1, scaleMax = 7;  // Likert: the scale offered; choice: 1 and the option count
    double time = 0.0;  // display time of the answer, s
    double answerS = kNotApplicable;  // from the question's appearance to the answer, s
};

// One click-game match: a row of matches.csv (its ratings also go to ratings.csv).
struct MatchResult {
    std::string round;
    bool scoredPhase = false;
    int match = -1;
    std::string mode;
    std::string standIn;  // method drawn in the mode's place ("" = the mode's own)
    int greenHits = 0, redHits = 0, misses = 0, clicks = 0;
    double durationS = 0.0;
    double endTime = kNotApplicable;  // display time of the match's last frame, s
    std::vector<RatingResult> ratings;  // as answered; a session cut short may lack some
};

// What a game's hit rate counts, in words a report uses ("hits out of shots", "green hits out of
// clicks"): hitrates.csv's `hits` and `shots` for this game, written to games.csv.
struct HitMeasure {
    std::string hitsAre = "hits";  // plural noun: "hits", "green hits"
    std::string shotsAre = "shots";  // plural noun: "shots", "clicks"
};

struct SessionResults {
    bool canTimeOut = false;  // the game's trials can time out (hitrates.csv counts them)
    HitMeasure measure;  // the same for every session of a game
    std::vector<ShotResult> shots;
    std::vector<MatchResult> matches;  // empty for games without matches
    std::vector<AnswerResult> answers;  // in the order given; a match's ratings are among them
};

}  // namespace warplab::game
