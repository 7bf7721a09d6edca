// Private to export/: the rows each CSV file is written from and their column tables, one per
// file (columns.h), so that export.cpp gathers rows and these say what a row's cells are.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "columns.h"
#include "export/export.h"
#include "game/game.h"
#include "game/results.h"
#include "session/pacing.h"
#include "session/session_store.h"

namespace warplab::exporter {

// Hit counts of one participant x game x mode over the scored phase.
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

// Who and where a shot, match or rating comes from.
struct Origin {
    const std::string& participant;
    const std::string& session;
    const std::string& game;
};

struct ShotRow {
    Origin from;
    const game::ShotResult& shot;
    std::optional<std::int64_t> skipped;  // display frames skipped from the target's appearance to the shot
};

struct RatingRow {
    Origin from;
    const game::MatchResult& match;
    const game::RatingResult& rating;
};

struct AnswerRow {
    Origin from;
    const game::AnswerResult& answer;
};

struct PacingRow {
    const std::string& participant;
    const std::string& session;
    const session::ModePacing& pacing;
};

struct HitRateRow {
    const std::string& participant;
    const std::string& game;
    const std::string& mode;
    const Tally& tally;
    bool canTimeOut;
};

struct MatchRow {
    std::string participant;
    std::string session;
    game::MatchResult match;
    std::optional<std::int64_t> skipped;  // display frames skipped during the match
};

// matches.csv's fixed columns; kRatingColumn + k (1-based) follow, one per statement of the
// longest list seen.
constexpr const char* kRatingColumn = "rating_";

struct GameRow {
    const std::string& game;
    const game::HitMeasure& measure;
};

// The flag names of a session, ;-separated, as sessions.csv lists them.
std::string joined(const std::map<std::string, std::string>& flags);

// Each CSV file's columns (docs/export.md lists them; a test checks it against these).
const std::vector<Column<SessionRow>>& sessionColumns();
const std::vector<Column<ShotRow>>& shotColumns();
const std::vector<Column<RatingRow>>& ratingColumns();
const std::vector<Column<AnswerRow>>& answerColumns();
const std::vector<Column<PacingRow>>& pacingColumns();
const std::vector<Column<HitRateRow>>& hitRateColumns();
const std::vector<Column<MatchRow>>& matchColumns();
const std::vector<Column<ConditionListing>>& conditionColumns();
const std::vector<Column<GameRow>>& gameColumns();

}  // namespace warplab::exporter
