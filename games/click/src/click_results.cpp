#include "click_results.h"

#include "click/click_study.h"

#include <algorithm>

#include "table/columns.h"

namespace warplab::game {
namespace {

using table::CellWriter;
using table::Column;

struct RatingOf {
    const MatchResult& match;
    const RatingResult& rating;
};

const std::vector<Column<MatchResult>>& matchColumns() {
    using F = CellWriter;
    using R = MatchResult;
    static const std::vector<Column<R>> columns = {
        {"round", [](F& f, const R& r) { f.text(r.round); }},
        {"scored_phase", [](F& f, const R& r) { f.boolean(r.scoredPhase); }},
        {"match", [](F& f, const R& r) { f.integer(r.match); }},
        {"condition", [](F& f, const R& r) { f.text(r.condition); }},
        {"stand_in", [](F& f, const R& r) { f.text(r.standIn); }},
        {"green_hits", [](F& f, const R& r) { f.integer(r.greenHits); }},
        {"red_hits", [](F& f, const R& r) { f.integer(r.redHits); }},
        {"misses", [](F& f, const R& r) { f.integer(r.misses); }},
        {"clicks", [](F& f, const R& r) { f.integer(r.clicks); }},
        {"duration_s", [](F& f, const R& r) { f.number(r.durationS); }},
    };
    return columns;
}

const std::vector<Column<RatingOf>>& ratingColumns() {
    using F = CellWriter;
    using R = RatingOf;
    static const std::vector<Column<R>> columns = {
        {"round", [](F& f, const R& r) { f.text(r.match.round); }},
        {"scored_phase", [](F& f, const R& r) { f.boolean(r.match.scoredPhase); }},
        {"match", [](F& f, const R& r) { f.integer(r.match.match); }},
        {"condition", [](F& f, const R& r) { f.text(r.match.condition); }},
        {"statement_index", [](F& f, const R& r) { f.integer(r.rating.statementIndex); }},
        {"statement", [](F& f, const R& r) { f.text(r.rating.statement); }},
        {"value", [](F& f, const R& r) { f.integer(r.rating.value); }},
        {"answered_with", [](F& f, const R& r) { f.text(r.rating.answeredWith); }},
        {"scale_min", [](F& f, const R& r) { f.integer(r.rating.scaleMin); }},
        {"scale_max", [](F& f, const R& r) { f.integer(r.rating.scaleMax); }},
    };
    return columns;
}

// The click game's own columns of shots.csv (docs/click-study.md), from a click's event detail.
const std::vector<Column<EventDetail>>& shotColumns() {
    using F = CellWriter;
    using R = EventDetail;
    static const std::vector<Column<R>> columns = {
        // Cursor to the nearest green sphere's centre on screen; empty with none.
        {"error_px", [](F& f, const R& d) { f.number(d.number("nearest_green_px")); }},
    };
    return columns;
}

}  // namespace

void writeClickShotCells(table::Cells& own, const EventDetail& click) { table::writeCells(own, shotColumns(), click); }

GameExport clickExport() { return {table::headerOf(shotColumns()), clickTables}; }

std::vector<GameTable> clickTables(const std::vector<MatchResult>& matches) {
    GameTable byMatch{"matches.csv", table::headerOf(matchColumns()), true, "rating_", {}};
    GameTable byRating{"ratings.csv", table::headerOf(ratingColumns()), false, "", {}};
    for (const MatchResult& m : matches) {
        GameTableRow row;
        row.condition = m.condition;
        row.scoredPhase = m.scoredPhase;
        row.startTime = m.endTime - m.durationS;  // a match event is logged at its last frame
        row.endTime = m.endTime;
        table::writeCells(row.cells, matchColumns(), m);
        // rating_k answers statement k - 1; one the session never reached is empty.
        int statements = 0;
        for (const RatingResult& r : m.ratings) statements = std::max(statements, r.statementIndex + 1);
        for (int k = 0; k < statements; ++k) {
            const auto r = std::find_if(m.ratings.begin(), m.ratings.end(),
                                        [&](const RatingResult& x) { return x.statementIndex == k; });
            if (r == m.ratings.end())
                row.numbered.empty();
            else
                row.numbered.integer(r->value);
        }
        byMatch.rows.push_back(std::move(row));
        for (const RatingResult& r : m.ratings) {
            GameTableRow rating;
            rating.condition = m.condition;
            rating.scoredPhase = m.scoredPhase;
            table::writeCells(rating.cells, ratingColumns(), RatingOf{m, r});
            byRating.rows.push_back(std::move(rating));
        }
    }
    return {std::move(byMatch), std::move(byRating)};
}

std::vector<GameTable> clickTables() { return clickTables(std::vector<MatchResult>{}); }

}  // namespace warplab::game
