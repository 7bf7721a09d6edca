// A session's results: the rows every game shares, which `warplab export` writes as shots.csv
// and answers.csv, and the tables a game adds of its own (docs/export.md). Each game reads its
// own events (Study::results), so export merges sessions of any game without naming one.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "table/csv.h"

namespace warplab::game {

inline constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();  // an empty CSV cell

// One shot (shooter) or click (click game): a row of shots.csv.
struct ShotResult {
    std::string phase;  // shooter: acclimation/training/test; click: the round's name
    bool scoredPhase = false;  // the phase the study analyses (shooter "test", a scored round)
    int trial = -1;  // shooter: trial index; click: match index
    std::string condition;
    std::string outcome;  // the one the protocol scores: hit/miss/timeout, green/red/miss
    std::string worldOutcome, displayedOutcome;
    bool hit = false;  // outcome counts as a hit (shooter "hit", click "green")
    bool timeout = false;
    double time = 0.0;  // display time of the shot, click or timeout, s
    // When the trial's target appeared (display clock, s) and the time from then to the shot;
    // kNotApplicable where a game has no such moment (the click game: a match's clicks). Export
    // counts a trial's skipped frames and its frame time from spawnTime.
    double spawnTime = kNotApplicable;
    double aimTime = kNotApplicable;
    // The game's own columns of shots.csv (GameExport::shotColumns), in that order: the measures
    // of a trial only it has (the shooter's angular error, the click game's distance in pixels).
    table::Cells own;
};

// One answer to a question after a block (a click match, a block of the shooter's test): a row
// of answers.csv. Every kind of question, every game.
struct AnswerResult {
    std::string block;  // what the answer is about: the click round's name, the shooter's "test"
    bool scoredPhase = false;  // the block is in the part the study analyses
    int blockIndex = -1;  // click: the match index; shooter: the test block, 0-based
    std::string condition;  // the block's condition; "" where its trials mixed conditions
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

// A row of a table of a game's own (the click game's matches.csv): the game's cells, and what
// export needs to add its own columns to them.
struct GameTableRow {
    std::string condition;  // the condition it ran in: condition_position
    bool scoredPhase = false;  // false: written only with --all-phases
    // A span table's row covers the stretch of play from startTime to endTime (display clock, s):
    // export adds the frames skipped in it and the frame time of its last second.
    double startTime = kNotApplicable, endTime = kNotApplicable;
    table::Cells cells;  // GameTable::columns, in order
    table::Cells numbered;  // GameTable::numbered + 1, + 2, ...: as many as it has, the rest empty
};

// A table a game adds to the export beside the shared ones (docs/export.md). Its file has
// participant, session, then the game's columns; for a span table skipped_frames; then the
// numbered columns, as many as the widest row has; then player_kind, condition_position and, for
// a span table, frame_time_p95_ms. Rows of every session of the game go to one file.
struct GameTable {
    std::string file;  // "matches.csv"; one file, one game
    std::vector<std::string> columns;  // the game's own, in order
    bool spans = false;  // every row covers a stretch of play (a match, a block)
    std::string numbered;  // the numbered columns' prefix ("rating_"); "" for none
    std::vector<GameTableRow> rows;
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
    // The game's own tables: their columns even when it has no rows (a study with no session yet).
    // A scored span row also ran its condition: hitrates.csv and condition_position count it.
    std::vector<GameTable> tables;
    std::vector<AnswerResult> answers;  // in the order given; a match's ratings are among them
};

}  // namespace warplab::game
