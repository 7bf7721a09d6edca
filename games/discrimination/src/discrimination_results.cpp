#include "discrimination_results.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "game/event_detail.h"
#include "spellings.h"
#include "table/columns.h"

namespace warplab::discrimination {
namespace {

using F = table::CellWriter;

// A row of discrimination_trials.csv: an answered trial.
struct TrialRow {
    const session::EventRecord& event;
    game::EventDetail detail;
    const ProcedureSpec* spec;  // nullptr for a procedure the protocol does not have
};

const std::vector<table::Column<TrialRow>>& trialColumns() {
    using R = TrialRow;
    static const std::vector<table::Column<R>> columns = {
        {"procedure", [](F& f, const R& r) { f.text(r.detail.text("procedure")); }},
        {"trial", [](F& f, const R& r) { f.integer(r.event.trial); }},
        {"procedure_trial", [](F& f, const R& r) { f.integer(r.detail.integer("procedure_trial", -1)); }},
        {"method", [](F& f, const R& r) { f.text(r.spec ? protocol::nameOf(r.spec->method) : ""); }},
        {"dimension", [](F& f, const R& r) { f.text(r.detail.text("dimension")); }},
        {"reference", [](F& f, const R& r) { f.text(r.event.condition); }},
        {"level", [](F& f, const R& r) { f.number(r.detail.number("level")); }},
        {"stimulus", [](F& f, const R& r) { f.number(r.detail.number("stimulus")); }},
        {"test_condition", [](F& f, const R& r) { f.text(r.detail.text("test_condition")); }},
        {"test_interval", [](F& f, const R& r) { f.integer(r.detail.integer("test_interval", -1)); }},
        {"answer", [](F& f, const R& r) { f.integer(r.detail.integer("answer", -1)); }},
        {"correct", [](F& f, const R& r) { f.integer(r.detail.boolean("correct", false) ? 1 : 0); }},
        {"answered_with", [](F& f, const R& r) { f.text(r.detail.text("answered_with")); }},
        {"answer_s", [](F& f, const R& r) { f.number(r.detail.number("answer_s")); }},
    };
    return columns;
}

// A row of thresholds.csv: one procedure of one session, its answers replayed through its method.
struct ThresholdRow {
    const DiscriminationProtocol& protocol;
    const ProcedureSpec& spec;
    std::size_t trials = 0;
    bool finished = false;
    double fitLapse = 0.0;
    adaptive::Estimate threshold{game::kNotApplicable, game::kNotApplicable, game::kNotApplicable};
    std::optional<adaptive::Estimate> slope, lapse;
};

void estimate(F& f, const std::optional<adaptive::Estimate>& e, double adaptive::Estimate::*part) {
    f.number(e ? (*e).*part : game::kNotApplicable);
}

const std::vector<table::Column<ThresholdRow>>& thresholdColumns() {
    using R = ThresholdRow;
    using E = adaptive::Estimate;
    static const std::vector<table::Column<R>> columns = {
        {"procedure", [](F& f, const R& r) { f.text(r.spec.name); }},
        {"method", [](F& f, const R& r) { f.text(protocol::nameOf(r.spec.method)); }},
        {"dimension", [](F& f, const R& r) { f.text(condition::dimensionName(r.spec.dimension)); }},
        {"reference", [](F& f, const R& r) { f.text(r.spec.reference); }},
        {"units", [](F& f, const R& r) { f.text(condition::dimensionUnits(r.spec.dimension)); }},
        {"trials", [](F& f, const R& r) { f.integer(static_cast<long long>(r.trials)); }},
        {"finished", [](F& f, const R& r) { f.integer(r.finished ? 1 : 0); }},
        {"shape", [](F& f, const R& r) { f.text(protocol::nameOf(r.spec.shape)); }},
        {"scale", [](F& f, const R& r) { f.text(protocol::nameOf(r.spec.scale)); }},
        {"guess", [](F& f, const R&) { f.number(0.5); }},
        {"percent_correct", [](F& f, const R& r) { f.number(r.spec.percentCorrect); }},
        {"fit_lapse", [](F& f, const R& r) { f.number(r.fitLapse); }},
        {"threshold", [](F& f, const R& r) { f.number(r.threshold.mean); }},
        {"threshold_low", [](F& f, const R& r) { f.number(r.threshold.low); }},
        {"threshold_high", [](F& f, const R& r) { f.number(r.threshold.high); }},
        {"slope", [](F& f, const R& r) { estimate(f, r.slope, &E::mean); }},
        {"slope_low", [](F& f, const R& r) { estimate(f, r.slope, &E::low); }},
        {"slope_high", [](F& f, const R& r) { estimate(f, r.slope, &E::high); }},
        {"lapse", [](F& f, const R& r) { estimate(f, r.lapse, &E::mean); }},
        {"lapse_low", [](F& f, const R& r) { estimate(f, r.lapse, &E::low); }},
        {"lapse_high", [](F& f, const R& r) { estimate(f, r.lapse, &E::high); }},
    };
    return columns;
}

game::GameTable trialsTable() { return {"discrimination_trials.csv", table::headerOf(trialColumns()), false, "", {}}; }
game::GameTable thresholdsTable() { return {"thresholds.csv", table::headerOf(thresholdColumns()), false, "", {}}; }

// The procedure's answers (level index, correct), in order, replayed through its method.
ThresholdRow thresholdRow(const DiscriminationProtocol& p, const ProcedureSpec& spec,
                          const std::vector<std::pair<std::size_t, bool>>& answers) {
    ThresholdRow row{p,  spec, 0, false, 0.0, {game::kNotApplicable, game::kNotApplicable, game::kNotApplicable},
                     {}, {}};
    row.trials = answers.size();
    const adaptive::ProcedureSettings settings = procedureSettings(p, spec);
    adaptive::Procedure procedure(settings, 0);  // the seed orders constant stimuli only: not their end
    for (const auto& a : answers)
        if (!procedure.finished()) procedure.update(a.second);
    row.finished = procedure.finished();
    row.fitLapse =
        std::accumulate(spec.lapses.begin(), spec.lapses.end(), 0.0) / static_cast<double>(spec.lapses.size());
    switch (spec.method) {
        case adaptive::Method::QuestPlus: {
            adaptive::QuestPlus quest(settings.quest);
            for (const auto& a : answers) quest.update(a.first, a.second);
            row.threshold = thresholdAt(quest, spec.percentCorrect);
            row.slope = quest.slope();
            row.lapse = quest.lapse();
            row.fitLapse = row.lapse->mean;
            break;
        }
        case adaptive::Method::Staircase: {
            adaptive::Staircase staircase(settings.staircase);
            for (const auto& a : answers) staircase.update(a.second);
            row.threshold.mean = staircase.threshold(static_cast<std::size_t>(spec.reversalsAveraged));
            break;
        }
        case adaptive::Method::ConstantStimuli: break;  // the analysis fits its trials
    }
    return row;
}

}  // namespace

adaptive::Estimate thresholdAt(const adaptive::QuestPlus& quest, double percentCorrect) {
    const adaptive::QuestPlusSettings& s = quest.settings();
    std::vector<std::pair<double, double>> weighted;  // (stimulus at percentCorrect, posterior)
    std::size_t i = 0;
    for (double t : s.thresholds)
        for (double b : s.slopes)
            for (double l : s.lapses)
                weighted.emplace_back(s.function.stimulusAt(percentCorrect, t, b, l), quest.posterior()[i++]);
    adaptive::Estimate e;
    for (const auto& [x, w] : weighted) e.mean += x * w;
    std::sort(weighted.begin(), weighted.end());
    double cumulative = 0.0;
    bool low = false;
    e.high = weighted.back().first;
    for (const auto& [x, w] : weighted) {
        cumulative += w;
        if (!low && cumulative >= 0.025) {
            e.low = x;
            low = true;
        }
        if (cumulative >= 0.975) {
            e.high = x;
            break;
        }
    }
    return e;
}

std::vector<game::GameTable> emptyTables() { return {trialsTable(), thresholdsTable()}; }

std::vector<game::GameTable> resultTables(const DiscriminationProtocol& p,
                                          const std::vector<session::EventRecord>& events) {
    std::vector<game::GameTable> tables = emptyTables();
    std::vector<std::vector<std::pair<std::size_t, bool>>> answers(p.procedures.size());
    for (const session::EventRecord& e : events) {
        if (e.type != "judgement") continue;
        const game::EventDetail detail(e.detailJson);
        const std::string name = detail.text("procedure");
        const auto spec = std::find_if(p.procedures.begin(), p.procedures.end(),
                                       [&](const ProcedureSpec& s) { return s.name == name; });
        game::GameTableRow row;
        row.condition = e.condition;
        row.scoredPhase = true;
        table::writeCells(row.cells, trialColumns(),
                          TrialRow{e, detail, spec == p.procedures.end() ? nullptr : &*spec});
        tables[0].rows.push_back(std::move(row));
        if (spec == p.procedures.end()) continue;
        const auto level = std::find(spec->levels.begin(), spec->levels.end(), detail.number("level"));
        if (level == spec->levels.end()) continue;
        answers[static_cast<std::size_t>(spec - p.procedures.begin())].emplace_back(
            static_cast<std::size_t>(level - spec->levels.begin()), detail.boolean("correct", false));
    }
    for (std::size_t i = 0; i < p.procedures.size(); ++i) {
        game::GameTableRow row;
        row.condition = p.procedures[i].reference;
        row.scoredPhase = true;
        table::writeCells(row.cells, thresholdColumns(), thresholdRow(p, p.procedures[i], answers[i]));
        tables[1].rows.push_back(std::move(row));
    }
    return tables;
}

}  // namespace warplab::discrimination
