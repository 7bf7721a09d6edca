#include "tables.h"

#include "game/registry.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <utility>
#include <stdexcept>

namespace warplab::exporter {
namespace {

void optionalInteger(CellWriter& f, const std::optional<std::int64_t>& v) {
    if (v)
        f.integer(*v);
    else
        f.empty();
}

// A cell that only a readable session has.
template <class F>
std::function<void(CellWriter&, const SessionRow&)> whenRead(F cell) {
    return [cell](CellWriter& f, const SessionRow& r) {
        if (r.data == nullptr)
            f.empty();
        else
            cell(f, r);
    };
}

// A human session's cm_per_360 as it played: its player says "human (cm_per_360=C, dpi=D, ...)",
// where C = 0 (as live runs before they wrote the value used did) means the protocol's own turn
// per count, which at the mouse's D counts per inch is a full turn in 2 pi / (turn per count) / D
// inches. None for other players, and for a protocol whose mouse turns nothing.
std::optional<double> cmPer360Used(const SessionRow& r) {
    const std::string& player = r.data->header.player;
    if (session::playerKind(player) != "human") return std::nullopt;
    const auto field = [&](const std::string& name) -> std::optional<double> {
        const std::size_t at = player.find(name + "=");
        if (at == std::string::npos) return std::nullopt;
        try {
            return std::stod(player.substr(at + name.size() + 1));
        } catch (const std::exception&) {
            return std::nullopt;
        }
    };
    const std::optional<double> cm = field("cm_per_360"), dpi = field("dpi");
    if (cm && *cm > 0.0) return cm;
    const double radiansPerCount = r.study->mouseRadiansPerCount();
    if (!dpi || !(*dpi > 0.0) || !(radiansPerCount > 0.0)) return std::nullopt;
    constexpr double kTwoPi = 6.283185307179586476925;
    return kTwoPi / radiansPerCount / *dpi * 2.54;
}

}  // namespace

std::optional<std::int64_t> positionOf(const Positions& positions, const std::string& condition, bool scoredPhase) {
    if (!scoredPhase) return std::nullopt;
    const auto found = positions.find(condition);
    if (found == positions.end()) return std::nullopt;
    return found->second;
}

std::string joined(const std::map<std::string, std::string>& flags) {
    std::string out;
    for (const auto& [name, text] : flags) out += (out.empty() ? "" : ";") + name;
    return out;
}

const std::vector<Column<SessionRow>>& sessionColumns() {
    using F = CellWriter;
    using R = SessionRow;
    static const std::vector<Column<R>> columns = {
        {"file", [](F& f, const R& r) { f.text(r.file); }},
        {"participant", whenRead([](F& f, const R& r) { f.text(r.data->header.participant); })},
        {"game", whenRead([](F& f, const R& r) { f.text(r.study->game()); })},
        {"protocol", whenRead([](F& f, const R& r) { f.text(r.study->name()); })},
        {"seed", whenRead([](F& f, const R& r) { f.integer(static_cast<std::int64_t>(r.data->header.seed)); })},
        {"started_at", whenRead([](F& f, const R& r) { f.text(r.data->header.startedAt); })},
        {"player", whenRead([](F& f, const R& r) { f.text(r.data->header.player); })},
        // A simulated participant's traits (a JSON object), "" for anyone else.
        {"player_model", whenRead([](F& f, const R& r) { f.text(r.data->header.playerModel); })},
        {"session_id", whenRead([](F& f, const R& r) { f.text(r.data->header.sessionId); })},
        {"plan_id", whenRead([](F& f, const R& r) { f.text(r.data->header.planId); })},
        {"completed", whenRead([](F& f, const R& r) { f.boolean(r.data->completed); })},
        {"flags", whenRead([](F& f, const R& r) { f.text(joined(r.data->flags)); })},
        {"status", [](F& f, const R& r) { f.text(r.outcome.status); }},
        {"included", [](F& f, const R& r) { f.boolean(r.outcome.included); }},
        {"trials", whenRead([](F& f, const R& r) { f.integer(static_cast<std::int64_t>(r.results->shots.size())); })},
        // The rows of its game's span tables (the click game's matches); 0 for a game without.
        {"matches", whenRead([](F& f, const R& r) {
             std::int64_t spans = 0;
             for (const game::GameTable& t : r.results->tables)
                 if (t.spans) spans += static_cast<std::int64_t>(t.rows.size());
             f.integer(spans);
         })},
        // How its frames kept pace with the display (pacing.csv has them per condition).
        {"display_frames",
         whenRead([](F& f, const R& r) { f.integer(static_cast<std::int64_t>(r.data->frames.size())); })},
        {"late_frames", whenRead([](F& f, const R& r) {
             f.integer(std::count_if(r.data->frames.begin(), r.data->frames.end(),
                                     [](const session::FrameRecord& x) { return x.missedVsyncs > 0; }));
         })},
        {"skipped_frames", whenRead([](F& f, const R& r) {
             f.integer(std::count_if(r.data->frames.begin(), r.data->frames.end(), [](const session::FrameRecord& x) {
                 return x.kind == session::kSkippedFrameKind;
             }));
         })},
        {"note", [](F& f, const R& r) { f.text(r.outcome.why); }},
        {"player_kind", whenRead([](F& f, const R& r) { f.text(session::playerKind(r.data->header.player)); })},
        {"cm_per_360", whenRead([](F& f, const R& r) {
             const std::optional<double> cm = cmPer360Used(r);
             if (cm)
                 f.number(*cm);
             else
                 f.empty();
         })},
    };
    return columns;
}

const std::vector<Column<ShotRow>>& shotLeadingColumns() {
    using F = CellWriter;
    using R = ShotRow;
    static const std::vector<Column<R>> columns = {
        {"participant", [](F& f, const R& r) { f.text(r.from.participant); }},
        {"session", [](F& f, const R& r) { f.text(r.from.session); }},
        {"game", [](F& f, const R& r) { f.text(r.from.game); }},
        {"phase", [](F& f, const R& r) { f.text(r.shot.phase); }},
        {"scored_phase", [](F& f, const R& r) { f.boolean(r.shot.scoredPhase); }},
        {"trial", [](F& f, const R& r) { f.integer(r.shot.trial); }},
        {"condition", [](F& f, const R& r) { f.text(r.shot.condition); }},
        {"outcome", [](F& f, const R& r) { f.text(r.shot.outcome); }},
        {"hit", [](F& f, const R& r) { f.boolean(r.shot.hit); }},
        {"world_outcome", [](F& f, const R& r) { f.text(r.shot.worldOutcome); }},
        {"displayed_outcome", [](F& f, const R& r) { f.text(r.shot.displayedOutcome); }},
        {"time_s", [](F& f, const R& r) { f.number(r.shot.time); }},
        {"spawn_time_s", [](F& f, const R& r) { f.number(r.shot.spawnTime); }},
        {"aim_time_s", [](F& f, const R& r) { f.number(r.shot.aimTime); }},
    };
    return columns;
}

const std::vector<Column<ShotRow>>& shotTrailingColumns() {
    using F = CellWriter;
    using R = ShotRow;
    static const std::vector<Column<R>> columns = {
        {"skipped_frames", [](F& f, const R& r) { optionalInteger(f, r.skipped); }},
        {"player_kind", [](F& f, const R& r) { f.text(r.from.playerKind); }},
        {"condition_position",
         [](F& f, const R& r) {
             optionalInteger(f, positionOf(r.from.positions, r.shot.condition, r.shot.scoredPhase));
         }},
        {"frame_time_p95_ms", [](F& f, const R& r) { f.number(r.frameTimeP95S * 1000.0); }},
    };
    return columns;
}

ShotsLayout shotsLayout() {
    ShotsLayout out;
    out.header = headerOf(shotLeadingColumns());
    const auto games = game::gameShotColumns();
    for (const auto& [gameName, own] : games) out.gameColumns.insert(out.gameColumns.end(), own.begin(), own.end());
    // A game's cells go under its own columns, each game's a run of its own (registerGame).
    for (const auto& [gameName, own] : games) {
        std::vector<int>& at = out.at[gameName];
        for (const std::string& name : out.gameColumns) {
            const auto found = std::find(own.begin(), own.end(), name);
            at.push_back(found == own.end() ? -1 : static_cast<int>(found - own.begin()));
        }
    }
    out.header.insert(out.header.end(), out.gameColumns.begin(), out.gameColumns.end());
    for (const std::string& name : headerOf(shotTrailingColumns())) out.header.push_back(name);
    return out;
}

void writeShot(CsvFile& file, const ShotsLayout& layout, const ShotRow& row) {
    writeCells(file, shotLeadingColumns(), row);
    // A readable session's game is a registered one, so it has its entry.
    file.cells(row.shot.own.rearranged(layout.at.at(row.from.game)));
    writeCells(file, shotTrailingColumns(), row);
}

const std::vector<Column<AnswerRow>>& answerColumns() {
    using F = CellWriter;
    using R = AnswerRow;
    static const std::vector<Column<R>> columns = {
        {"participant", [](F& f, const R& r) { f.text(r.from.participant); }},
        {"session", [](F& f, const R& r) { f.text(r.from.session); }},
        {"game", [](F& f, const R& r) { f.text(r.from.game); }},
        {"block", [](F& f, const R& r) { f.text(r.answer.block); }},
        {"scored_phase", [](F& f, const R& r) { f.boolean(r.answer.scoredPhase); }},
        {"block_index", [](F& f, const R& r) { f.integer(r.answer.blockIndex); }},
        {"condition", [](F& f, const R& r) { f.text(r.answer.condition); }},
        {"question_index", [](F& f, const R& r) { f.integer(r.answer.questionIndex); }},
        {"question_id", [](F& f, const R& r) { f.text(r.answer.questionId); }},
        {"kind", [](F& f, const R& r) { f.text(r.answer.kind); }},
        {"prompt", [](F& f, const R& r) { f.text(r.answer.prompt); }},
        // A text answer has no number: an empty cell (NA).
        {"value",
         [](F& f, const R& r) {
             if (r.answer.value)
                 f.integer(*r.answer.value);
             else
                 f.empty();
         }},
        {"text", [](F& f, const R& r) { f.text(r.answer.text); }},
        {"answered_with", [](F& f, const R& r) { f.text(r.answer.answeredWith); }},
        // The answers offered, both ends included; none for a text question.
        {"scale_min",
         [](F& f, const R& r) {
             if (r.answer.kind == "text")
                 f.empty();
             else
                 f.integer(r.answer.scaleMin);
         }},
        {"scale_max",
         [](F& f, const R& r) {
             if (r.answer.kind == "text")
                 f.empty();
             else
                 f.integer(r.answer.scaleMax);
         }},
        {"time_s", [](F& f, const R& r) { f.number(r.answer.time); }},
        {"answer_s", [](F& f, const R& r) { f.number(r.answer.answerS); }},
        {"player_kind", [](F& f, const R& r) { f.text(r.from.playerKind); }},
        // None for a block of mixed conditions (condition "").
        {"condition_position",
         [](F& f, const R& r) {
             optionalInteger(f, positionOf(r.from.positions, r.answer.condition, r.answer.scoredPhase));
         }},
    };
    return columns;
}

const std::vector<Column<PacingRow>>& pacingColumns() {
    using F = CellWriter;
    using R = PacingRow;
    static const std::vector<Column<R>> columns = {
        {"participant", [](F& f, const R& r) { f.text(r.participant); }},
        {"session", [](F& f, const R& r) { f.text(r.session); }},
        {"condition", [](F& f, const R& r) { f.text(r.pacing.condition); }},
        {"shown", [](F& f, const R& r) { f.integer(r.pacing.shown); }},
        {"late", [](F& f, const R& r) { f.integer(r.pacing.late); }},
        {"skipped", [](F& f, const R& r) { f.integer(r.pacing.skipped); }},
        {"median_ms", [](F& f, const R& r) { f.number(r.pacing.medianMs); }},
        {"p95_ms", [](F& f, const R& r) { f.number(r.pacing.p95Ms); }},
        {"max_ms", [](F& f, const R& r) { f.number(r.pacing.maxMs); }},
        {"budget_ms", [](F& f, const R& r) { f.number(r.pacing.budgetMs); }},
        {"over_budget", [](F& f, const R& r) { f.integer(r.pacing.overBudget); }},
        {"player_kind", [](F& f, const R& r) { f.text(r.playerKind); }},
        // After the columns above, so that they keep their places: the condition's own unevenness
        // against what was shown (session::ConditionPacing). A summary stored before these were kept
        // has none of them: empty cells, not zeros that claim a count.
        {"new_images", [](F& f, const R& r) { optionalInteger(f, r.pacing.newImages); }},
        {"intended_p95_ms", [](F& f, const R& r) { f.number(r.pacing.intendedP95Ms); }},
        {"intended_max_ms", [](F& f, const R& r) { f.number(r.pacing.intendedMaxMs); }},
        {"shown_p95_ms", [](F& f, const R& r) { f.number(r.pacing.shownP95Ms); }},
        {"shown_max_ms", [](F& f, const R& r) { f.number(r.pacing.shownMaxMs); }},
    };
    return columns;
}

const std::vector<Column<HitRateRow>>& hitRateColumns() {
    using F = CellWriter;
    using R = HitRateRow;
    static const std::vector<Column<R>> columns = {
        {"participant", [](F& f, const R& r) { f.text(r.participant); }},
        {"game", [](F& f, const R& r) { f.text(r.game); }},
        {"condition", [](F& f, const R& r) { f.text(r.condition); }},
        {"shots", [](F& f, const R& r) { f.integer(r.tally.shots); }},
        {"hits", [](F& f, const R& r) { f.integer(r.tally.hits); }},
        // The click game has no timeouts: an empty cell, not a zero that claims it measured some.
        {"timeouts",
         [](F& f, const R& r) {
             if (r.canTimeOut)
                 f.integer(r.tally.timeouts);
             else
                 f.empty();
         }},
        // A condition played without a shot or click has no rate: an empty cell (NA), never 0/0.
        {"hit_rate",
         [](F& f, const R& r) {
             if (r.tally.shots == 0)
                 f.empty();
             else
                 f.number(static_cast<double>(r.tally.hits) / static_cast<double>(r.tally.shots));
         }},
        {"player_kind", [](F& f, const R& r) { f.text(r.playerKinds); }},
    };
    return columns;
}

const std::vector<Column<GameTableEntry>>& gameTableLeadingColumns() {
    using F = CellWriter;
    using R = GameTableEntry;
    static const std::vector<Column<R>> columns = {
        {"participant", [](F& f, const R& r) { f.text(r.participant); }},
        {"session", [](F& f, const R& r) { f.text(r.session); }},
    };
    return columns;
}

const std::vector<Column<GameTableEntry>>& gameTableSpanColumns() {
    using F = CellWriter;
    using R = GameTableEntry;
    static const std::vector<Column<R>> columns = {
        {"skipped_frames", [](F& f, const R& r) { optionalInteger(f, r.skipped); }},
    };
    return columns;
}

// After the numbered columns, so that the columns before them keep their places.
const std::vector<Column<GameTableEntry>>& gameTableTrailingColumns() {
    using F = CellWriter;
    using R = GameTableEntry;
    static const std::vector<Column<R>> columns = {
        {"player_kind", [](F& f, const R& r) { f.text(r.playerKind); }},
        {"condition_position", [](F& f, const R& r) { optionalInteger(f, r.position); }},
    };
    return columns;
}

const std::vector<Column<GameTableEntry>>& gameTableSpanTrailingColumns() {
    using F = CellWriter;
    using R = GameTableEntry;
    static const std::vector<Column<R>> columns = {
        {"frame_time_p95_ms", [](F& f, const R& r) { f.number(r.frameTimeP95S * 1000.0); }},
    };
    return columns;
}

// The conditions the sessions were run in, with their parts and latencies at the refresh they
// ran at, so the analysis keeps no list of its own. An unset fill rate is an empty cell.
const std::vector<Column<ConditionListing>>& conditionColumns() {
    using F = CellWriter;
    using R = ConditionListing;
    auto ms = [](double seconds) { return seconds * 1000.0; };
    static const std::vector<Column<R>> columns = {
        {"condition", [](F& f, const R& r) { f.text(r.summary.condition.name); }},
        {"render_hz", [](F& f, const R& r) { f.number(r.summary.condition.renderHz); }},
        {"lag_frames", [](F& f, const R& r) { f.integer(r.summary.lagFrames); }},
        {"fill", [](F& f, const R& r) { f.text(r.summary.condition.fill); }},
        {"late_warp", [](F& f, const R& r) { f.text(condition::lateWarpName(r.summary.condition.lateWarp)); }},
        {"view_latency_min_ms", [ms](F& f, const R& r) { f.number(ms(r.summary.viewS.min)); }},
        {"view_latency_max_ms", [ms](F& f, const R& r) { f.number(ms(r.summary.viewS.max)); }},
        {"scene_latency_min_ms", [ms](F& f, const R& r) { f.number(ms(r.summary.sceneS.min)); }},
        {"scene_latency_max_ms", [ms](F& f, const R& r) { f.number(ms(r.summary.sceneS.max)); }},
        {"fill_hz",
         [](F& f, const R& r) {
             const condition::Condition& c = r.summary.condition;
             if (c.fillKind() == condition::Fill::Hold)
                 f.empty();
             else
                 f.number(c.fillHz.value_or(r.summary.refreshHz));
         }},
        {"refresh_hz", [](F& f, const R& r) { f.number(r.summary.refreshHz); }},
        {"game", [](F& f, const R& r) { f.text(r.game); }},
        {"description", [](F& f, const R& r) { f.text(r.summary.condition.description); }},
        {"used_in", [](F& f, const R& r) { f.text(r.analysed ? "test" : "training"); }},
        // Its pacing over condition::kPacingStatsHorizonS (docs/frame-pacing.md, "Pacing as numbers").
        {"mean_fps", [](F& f, const R& r) { f.number(r.pacing.frameTimes.meanFps); }},
        {"low_1pct_fps", [](F& f, const R& r) { f.number(r.pacing.frameTimes.low1Fps); }},
        {"low_5pct_fps", [](F& f, const R& r) { f.number(r.pacing.frameTimes.low5Fps); }},
        {"frame_time_median_ms", [ms](F& f, const R& r) { f.number(ms(r.pacing.frameTimes.medianS)); }},
        {"frame_time_p95_ms", [ms](F& f, const R& r) { f.number(ms(r.pacing.frameTimes.p95S)); }},
        {"frame_time_p99_ms", [ms](F& f, const R& r) { f.number(ms(r.pacing.frameTimes.p99S)); }},
        {"frame_time_max_ms", [ms](F& f, const R& r) { f.number(ms(r.pacing.frameTimes.maxS)); }},
        {"stutters", [](F& f, const R& r) { f.integer(r.pacing.frameTimes.stutters); }},
        {"view_latency_median_ms", [ms](F& f, const R& r) { f.number(ms(r.pacing.viewS.median)); }},
        {"view_latency_p95_ms", [ms](F& f, const R& r) { f.number(ms(r.pacing.viewS.p95)); }},
        {"scene_latency_median_ms", [ms](F& f, const R& r) { f.number(ms(r.pacing.sceneS.median)); }},
        {"scene_latency_p95_ms", [ms](F& f, const R& r) { f.number(ms(r.pacing.sceneS.p95)); }},
    };
    return columns;
}

// The frame times behind conditions.csv's pacing columns, for the report's frame-time graphs.
const std::vector<Column<FrameTimeRow>>& frameTimeColumns() {
    using F = CellWriter;
    using R = FrameTimeRow;
    static const std::vector<Column<R>> columns = {
        {"game", [](F& f, const R& r) { f.text(r.listing.game); }},
        {"condition", [](F& f, const R& r) { f.text(r.listing.summary.condition.name); }},
        {"refresh_hz", [](F& f, const R& r) { f.number(r.listing.summary.refreshHz); }},
        // From the start of the horizon, so every condition's graph starts at 0.
        {"time_s",
         [](F& f, const R& r) {
             const condition::PacingStats& p = r.listing.pacing;
             f.number(p.frames.shownAtS[r.index] - static_cast<double>(p.firstFrame) / r.listing.summary.refreshHz);
         }},
        {"frame_time_ms", [](F& f, const R& r) { f.number(r.listing.pacing.frames.frameTimeS[r.index] * 1000.0); }},
    };
    return columns;
}

std::vector<LatencyRow> latencyRows(const ConditionListing& listing) {
    std::vector<LatencyRow> rows;
    const auto add = [&](const char* kind, const std::vector<condition::ConditionSchedule::LatencySpan>& spans) {
        // A step in (from, to] waits shownAt - tau: uniformly over [shownAt - to, shownAt - from),
        // as likely as the span is long. A steady cadence repeats a few spans over and over; they
        // differ only by rounding, so spans a nanosecond apart are one, keeping the widest bounds.
        std::map<std::pair<std::int64_t, std::int64_t>, LatencyRow> same;
        double total = 0.0;
        for (const auto& s : spans) {
            const double from = s.shownAt - s.to, to = s.shownAt - s.from;
            const auto key = std::make_pair(std::llround(from * 1e9), std::llround(to * 1e9));
            const auto [at, fresh] = same.try_emplace(key, LatencyRow{listing, kind, from, to, 0.0});
            if (!fresh) {
                at->second.fromS = std::min(at->second.fromS, from);
                at->second.toS = std::max(at->second.toS, to);
            }
            at->second.weight += s.to - s.from;
            total += s.to - s.from;
        }
        for (auto& [key, row] : same) {
            row.weight /= total;
            rows.push_back(row);
        }
    };
    add("view", listing.pacing.viewSpans);
    add("scene", listing.pacing.sceneSpans);
    return rows;
}

// The latency distributions behind conditions.csv's latency columns, exactly, for the report's
// latency histograms.
const std::vector<Column<LatencyRow>>& latencyColumns() {
    using F = CellWriter;
    using R = LatencyRow;
    static const std::vector<Column<R>> columns = {
        {"game", [](F& f, const R& r) { f.text(r.listing.game); }},
        {"condition", [](F& f, const R& r) { f.text(r.listing.summary.condition.name); }},
        {"refresh_hz", [](F& f, const R& r) { f.number(r.listing.summary.refreshHz); }},
        {"kind", [](F& f, const R& r) { f.text(r.kind); }},
        {"latency_ms_from", [](F& f, const R& r) { f.number(r.fromS * 1000.0); }},
        {"latency_ms_to", [](F& f, const R& r) { f.number(r.toS * 1000.0); }},
        {"weight", [](F& f, const R& r) { f.number(r.weight); }},
    };
    return columns;
}

// What each game's hit rate counts, in its own words, so a report words a game's measure without
// knowing the game.
const std::vector<Column<GameRow>>& gameColumns() {
    using F = CellWriter;
    using R = GameRow;
    static const std::vector<Column<R>> columns = {
        {"game", [](F& f, const R& r) { f.text(r.game); }},
        {"hits_are", [](F& f, const R& r) { f.text(r.measure.hitsAre); }},
        {"shots_are", [](F& f, const R& r) { f.text(r.measure.shotsAre); }},
        {"tables", [](F& f, const R& r) { f.text(r.tables); }},
    };
    return columns;
}

}  // namespace warplab::exporter
