#include "export/export.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <stdexcept>
#include <tuple>

#include "export/csv.h"
#include "game/registry.h"
#include "session/session_store.h"

namespace warplab::exporter {
namespace fs = std::filesystem;

namespace {

constexpr const char* kSessionSuffix = ".warplab-session";

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
        if (it->is_regular_file(ec)) files.push_back(p);
        else log << "export: '" << p.string() << "' is not a regular file, skipped\n";
    }
    // Unreadable folders are skipped (skip_permission_denied); any other listing error ends
    // the iteration early and would silently drop sessions, so it ends the export instead.
    if (ec) throw std::runtime_error("cannot list the results folder '" + dir.string() + "': " + ec.message());
    std::sort(files.begin(), files.end());
    return files;
}

std::string joined(const std::map<std::string, std::string>& flags) {
    std::string out;
    for (const auto& [name, text] : flags) out += (out.empty() ? "" : ";") + name;
    return out;
}

// Hit counts of one participant x game x mode over the scored phase.
struct Tally {
    std::int64_t shots = 0, hits = 0, timeouts = 0;
};

class Exporter {
public:
    Exporter(const fs::path& outDir, const ExportOptions& options)
        : options_(options),
          sessions_(file(outDir, "sessions.csv"), {"file", "participant", "game", "protocol", "seed", "started_at",
                                                   "player", "completed", "flags", "status", "included", "trials",
                                                   "matches", "note"}),
          shots_(file(outDir, "shots.csv"),
                 {"participant", "session", "game", "phase", "scored_phase", "trial", "mode", "outcome", "hit",
                  "world_outcome", "displayed_outcome", "time_s", "spawn_time_s", "aim_time_s", "angular_error_deg",
                  "error_px", "difficulty", "target_speed"}),
          ratings_(file(outDir, "ratings.csv"), {"participant", "session", "round", "scored_phase", "match", "mode",
                                                 "statement_index", "statement", "value", "answered_with"}) {}

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
            sessions_.text(name).empty().empty().empty().empty().empty().empty().empty().empty()
                .text(out.status).boolean(false).empty().empty().text(out.why);
            sessions_.endRow();
            return out;
        }
        const session::SessionHeader& h = data.header;
        const auto key = std::make_tuple(h.participant, h.startedAt, h.seed, h.player, h.protocolJson);
        // A copy of a session already counted intact is a duplicate. Only intact copies count as
        // the original: a damaged or cut copy listed first must not shut out a whole one after it.
        if (const auto seen = firstWith_.find(key); seen != firstWith_.end()) {
            out.status = "duplicate";
            out.why = "the same session as " + seen->second + " (participant, start time, seed, player, protocol)";
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
        sessions_.text(name).text(h.participant).text(study->game()).text(study->name())
            .integer(static_cast<std::int64_t>(h.seed)).text(h.startedAt).text(h.player).boolean(data.completed)
            .text(joined(data.flags)).text(out.status).boolean(out.included)
            .integer(static_cast<std::int64_t>(results.shots.size()))
            .integer(static_cast<std::int64_t>(results.matches.size())).text(out.why);
        sessions_.endRow();
        if (out.included) write(h.participant, name, study->game(), results);
        return out;
    }

    // Said once every session has been read: copies of one session both included.
    const std::vector<std::string>& warnings() const { return warnings_; }

    std::vector<std::string> close(const fs::path& outDir) {
        CsvFile hitrates(file(outDir, "hitrates.csv"),
                         {"participant", "game", "mode", "shots", "hits", "timeouts", "hit_rate"});
        for (const auto& [key, t] : tallies_) {
            const auto& [participant, gameName, mode] = key;
            hitrates.text(participant).text(gameName).text(mode).integer(t.shots).integer(t.hits);
            // The click game has no timeouts: an empty cell, not a zero that claims it measured some.
            if (timeoutGames_.count(gameName) != 0) hitrates.integer(t.timeouts);
            else hitrates.empty();
            hitrates.number(static_cast<double>(t.hits) / static_cast<double>(t.shots));
            hitrates.endRow();
        }
        // One rating column per statement of the longest list seen (rating_1 is statement 0).
        std::vector<std::string> header{"participant", "session", "round", "scored_phase", "match", "mode",
                                        "stand_in", "green_hits", "red_hits", "misses", "clicks", "duration_s"};
        for (int k = 1; k <= ratingColumns_; ++k) header.push_back("rating_" + std::to_string(k));
        CsvFile matches(file(outDir, "matches.csv"), header);
        for (const auto& [participant, session, m] : matches_) {
            matches.text(participant).text(session).text(m.round).boolean(m.scoredPhase).integer(m.match)
                .text(m.mode).text(m.standIn).integer(m.greenHits).integer(m.redHits).integer(m.misses)
                .integer(m.clicks).number(m.durationS);
            for (int k = 0; k < ratingColumns_; ++k) {
                const auto r = std::find_if(m.ratings.begin(), m.ratings.end(),
                                            [&](const game::RatingResult& x) { return x.statementIndex == k; });
                if (r == m.ratings.end()) matches.empty();
                else matches.integer(r->value);
            }
            matches.endRow();
        }
        std::vector<std::string> written;
        for (CsvFile* f : {&sessions_, &shots_, &ratings_, &hitrates, &matches}) {
            f->close();
            written.push_back(f->path());
        }
        return written;
    }

private:
    static std::string file(const fs::path& dir, const char* name) { return (dir / name).string(); }

    void write(const std::string& participant, const std::string& session, const std::string& gameName,
               const game::SessionResults& results) {
        if (results.canTimeOut) timeoutGames_.insert(gameName);
        for (const auto& s : results.shots) {
            if (!s.scoredPhase && !options_.allPhases) continue;
            shots_.text(participant).text(session).text(gameName).text(s.phase).boolean(s.scoredPhase)
                .integer(s.trial).text(s.mode).text(s.outcome).boolean(s.hit).text(s.worldOutcome)
                .text(s.displayedOutcome).number(s.time).number(s.spawnTime).number(s.aimTime)
                .number(s.angularErrorDeg).number(s.errorPx).number(s.difficulty).number(s.targetSpeed);
            shots_.endRow();
            if (!s.scoredPhase) continue;  // hit rates: the scored phase only, always
            Tally& t = tallies_[{participant, gameName, s.mode}];
            ++t.shots;
            t.hits += s.hit;
            t.timeouts += s.timeout;
        }
        for (const auto& m : results.matches) {
            if (!m.scoredPhase && !options_.allPhases) continue;
            for (const auto& r : m.ratings) {
                ratingColumns_ = std::max(ratingColumns_, r.statementIndex + 1);
                ratings_.text(participant).text(session).text(m.round).boolean(m.scoredPhase).integer(m.match)
                    .text(m.mode).integer(r.statementIndex).text(r.statement).integer(r.value).text(r.answeredWith);
                ratings_.endRow();
            }
            matches_.emplace_back(participant, session, m);
        }
    }

    ExportOptions options_;
    CsvFile sessions_, shots_, ratings_;
    std::map<std::tuple<std::string, std::string, std::string>, Tally> tallies_;  // participant, game, mode
    std::set<std::string> timeoutGames_;  // games whose trials can time out (shooter)
    std::vector<std::tuple<std::string, std::string, game::MatchResult>> matches_;
    int ratingColumns_ = 0;
    using SessionKey = std::tuple<std::string, std::string, std::uint64_t, std::string, std::string>;
    std::map<SessionKey, std::string> firstWith_;    // intact sessions, by what identifies them
    std::map<SessionKey, std::string> partialCopy_;  // included incomplete or damaged ones
    std::vector<std::string> warnings_;
};

}  // namespace

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
    if (!fs::is_directory(outDir, ec)) throw std::runtime_error("cannot create the output folder '" + outDir + "'.");

    ExportSummary summary;
    Exporter exporter(outDir, options);
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

}  // namespace warplab::exporter
