#include "export/export.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <stdexcept>
#include <tuple>

#include "tables.h"
#include "table/csv.h"
#include "participants_csv.h"
#include "condition/schedule.h"
#include "game/registry.h"
#include "plan/status.h"
#include "plan/study_plan.h"
#include "session/pacing.h"
#include "session/session_store.h"

namespace warplab::exporter {
namespace fs = std::filesystem;

namespace {

constexpr const char* kSessionSuffix = ".warplab-session";

// conditionsOf without their pacing, which export works out once per condition, not per session.
std::vector<ConditionListing> listedConditions(const game::Study& study);

// Every regular *.warplab-session file under dir, sorted, so that every export of the same
// folder lists (and de-duplicates) them in the same order. Hidden files are sessions still
// being created (SessionWriter links them into place once their header is whole).
std::vector<fs::path> sessionFiles(const fs::path& dir, std::ostream& log) {
    std::vector<fs::path> files;
    std::error_code ec;
    fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
    if (ec) throw std::runtime_error("cannot read the results folder '" + dir.string() + "': " + ec.message());
    for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
        const fs::path& p = it->path();
        const std::string name = p.filename().string();
        if (name.empty() || name.front() == '.') {
            if (it->is_directory(ec)) it.disable_recursion_pending();
            continue;
        }
        const std::string suffix = kSessionSuffix;
        if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        // Regular files only: a named pipe or device under that name would block the reader.
        if (it->is_regular_file(ec))
            files.push_back(p);
        else
            log << "export: '" << p.string() << "' is not a regular file, skipped\n";
    }
    // Unreadable folders are skipped (skip_permission_denied); any other listing error ends
    // the iteration early and would silently drop sessions, so it ends the export instead.
    if (ec) throw std::runtime_error("cannot list the results folder '" + dir.string() + "': " + ec.message());
    std::sort(files.begin(), files.end());
    return files;
}

// The display frames a live session skipped (never shown: docs/session-format.md), to count
// those within a stretch of it.
class SkippedFrames {
public:
    SkippedFrames(const session::SessionData& data, double refreshHz) : refreshHz_(refreshHz) {
        for (const auto& f : data.frames)
            if (f.kind == session::kSkippedFrameKind) frames_.push_back(f.frame);
    }
    // Skipped frames after display time `from` up to and including `to`, seconds; nullopt
    // where `from` is unknown (NaN).
    std::optional<std::int64_t> between(double from, double to) const {
        if (std::isnan(from) || std::isnan(to)) return std::nullopt;
        const auto first = std::upper_bound(frames_.begin(), frames_.end(), std::llround(from * refreshHz_));
        const auto last = std::upper_bound(frames_.begin(), frames_.end(), std::llround(to * refreshHz_));
        return static_cast<std::int64_t>(last - first);
    }
    std::int64_t total() const { return static_cast<std::int64_t>(frames_.size()); }

private:
    double refreshHz_;
    std::vector<std::int64_t> frames_;  // in order: the frames table is
};

// The display frames of a session that showed a new image (docs/frame-pacing.md: any but a held
// frame, a frozen feedback pause, a screen or a skipped frame), for the frame times of a stretch.
class NewImages {
public:
    NewImages(const session::SessionData& data, double refreshHz) : refreshHz_(refreshHz) {
        using condition::FrameKind;
        const std::string made[] = {condition::frameKindName(FrameKind::Rendered),
                                    condition::frameKindName(FrameKind::Warped),
                                    condition::frameKindName(FrameKind::Interpolated)};
        for (const auto& f : data.frames)
            if (std::find(std::begin(made), std::end(made), f.kind) != std::end(made)) frames_.push_back(f.frame);
    }
    // The nearest-rank 95th percentile of the frame times between the new images shown over the
    // second of display time up to and including `end` (s), within the trial, from `start` (a
    // pause or screen before it is no stutter of it); NaN where fewer than two were shown.
    double p95Before(double start, double end) const {
        constexpr double kStretchS = 1.0;
        if (std::isnan(end)) return std::numeric_limits<double>::quiet_NaN();
        const double from = std::isnan(start) ? end - kStretchS : std::max(start, end - kStretchS);
        const auto first = std::lower_bound(frames_.begin(), frames_.end(), std::llround(from * refreshHz_));
        const auto last = std::upper_bound(frames_.begin(), frames_.end(), std::llround(end * refreshHz_));
        std::vector<double> times;
        for (auto it = first; it != last && std::next(it) != last; ++it)
            times.push_back(static_cast<double>(*std::next(it) - *it) / refreshHz_);
        return condition::percentile(times, 95.0);
    }

private:
    double refreshHz_;
    std::vector<std::int64_t> frames_;  // in order: the frames table is
};

// Session id -> the file of the resumed session that carries it on (its header's `resumed`).
using CarriedOn = std::map<std::string, std::string>;

CarriedOn carriedOn(const std::vector<fs::path>& files, const fs::path& resultsDir) {
    CarriedOn out;
    std::error_code ec;
    for (const fs::path& file : files) {
        session::SessionHeader h;
        try {
            h = session::readSessionHeader(file.string());
        } catch (const session::SessionError&) {
            continue;  // add() says why it cannot be read
        }
        for (const session::Resumption& r : h.resumed)
            out.emplace(r.sessionId, fs::relative(file, resultsDir, ec).generic_string());
    }
    return out;
}

// The plan folder of the folder exported: DIR itself when it holds the plan (export DIR, whose
// sessions are in DIR/results and its rigs' DIR/results/RIG), else DIR for DIR/results (as
// `study init` makes them) or for one rig's DIR/results/RIG.
fs::path planFolderOf(const std::string& resultsDir) {
    fs::path dir = fs::absolute(resultsDir).lexically_normal();
    if (dir.filename().empty()) dir = dir.parent_path();
    std::error_code ec;
    if (fs::exists(dir / "study.json", ec)) return dir;
    const fs::path above = dir.parent_path().parent_path();
    if (dir.parent_path().filename() == "results" && fs::exists(above / "study.json", ec)) return above;
    return dir.parent_path();
}

class Exporter {
public:
    Exporter(const fs::path& outDir, const ExportOptions& options, CarriedOn carriedOn)
        : options_(options),
          carriedOn_(std::move(carriedOn)),
          sessions_(file(outDir, "sessions.csv"), headerOf(sessionColumns())),
          shotsLayout_(shotsLayout()),
          shots_(file(outDir, "shots.csv"), shotsLayout_.header),
          answers_(file(outDir, "answers.csv"), headerOf(answerColumns())),
          pacing_(file(outDir, "pacing.csv"), headerOf(pacingColumns())) {
        for (auto& [gameName, shape] : game::gameTables()) gameFiles_.push_back({gameName, std::move(shape), {}, 0});
    }

    ExportedSession add(const fs::path& path, const std::string& name) {
        ExportedSession out{name, "ok", false, ""};
        session::SessionData data;
        std::unique_ptr<game::Study> study;
        try {
            data = session::readSession(path.string());
            study = game::parseStudy(data.header.protocolJson, path.string() + " (its stored protocol)");
        } catch (const std::exception& e) {
            out.status = "damaged";
            out.why = e.what();
            writeCells(sessions_, sessionColumns(), SessionRow{name, out});
            sessions_.endRow();
            return out;
        }
        const session::SessionHeader& h = data.header;
        if (!h.planId.empty()) ++planIds_[h.planId];
        // What makes two files copies of one session: its id from format version 3 on (a copy
        // keeps it; two runs never share one, not even twins started in the same millisecond
        // with the same participant and seed), what the header says in older files.
        const SessionKey key = h.sessionId.empty()
            ? SessionKey{"", h.participant, h.startedAt, h.seed, h.player, h.protocolJson}
            : SessionKey{h.sessionId, "", "", 0, "", ""};
        const char* const sameWhat =
            h.sessionId.empty() ? "participant, start time, seed, player, protocol" : "session_id";
        // A copy of a session already counted intact is a duplicate. Only intact copies count as
        // the original: a damaged or cut copy listed first must not shut out a whole one after it.
        if (const auto by = carriedOn_.find(h.sessionId); !h.sessionId.empty() && by != carriedOn_.end()) {
            // Its kept trials were copied into the resumed session: counted there, once.
            out.status = "resumed";
            out.why = "carried on by " + by->second + ", which holds its completed trials";
        } else if (const auto seen = firstWith_.find(key); seen != firstWith_.end()) {
            out.status = "duplicate";
            out.why = "the same session as " + seen->second + " (" + sameWhat + ")";
        } else {
            if (data.completed && !data.damaged) {
                firstWith_.emplace(key, name);
                if (const auto partial = partialCopy_.find(key); partial != partialCopy_.end())
                    warnings_.push_back(name + " and " + partial->second +
                                        " are copies of one session, the latter incomplete or damaged and included "
                                        "(--include-incomplete): keep one of them");
            } else if (options_.includeIncomplete) {
                partialCopy_.emplace(key, name);
            }
            if (data.damaged) {
                // Readable up to the damage: what survives is kept only when asked for, like an
                // incomplete session's, but it is not called incomplete (replay's exit code 4).
                out.status = "damaged";
                out.why = data.note;
                out.included = options_.includeIncomplete;
            } else if (!data.completed) {
                out.status = "incomplete";
                out.why = data.note.empty() ? "it never finished" : data.note;
                out.included = options_.includeIncomplete;
            } else if (!data.flags.empty()) {
                out.status = "flagged";
                out.why = "flagged " + joined(data.flags) + ": " + data.flags.begin()->second;
                out.included = options_.includeFlagged;
            } else {
                out.included = true;
            }
        }

        const game::SessionResults results = study->results(data.events);
        measures_.emplace(study->game(), results.measure);
        checkTables(study->game(), results.tables);
        const std::string kind = session::playerKind(h.player);
        // What participants.csv needs of a plan's session, so it is not read a second time.
        if (!h.planId.empty()) planSessions_.push_back(plan::factsOf(path.string(), data, *study));
        // Rigs lock only their own folders: a participant who played a protocol on two of them
        // (or in two folders copied together) is said, not silently counted twice.
        if (!h.planId.empty() && out.included)
            completeIn_[{h.planId, h.participant, study->name()}].insert(fs::path(name).parent_path().generic_string());
        addConditions(*study, name);
        writeCells(sessions_, sessionColumns(), SessionRow{name, out, &data, study.get(), &results});
        sessions_.endRow();
        const SkippedFrames skipped(data, study->refreshHz());
        writePacing(h.participant, name, data, kind);
        if (out.included)
            write({h.participant, name, study->game(), kind, positionsOf(results)}, results, skipped,
                  NewImages(data, study->refreshHz()));
        return out;
    }

    // Said once every session has been read: copies of one session both included, a
    // participant's protocol included from two folders (rigs).
    std::vector<std::string> warnings() const {
        std::vector<std::string> out = warnings_;
        for (const auto& [key, folders] : completeIn_) {
            if (folders.size() < 2) continue;
            std::string where;
            for (const std::string& folder : folders)
                where += (where.empty() ? "" : ", ") + (folder.empty() ? "." : folder);
            out.push_back("participant " + std::get<1>(key) + " has complete sessions of " + std::get<2>(key) + " in " +
                          std::to_string(folders.size()) + " folders (" + where +
                          "), all included: played on two rigs; move the one played by mistake out of the results "
                          "folder");
        }
        return out;
    }
    // The study plans the readable sessions were run from: plan id, how many sessions.
    const std::map<std::string, int>& planIds() const { return planIds_; }
    // The readable sessions run from a plan, as the plan's status reads them.
    const std::vector<plan::SessionFacts>& planSessions() const { return planSessions_; }

    // The conditions `study` runs, new ones (by game, name and refresh) in order of first use.
    // One name meaning two things in one export is said, since the analysis keys on names.
    // A condition one session runs only in training and another in its test is used in a test.
    void addConditions(const game::Study& study, const std::string& session) {
        for (ConditionListing& listing : listedConditions(study)) {
            const condition::Condition& c = listing.summary.condition;
            const auto same = std::find_if(conditions_.begin(), conditions_.end(), [&](const ConditionListing& r) {
                return r.game == listing.game && r.summary.condition.name == c.name &&
                    r.summary.refreshHz == listing.summary.refreshHz;
            });
            if (same == conditions_.end()) {
                // Once per condition, not per session: it walks the horizon's frames.
                listing.pacing = condition::pacingStats(condition::ConditionSchedule(c, listing.summary.refreshHz));
                conditions_.push_back(std::move(listing));
                continue;
            }
            same->analysed = same->analysed || listing.analysed;
            if (!same->summary.condition.sameParts(c)) {
                warnings_.push_back(session + " defines condition " + c.name +
                                    " with other parts than an earlier session: conditions.csv lists the first");
            }
        }
    }

    std::vector<std::string> close(const fs::path& outDir) {
        CsvFile hitrates(file(outDir, "hitrates.csv"), headerOf(hitRateColumns()));
        for (const auto& [key, t] : tallies_) {
            const auto& [participant, gameName, condition] = key;
            std::string kinds;
            for (const std::string& kind : kinds_[participant]) kinds += (kinds.empty() ? "" : ";") + kind;
            writeCells(hitrates, hitRateColumns(),
                       HitRateRow{participant, gameName, condition, t, timeoutGames_.count(gameName) != 0, kinds});
            hitrates.endRow();
        }
        // Every condition a readable session's protocol runs, once per game and refresh.
        CsvFile conditions(file(outDir, "conditions.csv"), headerOf(conditionColumns()));
        for (const ConditionListing& row : conditions_) {
            writeCells(conditions, conditionColumns(), row);
            conditions.endRow();
        }
        CsvFile frameTimes(file(outDir, "frametimes.csv"), headerOf(frameTimeColumns()));
        for (const ConditionListing& row : conditions_)
            for (std::size_t i = 0; i < row.pacing.frames.frameTimeS.size(); ++i) {
                writeCells(frameTimes, frameTimeColumns(), FrameTimeRow{row, i});
                frameTimes.endRow();
            }
        CsvFile latency(file(outDir, "latency.csv"), headerOf(latencyColumns()));
        for (const ConditionListing& row : conditions_)
            for (const LatencyRow& span : latencyRows(row)) {
                writeCells(latency, latencyColumns(), span);
                latency.endRow();
            }
        // The games of the readable sessions, in the order the registry knows them.
        CsvFile games(file(outDir, "games.csv"), headerOf(gameColumns()));
        for (const std::string& name : game::gameNames()) {
            const auto measure = measures_.find(name);
            if (measure == measures_.end()) continue;
            std::string tables;
            for (const GameFile& g : gameFiles_)
                if (g.game == name) tables += (tables.empty() ? "" : ";") + g.shape.file;
            writeCells(games, gameColumns(), GameRow{name, measure->second, tables});
            games.endRow();
        }
        std::vector<std::string> written;
        for (CsvFile* f :
             {&sessions_, &shots_, &answers_, &hitrates, &conditions, &frameTimes, &latency, &games, &pacing_}) {
            f->close();
            written.push_back(f->path());
        }
        for (const GameFile& g : gameFiles_) written.push_back(writeGameTable(outDir, g));
        return written;
    }

private:
    static std::string file(const fs::path& dir, const char* name) { return (dir / name).string(); }

    // The session's pacing per condition: as its live run stored it, else (a headless session, an
    // older or interrupted one) from its frames table.
    void writePacing(const std::string& participant, const std::string& session, const session::SessionData& data,
                     const std::string& kind) {
        std::vector<session::ConditionPacing> pacing;
        const auto stored = data.summaries.find("pacing");
        if (stored == data.summaries.end() || !session::parsePacing(stored->second, pacing))
            pacing = session::summarizePacing(data.frames, data.header.refreshHz);
        for (const session::ConditionPacing& p : pacing) {
            writeCells(pacing_, pacingColumns(), PacingRow{participant, session, p, kind});
            pacing_.endRow();
        }
    }

    // Each condition's place in the order the session's scored phase first presents it: its
    // first scored shot or match (a match without a click still ran its condition).
    static Positions positionsOf(const game::SessionResults& results) {
        std::vector<std::pair<double, std::string>> firsts;
        for (const auto& s : results.shots)
            if (s.scoredPhase) firsts.emplace_back(s.time, s.condition);
        for (const game::GameTable& t : results.tables)
            for (const game::GameTableRow& r : t.rows)
                if (t.spans && r.scoredPhase) firsts.emplace_back(r.startTime, r.condition);
        std::stable_sort(firsts.begin(), firsts.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        Positions positions;
        for (const auto& [time, condition] : firsts)
            positions.emplace(condition, static_cast<std::int64_t>(positions.size()) + 1);
        return positions;
    }

    void write(const Origin& from, const game::SessionResults& results, const SkippedFrames& skipped,
               const NewImages& newImages) {
        const std::string& participant = from.participant;
        const std::string& gameName = from.game;
        kinds_[participant].insert(from.playerKind);
        if (results.canTimeOut) timeoutGames_.insert(gameName);
        for (const auto& s : results.shots) {
            if (!s.scoredPhase && !options_.allPhases) continue;
            writeShot(shots_, shotsLayout_,
                      ShotRow{from, s, skipped.between(s.spawnTime, s.time), newImages.p95Before(s.spawnTime, s.time)});
            shots_.endRow();
            if (!s.scoredPhase) continue;  // hit rates: the scored phase only, always
            Tally& t = tallies_[{participant, gameName, s.condition}];
            ++t.shots;
            t.hits += s.hit;
            t.timeouts += s.timeout;
        }
        for (const game::GameTable& t : results.tables) {
            GameFile& g = *gameFileOf(t.file);
            for (const game::GameTableRow& r : t.rows) {
                // A scored span without a shot (a match without a click) still ran its condition:
                // hitrates.csv has its row, with 0 shots, so that every participant x condition
                // the study ran is there.
                if (t.spans && r.scoredPhase) tallies_.try_emplace({participant, gameName, r.condition});
                if (!r.scoredPhase && !options_.allPhases) continue;
                GameTableEntry e{participant,
                                 from.session,
                                 from.playerKind,
                                 r,
                                 positionOf(from.positions, r.condition, r.scoredPhase),
                                 std::nullopt,
                                 std::numeric_limits<double>::quiet_NaN()};
                if (t.spans) {
                    e.skipped = skipped.between(r.startTime, r.endTime);
                    e.frameTimeP95S = newImages.p95Before(r.startTime, r.endTime);
                }
                g.numbered = std::max(g.numbered, r.numbered.size());
                g.entries.push_back(std::move(e));
            }
        }
        for (const auto& a : results.answers) {
            if (!a.scoredPhase && !options_.allPhases) continue;
            writeCells(answers_, answerColumns(), AnswerRow{from, a});
            answers_.endRow();
        }
    }

    ExportOptions options_;
    CarriedOn carriedOn_;
    CsvFile sessions_;
    ShotsLayout shotsLayout_;  // before shots_, whose header it gives
    CsvFile shots_, answers_, pacing_;
    std::map<std::tuple<std::string, std::string, std::string>, Tally> tallies_;  // participant, game, condition
    std::set<std::string> timeoutGames_;  // games whose trials can time out (shooter)
    std::map<std::string, std::set<std::string>> kinds_;  // participant -> the kinds of their included sessions
    std::map<std::string, game::HitMeasure> measures_;  // every game of a readable session
    // A game's own table, gathered over the sessions and written at the end, when the widest
    // row's numbered columns are known; header only when no session of the game is included.
    struct GameFile {
        std::string game;
        game::GameTable shape;  // its columns, without rows
        std::vector<GameTableEntry> entries;
        std::size_t numbered = 0;
    };
    std::vector<GameFile> gameFiles_;  // every registered game's, in the order registered

    GameFile* gameFileOf(const std::string& name) {
        for (GameFile& g : gameFiles_)
            if (g.shape.file == name) return &g;
        return nullptr;
    }

    // A session's tables are the ones its game registered (game::registerGame), column for column.
    void checkTables(const std::string& gameName, const std::vector<game::GameTable>& tables) {
        for (const game::GameTable& t : tables) {
            const GameFile* g = gameFileOf(t.file);
            if (g == nullptr || g->game != gameName || g->shape.columns != t.columns || g->shape.spans != t.spans ||
                g->shape.numbered != t.numbered)
                throw std::logic_error("the " + gameName + " game's results have a table " + t.file +
                                       " it did not register with these columns (game::registerGame)");
        }
    }

    std::string writeGameTable(const fs::path& outDir, const GameFile& g) {
        CsvColumns shape = gameTableColumns(g.shape);
        std::vector<std::string> header(shape.columns.begin(), shape.columns.begin() + shape.numberedAt);
        for (std::size_t k = 1; k <= g.numbered; ++k) header.push_back(shape.numbered + std::to_string(k));
        header.insert(header.end(), shape.columns.begin() + shape.numberedAt, shape.columns.end());
        CsvFile out(file(outDir, g.shape.file.c_str()), header);
        for (const GameTableEntry& e : g.entries) {
            writeCells(out, gameTableLeadingColumns(), e);
            out.cells(e.row.cells);
            if (g.shape.spans) writeCells(out, gameTableSpanColumns(), e);
            out.cells(e.row.numbered);
            for (std::size_t k = e.row.numbered.size(); k < g.numbered; ++k) out.empty();
            writeCells(out, gameTableTrailingColumns(), e);
            if (g.shape.spans) writeCells(out, gameTableSpanTrailingColumns(), e);
            out.endRow();
        }
        out.close();
        return out.path();
    }
    using SessionKey = std::tuple<std::string, std::string, std::string, std::uint64_t, std::string, std::string>;
    std::map<SessionKey, std::string> firstWith_;  // intact sessions, by what identifies them
    std::map<SessionKey, std::string> partialCopy_;  // included incomplete or damaged ones
    std::vector<std::string> warnings_;
    std::vector<ConditionListing> conditions_;
    std::map<std::string, int> planIds_;
    std::vector<plan::SessionFacts> planSessions_;
    // (plan id, participant, protocol name) -> the folders of its included sessions
    std::map<std::tuple<std::string, std::string, std::string>, std::set<std::string>> completeIn_;
};

}  // namespace

std::vector<CsvColumns> exportColumns() {
    std::vector<CsvColumns> out = {{"sessions.csv", headerOf(sessionColumns()), "", 0},
                                   {"shots.csv", shotsLayout().header, "", 0},
                                   {"hitrates.csv", headerOf(hitRateColumns()), "", 0},
                                   {"answers.csv", headerOf(answerColumns()), "", 0},
                                   {"conditions.csv", headerOf(conditionColumns()), "", 0},
                                   {"frametimes.csv", headerOf(frameTimeColumns()), "", 0},
                                   {"latency.csv", headerOf(latencyColumns()), "", 0},
                                   {"pacing.csv", headerOf(pacingColumns()), "", 0},
                                   {"games.csv", headerOf(gameColumns()), "", 0},
                                   {"participants.csv", headerOf(participantColumns()), "", 0},
                                   {"orders.csv", headerOf(orderColumns()), "", 0}};
    for (const auto& [gameName, table] : game::gameTables()) out.push_back(gameTableColumns(table));
    return out;
}

CsvColumns gameTableColumns(const game::GameTable& table) {
    CsvColumns out{table.file, headerOf(gameTableLeadingColumns()), table.numbered, 0};
    out.columns.insert(out.columns.end(), table.columns.begin(), table.columns.end());
    if (table.spans)
        for (const std::string& name : headerOf(gameTableSpanColumns())) out.columns.push_back(name);
    out.numberedAt = out.columns.size();
    for (const std::string& name : headerOf(gameTableTrailingColumns())) out.columns.push_back(name);
    if (table.spans)
        for (const std::string& name : headerOf(gameTableSpanTrailingColumns())) out.columns.push_back(name);
    return out;
}

ExportSummary exportResults(const std::string& resultsDir, const std::string& outDir, const ExportOptions& options,
                            std::ostream& log) {
    std::error_code ec;
    if (!fs::is_directory(resultsDir, ec))
        throw std::runtime_error("results folder '" + resultsDir + "' " +
                                 (fs::exists(resultsDir, ec) ? "is not a folder." : "does not exist."));
    const std::vector<fs::path> files = sessionFiles(resultsDir, log);
    if (files.empty())
        throw std::runtime_error("results folder '" + resultsDir + "' holds no session files (*" + kSessionSuffix +
                                 "), nothing to export.");
    fs::create_directories(outDir, ec);
    if (ec || !fs::is_directory(outDir, ec)) {
        // The reason a read-only mount or a file in the way gives, not just that it failed.
        const std::string why = ec ? ec.message() : "a file of that name is in the way";
        throw std::runtime_error("cannot create the output folder '" + outDir + "': " + why + ".");
    }

    // The study plan participants.csv lists: --study's, read first so that a bad one ends the
    // export before it writes anything.
    std::optional<plan::StudyPlan> studyPlan;
    std::string planDir = options.studyDir;
    if (!planDir.empty()) studyPlan = plan::readPlan(planDir);

    ExportSummary summary;
    Exporter exporter(outDir, options, carriedOn(files, resultsDir));
    for (std::size_t i = 0; i < files.size(); ++i) {
        const std::string name = fs::relative(files[i], resultsDir, ec).generic_string();
        const ExportedSession s = exporter.add(files[i], ec ? files[i].string() : name);
        log << "export: [" << i + 1 << "/" << files.size() << "] " << s.file << ": "
            << (s.included ? "included" : (s.status == "damaged" ? "skipped" : "excluded"));
        if (s.status != "ok") log << " (" << s.status << ": " << s.why << ")";
        log << "\n";
        summary.sessions.push_back(s);
    }
    summary.written = exporter.close(outDir);
    for (const auto& warning : exporter.warnings()) log << "export: warning: " << warning << "\n";
    // Else the plan beside the results folder, when the sessions were run from one.
    if (!studyPlan && !exporter.planIds().empty()) {
        planDir = planFolderOf(resultsDir).string();
        const std::string planFile = (fs::path(planDir) / "study.json").string();
        if (!fs::exists(planFile, ec)) {
            log << "export: warning: the sessions were run from a study plan, but there is no '" << planFile
                << "'; participants.csv is not written (--study DIR names the plan's folder)\n";
        } else {
            try {
                studyPlan = plan::readPlan(planDir);
            } catch (const plan::PlanError& e) {
                log << "export: warning: participants.csv is not written: " << e.what() << "\n";
            }
        }
    }
    if (studyPlan) {
        for (const auto& [id, count] : exporter.planIds())
            if (id != studyPlan->id)
                log << "export: warning: " << count << (count == 1 ? " session was" : " sessions were")
                    << " run from another study plan (plan_id " << id << ") than '"
                    << (fs::path(planDir) / "study.json").string() << "' (id " << studyPlan->id
                    << "); participants.csv does not count them\n";
        for (std::string& path : writeParticipants(outDir, *studyPlan, exporter.planSessions()))
            summary.written.push_back(std::move(path));
    }

    std::map<std::string, int> byStatus;
    int included = 0;
    for (const auto& s : summary.sessions) {
        ++byStatus[s.status];
        included += s.included;
    }
    log << "export: " << files.size() << " session files, " << included << " included";
    for (const auto& [status, count] : byStatus)
        if (status != "ok") log << ", " << count << " " << status;
    log << "\n";
    if (!options.includeIncomplete && byStatus.count("incomplete") != 0)
        log << "export: incomplete sessions are left out; --include-incomplete keeps their completed trials\n";
    if (!options.includeFlagged && byStatus.count("flagged") != 0)
        log << "export: flagged sessions are left out; --include-flagged keeps them\n";
    return summary;
}

std::vector<ConditionListing> conditionsOf(const game::Study& study) {
    std::vector<ConditionListing> rows = listedConditions(study);
    for (ConditionListing& row : rows)
        row.pacing = condition::pacingStats(condition::ConditionSchedule(row.summary.condition, row.summary.refreshHz));
    return rows;
}

namespace {

std::vector<ConditionListing> listedConditions(const game::Study& study) {
    const std::vector<std::string> analysed = study.analysedConditions();
    std::vector<ConditionListing> rows;
    for (const std::string& name : study.conditionNames()) {
        const bool seen = std::any_of(rows.begin(), rows.end(),
                                      [&](const ConditionListing& r) { return r.summary.condition.name == name; });
        if (seen) continue;
        rows.push_back({study.game(),
                        condition::summarize(study.conditions().at(name), study.refreshHz()),
                        std::find(analysed.begin(), analysed.end(), name) != analysed.end(),
                        {}});
    }
    return rows;
}

}  // namespace

void writeConditionTable(std::ostream& out, const std::vector<ConditionListing>& rows) {
    CsvFile table(out, headerOf(conditionColumns()));
    for (const ConditionListing& row : rows) {
        writeCells(table, conditionColumns(), row);
        table.endRow();
    }
    table.close();
}

}  // namespace warplab::exporter
