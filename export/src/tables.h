// Private to export/: the rows each CSV file is written from and their column tables, one per
// file (columns.h), so that export.cpp gathers rows and these say what a row's cells are.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "csv_columns.h"
#include "export/export.h"
#include "game/game.h"
#include "game/results.h"
#include "session/pacing.h"
#include "session/session_store.h"

namespace warplab::exporter {

// Hit counts of one participant x game x condition over the scored phase.
struct Tally {
    std::int64_t shots = 0, hits = 0, timeouts = 0;
};

// A session file as sessions.csv lists it. An unreadable one has only its name and what
// became of it; every other cell is empty.
struct SessionRow {
    const std::string& file;
    const ExportedSession& outcome;
    const session::SessionData* data = nullptr;  // null: unreadable
    const game::Study* study = nullptr;
    const game::SessionResults* results = nullptr;
};

// Each condition's place in the order a session's scored phase first presented it, 1-based:
// condition_position in shots.csv, answers.csv and the games' own tables (docs/export.md).
using Positions = std::map<std::string, std::int64_t>;

// Who and where a shot, match or rating comes from.
struct Origin {
    const std::string& participant;
    const std::string& session;
    const std::string& game;
    const std::string& playerKind;  // session::playerKind of the session's player
    const Positions& positions;
};

struct ShotRow {
    Origin from;
    const game::ShotResult& shot;
    std::optional<std::int64_t> skipped;  // display frames skipped from the target's appearance to the shot
    double frameTimeP95S;  // of the new images of the second before the shot; NaN: none
};

struct AnswerRow {
    Origin from;
    const game::AnswerResult& answer;
};

struct PacingRow {
    const std::string& participant;
    const std::string& session;
    const session::ConditionPacing& pacing;
    const std::string& playerKind;
};

struct HitRateRow {
    const std::string& participant;
    const std::string& game;
    const std::string& condition;
    const Tally& tally;
    bool canTimeOut;
    // The kinds of the sessions counted, ;-separated: one participant id can name a person in
    // one session and a bot in another.
    const std::string& playerKinds;
};

// A row of a game's own table (game::GameTable), with what export adds to the game's cells.
struct GameTableEntry {
    std::string participant, session, playerKind;
    game::GameTableRow row;
    std::optional<std::int64_t> position;  // condition_position; none outside the scored phase
    std::optional<std::int64_t> skipped;  // a span row's display frames skipped in its span
    double frameTimeP95S = 0.0;  // a span row's, of the new images of its last second; NaN: none
};

// One frame time of a condition's horizon, as frametimes.csv lists it.
struct FrameTimeRow {
    const ConditionListing& listing;
    std::size_t index;  // into listing.pacing.frames
};

// A piece of a condition's latency distribution, as latency.csv lists it: a step falling
// uniformly in time over the horizon waits between fromS and toS, uniformly, with probability
// weight. Spans of the schedule with the same latencies are one row.
struct LatencyRow {
    const ConditionListing& listing;
    const char* kind;  // "view" or "scene"
    double fromS = 0.0, toS = 0.0, weight = 0.0;
};
// The view spans, then the scene spans, of `listing`'s pacing, each by ascending latency.
std::vector<LatencyRow> latencyRows(const ConditionListing& listing);

struct GameRow {
    const std::string& game;
    const game::HitMeasure& measure;
    const std::string& tables;  // the game's own files, ;-separated
};

// The flag names of a session, ;-separated, as sessions.csv lists them.
std::string joined(const std::map<std::string, std::string>& flags);

// A condition's place in `positions`, for a row of the scored phase; none otherwise.
std::optional<std::int64_t> positionOf(const Positions& positions, const std::string& condition, bool scoredPhase);

// Each CSV file's columns (docs/export.md lists them; a test checks it against these).
const std::vector<Column<SessionRow>>& sessionColumns();
// shots.csv: export's leading columns, then every registered game's own (in the order the games
// were registered; empty in another game's rows), then export's trailing ones.
struct ShotsLayout {
    std::vector<std::string> header;
    std::vector<std::string> gameColumns;
    std::map<std::string, std::vector<int>> at;  // per game: where each of gameColumns is in its own cells; -1 none
};
ShotsLayout shotsLayout();
void writeShot(table::CsvFile& file, const ShotsLayout& layout, const ShotRow& row);
const std::vector<Column<ShotRow>>& shotLeadingColumns();
const std::vector<Column<ShotRow>>& shotTrailingColumns();
const std::vector<Column<AnswerRow>>& answerColumns();
const std::vector<Column<PacingRow>>& pacingColumns();
const std::vector<Column<HitRateRow>>& hitRateColumns();
// The columns export adds to a game's own table: before the game's, after them in a span table,
// after the numbered ones, and then last in a span table (game::GameTable).
const std::vector<Column<GameTableEntry>>& gameTableLeadingColumns();
const std::vector<Column<GameTableEntry>>& gameTableSpanColumns();
const std::vector<Column<GameTableEntry>>& gameTableTrailingColumns();
const std::vector<Column<GameTableEntry>>& gameTableSpanTrailingColumns();
const std::vector<Column<ConditionListing>>& conditionColumns();
const std::vector<Column<FrameTimeRow>>& frameTimeColumns();
const std::vector<Column<LatencyRow>>& latencyColumns();
const std::vector<Column<GameRow>>& gameColumns();

}  // namespace warplab::exporter
