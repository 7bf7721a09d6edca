#include "session/pacing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>
#include <utility>

#include <nlohmann/json.hpp>

namespace warplab::session {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A frame time within a tenth of the budget of it is on time: vsync intervals jitter by a
// fraction of a millisecond, and a timer's sleep overshoots by as much.
constexpr double kOverBudgetShare = 1.1;

// A held frame repeats the image before it and a frozen one holds the feedback pause's; every
// other frame shown (a render, a fill's frame, a screen) puts a new image on the display.
bool showsNewImage(const std::string& kind) { return kind != "held" && kind != "frozen" && kind != kSkippedFrameKind; }

// The nearest-rank 95th percentile and the maximum; NaN, NaN of nothing.
std::pair<double, double> p95AndMax(std::vector<double> t) {
    if (t.empty()) return {kNaN, kNaN};
    std::sort(t.begin(), t.end());
    return {t[static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(t.size()))) - 1], t.back()};
}

}  // namespace

void PacingTally::addInterval(Condition& m, const FrameRecord& f, bool newImage) {
    // A run of the condition's frames ends where another condition's frames, or a feedback pause, came
    // between: the time until the next run is no interval of the condition's cadence.
    if (f.frame != m.lastFrame + 1) {
        m.lastNewImage = -1;
        m.newImageShown = false;
        m.shownSince = 0.0;
    }
    m.lastFrame = f.kind == "frozen" ? -2 : f.frame;
    if (f.kind == "frozen") return;
    const bool skipped = f.kind == kSkippedFrameKind;
    if (!skipped) m.shownSince += f.frameMs > 0.0 ? f.frameMs : kNaN;
    if (!newImage) return;
    if (m.lastNewImage >= 0) m.intendedFrames.push_back(f.frame - m.lastNewImage);
    m.lastNewImage = f.frame;
    if (skipped) return;
    if (m.newImageShown && !std::isnan(m.shownSince)) m.shownMs.push_back(m.shownSince);
    m.newImageShown = true;
    m.shownSince = 0.0;
}

void PacingTally::add(const FrameRecord& f, const std::string& scheduledKind) {
    Condition* condition = &screens_;
    if (!f.condition.empty()) {
        // Few conditions a session: a search beats a map.
        auto it = std::find_if(conditions_.begin(), conditions_.end(),
                               [&](const Condition& m) { return m.counts.condition == f.condition; });
        if (it == conditions_.end()) {
            Condition added;
            added.counts.condition = f.condition;
            conditions_.push_back(std::move(added));
            it = conditions_.end() - 1;
        }
        condition = &*it;
    }
    const bool newImage = showsNewImage(scheduledKind.empty() ? f.kind : scheduledKind);
    addInterval(*condition, f, newImage);
    *condition->counts.newImages += newImage;
    if (f.kind == kSkippedFrameKind) {
        ++condition->counts.skipped;
        return;
    }
    ++condition->counts.shown;
    condition->counts.late += newImage && f.missedVsyncs > 0;
    if (f.frameMs > 0.0) condition->frameMs.push_back(f.frameMs);
}

std::vector<ConditionPacing> PacingTally::summary(double refreshHz) const {
    const double budget = refreshHz > 0.0 ? 1000.0 / refreshHz : kNaN;
    std::vector<ConditionPacing> out;
    auto summarize = [&](const Condition& condition) {
        ConditionPacing row = condition.counts;
        row.budgetMs = budget;
        std::vector<double> intended;
        for (const std::int64_t frames : condition.intendedFrames)
            intended.push_back(static_cast<double>(frames) * budget);
        std::tie(row.intendedP95Ms, row.intendedMaxMs) = p95AndMax(intended);
        std::tie(row.shownP95Ms, row.shownMaxMs) = p95AndMax(condition.shownMs);
        std::vector<double> t = condition.frameMs;
        if (t.empty()) {
            row.medianMs = row.p95Ms = row.maxMs = kNaN;
            return row;
        }
        std::sort(t.begin(), t.end());
        const std::size_t n = t.size();
        row.medianMs = n % 2 == 1 ? t[n / 2] : (t[n / 2 - 1] + t[n / 2]) / 2.0;
        std::tie(row.p95Ms, row.maxMs) = p95AndMax(t);
        row.overBudget = 0;
        for (const double ms : t) row.overBudget += ms > budget * kOverBudgetShare;
        return row;
    };
    for (const Condition& condition : conditions_) out.push_back(summarize(condition));
    if (screens_.counts.shown + screens_.counts.skipped > 0) out.push_back(summarize(screens_));
    return out;
}

std::vector<ConditionPacing> summarizePacing(const std::vector<FrameRecord>& frames, double refreshHz) {
    PacingTally tally;
    for (const FrameRecord& f : frames) tally.add(f);
    return tally.summary(refreshHz);
}

std::string pacingReport(const std::vector<ConditionPacing>& pacing) {
    if (pacing.empty()) return "";
    char line[512];
    std::snprintf(line, sizeof line, "pacing per condition (a display frame every %.2f ms):\n",
                  pacing.front().budgetMs);
    std::string out = line;
    for (const ConditionPacing& p : pacing) {
        const double all = static_cast<double>(std::max<std::int64_t>(1, p.shown + p.skipped));
        // How far short of the display it fell: the frames it showed a second of the display's.
        const double refreshHz = 1000.0 / p.budgetMs;
        std::snprintf(line, sizeof line,
                      "  %s: %lld shown (%.1f a second of %.0f), %lld late (%.1f %%), %lld skipped (%.1f %%); frame "
                      "time median %.1f ms, p95 %.1f, max %.1f\n",
                      p.condition.empty() ? "(screens)" : p.condition.c_str(), static_cast<long long>(p.shown),
                      static_cast<double>(p.shown) / all * refreshHz, refreshHz, static_cast<long long>(p.late),
                      100.0 * static_cast<double>(p.late) / all, static_cast<long long>(p.skipped),
                      100.0 * static_cast<double>(p.skipped) / all, p.medianMs, p.p95Ms, p.maxMs);
        out += line;
        if (!std::isnan(p.intendedMaxMs)) {
            // The condition's own unevenness beside what the display showed of it.
            out.pop_back();
            std::snprintf(line, sizeof line, "; new images %lld, intended p95 %.1f ms, max %.1f",
                          static_cast<long long>(p.newImages.value_or(0)), p.intendedP95Ms, p.intendedMaxMs);
            out += line;
            if (!std::isnan(p.shownMaxMs)) {
                std::snprintf(line, sizeof line, ", shown p95 %.1f, max %.1f", p.shownP95Ms, p.shownMaxMs);
                out += line;
            }
            out += "\n";
        }
    }
    return out;
}

std::string pacingText(const std::vector<ConditionPacing>& pacing) {
    nlohmann::json list = nlohmann::json::array();
    // NaN has no JSON form: null.
    auto number = [](double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); };
    for (const ConditionPacing& p : pacing)
        list.push_back({{"mode", p.condition},
                        {"shown", p.shown},
                        {"late", p.late},
                        {"skipped", p.skipped},
                        {"median_ms", number(p.medianMs)},
                        {"p95_ms", number(p.p95Ms)},
                        {"max_ms", number(p.maxMs)},
                        {"budget_ms", number(p.budgetMs)},
                        {"over_budget", p.overBudget},
                        {"new_images", p.newImages ? nlohmann::json(*p.newImages) : nlohmann::json()},
                        {"intended_p95_ms", number(p.intendedP95Ms)},
                        {"intended_max_ms", number(p.intendedMaxMs)},
                        {"shown_p95_ms", number(p.shownP95Ms)},
                        {"shown_max_ms", number(p.shownMaxMs)}});
    return list.dump();
}

bool parsePacing(const std::string& text, std::vector<ConditionPacing>& out) {
    const auto list = nlohmann::json::parse(text, nullptr, false);
    if (!list.is_array()) return false;
    out.clear();
    auto number = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : kNaN; };
    for (const auto& o : list) {
        if (!o.is_object() || !o.contains("mode") || !o["mode"].is_string()) return false;
        ConditionPacing p;
        p.condition = o["mode"].get<std::string>();
        p.shown = o.value("shown", std::int64_t{0});
        p.late = o.value("late", std::int64_t{0});
        p.skipped = o.value("skipped", std::int64_t{0});
        p.medianMs = number(o.value("median_ms", nlohmann::json()));
        p.p95Ms = number(o.value("p95_ms", nlohmann::json()));
        p.maxMs = number(o.value("max_ms", nlohmann::json()));
        p.budgetMs = number(o.value("budget_ms", nlohmann::json()));
        p.overBudget = o.value("over_budget", std::int64_t{0});
        const nlohmann::json newImages = o.value("new_images", nlohmann::json());
        p.newImages = newImages.is_number_integer() ? std::optional(newImages.get<std::int64_t>()) : std::nullopt;
        p.intendedP95Ms = number(o.value("intended_p95_ms", nlohmann::json()));
        p.intendedMaxMs = number(o.value("intended_max_ms", nlohmann::json()));
        p.shownP95Ms = number(o.value("shown_p95_ms", nlohmann::json()));
        p.shownMaxMs = number(o.value("shown_max_ms", nlohmann::json()));
        out.push_back(p);
    }
    return true;
}

}  // namespace warplab::session
