// `warplab export`: every session file in a results folder merged into tidy CSVs for the
// analysis (docs/export.md). Read-only: session files are opened read-only and never changed.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "condition/pacing_stats.h"
#include "condition/schedule.h"

namespace warplab::game {
class Study;
struct GameTable;
}  // namespace warplab::game

namespace warplab::exporter {

struct ExportOptions {
    bool allPhases = false;  // also practice rounds, acclimation and training
    bool includeIncomplete = false;  // sessions that never finished (killed, or cut by damage)
    bool includeFlagged = false;  // sessions their run flagged (e.g. missed_frames)
    // The study plan's folder (study.json) for participants.csv; "" means the results folder's
    // parent, looked at only when the sessions were run from a plan.
    std::string studyDir;
};

// What happened to one session file.
struct ExportedSession {
    std::string file;  // relative to the results folder
    std::string status;  // "ok", "incomplete", "flagged", "duplicate" or "damaged"
    bool included = false;
    std::string why;  // for the others: the reason, one sentence
};

struct ExportSummary {
    std::vector<ExportedSession> sessions;  // in file order
    std::vector<std::string> written;  // the CSV paths
};

// The columns of each CSV exportResults writes, in order, as docs/export.md lists them.
struct CsvColumns {
    std::string file;  // "shots.csv"
    std::vector<std::string> columns;  // the fixed ones
    // Non-empty: then one column per item, named this plus 1, 2, ... (matches.csv's rating_k),
    // written before columns[numberedAt] (at the end where numberedAt is columns.size()).
    std::string numbered;
    std::size_t numberedAt = 0;
};
// The files every export writes: its own, then every registered game's own tables.
std::vector<CsvColumns> exportColumns();
// The columns of a game's own table as export writes it (its game's page lists them).
CsvColumns gameTableColumns(const game::GameTable& table);

// One condition as conditions.csv and `warplab conditions --csv` list it: its parts and
// latencies at the refresh of the protocol that runs it.
struct ConditionListing {
    std::string game;
    condition::ConditionSummary summary;
    // The part the study analyses runs it (used_in "test"); false: only practice or training
    // does (used_in "training"), so no analysed row has it.
    bool analysed = true;
    // Its frame pacing and latency distributions over condition::kPacingStatsHorizonS (seed 0).
    condition::PacingStats pacing;
};
// The conditions `study` runs, each once, in the order its fields first name them, with their pacing.
std::vector<ConditionListing> conditionsOf(const game::Study& study);
// The rows as CSV, with conditions.csv's header, to `out`.
void writeConditionTable(std::ostream& out, const std::vector<ConditionListing>& rows);

// Reads every *.warplab-session under resultsDir (sub-folders too, sorted by path), writes
// sessions.csv, shots.csv, hitrates.csv, answers.csv, conditions.csv, frametimes.csv, latency.csv,
// games.csv and pacing.csv into outDir (created when missing), each readable session's game's own
// tables (game::gameTables: the click game's matches.csv and ratings.csv, header only
// where none of its sessions is included), and participants.csv and orders.csv when there is a study plan (options.studyDir, or the
// results folder's parent once a session carries a plan_id); a study.json that does not read
// is a plan::PlanError with options.studyDir and a warning on `log` without it. Progress and one line per excluded or damaged session go to `log`.
// Throws std::runtime_error naming the folder when resultsDir is not a readable folder or
// holds no session file; a damaged session file is reported and skipped, not fatal.
ExportSummary exportResults(const std::string& resultsDir, const std::string& outDir, const ExportOptions& options,
                            std::ostream& log);

}  // namespace warplab::exporter
