// Export's pacing beyond conditions.csv: latency.csv, each condition's view and scene latency
// distributions as exact spans, checked against conditions.csv's own latency columns; and
// pacing.csv's columns from the live pacing summary, for sessions that stored them and for
// sessions stored before they were kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "export_test_support.h"
#include "session/pacing.h"
#include "session/session_store.h"

namespace warplab::app {
namespace {

using namespace exporttest;

struct Span {
    double from = 0.0, to = 0.0, weight = 0.0;
};

// The q-quantile of a mix of uniform spans, found by bisection on the share of weight below x:
// independent of the sweep condition::pacingStats uses for conditions.csv's medians.
double quantileOf(const std::vector<Span>& spans, double q) {
    const auto below = [&](double x) {
        double share = 0.0;
        for (const Span& s : spans) share += s.weight * std::clamp((x - s.from) / (s.to - s.from), 0.0, 1.0);
        return share;
    };
    double lo = spans.front().from, hi = spans.front().to;
    for (const Span& s : spans) lo = std::min(lo, s.from), hi = std::max(hi, s.to);
    for (int i = 0; i < 200; ++i) {
        const double mid = (lo + hi) / 2.0;
        (below(mid) < q ? lo : hi) = mid;
    }
    return hi;
}

TEST(ExportLatency, EachConditionsSpansWeighOneAndCoverItsLatencyRange) {
    const std::string results = scratch("latency/results"), out = scratch("latency/out");
    headless("shooter-quick.json", "P01", results, 1);
    exportQuietly(results, out);
    // (condition, kind) -> its spans, in file order.
    std::map<std::tuple<std::string, std::string>, std::vector<Span>> spans;
    for (const Row& r : readCsv(out + "/latency.csv")) {
        EXPECT_EQ(r.at("game"), "shooter");
        EXPECT_EQ(r.at("refresh_hz"), "120");
        ASSERT_TRUE(r.at("kind") == "view" || r.at("kind") == "scene") << r.at("kind");
        const Span s{std::stod(r.at("latency_ms_from")), std::stod(r.at("latency_ms_to")), std::stod(r.at("weight"))};
        EXPECT_LT(s.from, s.to) << r.at("condition");
        EXPECT_GT(s.weight, 0.0) << r.at("condition");
        spans[{r.at("condition"), r.at("kind")}].push_back(s);
    }
    const std::vector<Row> conditions = readCsv(out + "/conditions.csv");
    ASSERT_EQ(conditions.size(), 3u);
    EXPECT_EQ(spans.size(), 2 * conditions.size()) << "a view and a scene distribution per condition";
    for (const Row& c : conditions)
        for (const std::string kind : {"view", "scene"}) {
            SCOPED_TRACE(c.at("condition") + " " + kind);
            const std::vector<Span>& of = spans[{c.at("condition"), kind}];
            ASSERT_FALSE(of.empty());
            double total = 0.0, least = of.front().from, most = of.front().to;
            for (std::size_t i = 0; i < of.size(); ++i) {
                total += of[i].weight;
                least = std::min(least, of[i].from);
                most = std::max(most, of[i].to);
                if (i > 0) {
                    EXPECT_LE(of[i - 1].from, of[i].from) << "in ascending latency";
                }
            }
            EXPECT_NEAR(total, 1.0, 1e-9);
            // conditions.csv's range, which the schedule works out on its own (ConditionSchedule::Range).
            EXPECT_NEAR(least, std::stod(c.at(kind + "_latency_min_ms")), 1e-9);
            EXPECT_NEAR(most, std::stod(c.at(kind + "_latency_max_ms")), 1e-9);
            // The spans are the distribution, not only its ends: its quantiles are conditions.csv's.
            EXPECT_NEAR(quantileOf(of, 0.5), std::stod(c.at(kind + "_latency_median_ms")), 1e-6);
            EXPECT_NEAR(quantileOf(of, 0.95), std::stod(c.at(kind + "_latency_p95_ms")), 1e-6);
        }
    // Spelled out for one: 15 renders a second held at 120 Hz, a mouse step waits up to one
    // render period for the next render, uniformly: one span, 0 to 66.7 ms.
    const std::vector<Span>& conv15 = spans[{"conv15", "view"}];
    ASSERT_EQ(conv15.size(), 1u);
    EXPECT_NEAR(conv15[0].to - conv15[0].from, 1000.0 / 15, 1e-6);
}

// A copy of `source` under a new session id whose stored pacing summary is `pacing`.
std::string withStoredPacing(const std::string& source, const std::string& dir, const std::string& participant,
                             const std::string& pacing) {
    session::SessionData data = session::readSession(source);
    data.header.participant = participant;
    data.header.sessionId = data.header.sessionId.substr(0, data.header.sessionId.size() - 1) +
        (data.header.sessionId.back() == '0' ? "1" : "0");
    session::SessionWriter w = session::SessionWriter::create(dir, data.header);
    for (const auto& r : data.inputs) w.addInput(r);
    for (const auto& r : data.frames) w.addFrame(r);
    for (const auto& e : data.events) w.addEvent(e);
    w.summarize("pacing", pacing);
    w.finish();
    return w.path();
}

TEST(ExportPacing, AppendsTheSummarysNewImagesAndIntervalsEmptyWhereItHasNone) {
    const std::string results = scratch("pacing-columns/results"), out = scratch("pacing-columns/out");
    const std::string scratchDir = scratch("pacing-columns/source");
    const std::string source = headless("shooter-quick.json", "P00", scratchDir, 1);
    session::ConditionPacing now;
    now.condition = "conv15";
    now.shown = 100;
    now.budgetMs = 1000.0 / 120;
    now.medianMs = now.p95Ms = now.maxMs = 8.5;
    now.newImages = 13;
    now.intendedP95Ms = 66.75;
    now.intendedMaxMs = 125.5;
    now.shownP95Ms = 75.25;
    now.shownMaxMs = 150.0;
    withStoredPacing(source, results, "P01", session::pacingText({now}));
    // As a live session stored it before new images and intervals were kept.
    withStoredPacing(source, results, "P02",
                     R"([{"mode":"conv15","shown":100,"late":0,"skipped":0,"median_ms":8.5,"p95_ms":8.5,)"
                     R"("max_ms":8.5,"budget_ms":8.333,"over_budget":0}])");
    exportQuietly(results, out);

    const std::vector<std::string> header = headerOf(out + "/pacing.csv");
    const std::vector<std::string> last(header.end() - 6, header.end());
    EXPECT_EQ(last,
              (std::vector<std::string>{"player_kind", "new_images", "intended_p95_ms", "intended_max_ms",
                                        "shown_p95_ms", "shown_max_ms"}))
        << "appended after the columns an older export had";
    std::map<std::string, Row> byParticipant;
    for (const Row& r : readCsv(out + "/pacing.csv")) byParticipant[r.at("participant")] = r;
    ASSERT_EQ(byParticipant.size(), 2u);
    const Row& stored = byParticipant["P01"];
    EXPECT_EQ(stored.at("new_images"), "13");
    EXPECT_EQ(stored.at("intended_p95_ms"), "66.75");
    EXPECT_EQ(stored.at("intended_max_ms"), "125.5");
    EXPECT_EQ(stored.at("shown_p95_ms"), "75.25");
    EXPECT_EQ(stored.at("shown_max_ms"), "150");
    const Row& older = byParticipant["P02"];
    EXPECT_EQ(older.at("shown"), "100");
    for (const char* column : {"new_images", "intended_p95_ms", "intended_max_ms", "shown_p95_ms", "shown_max_ms"})
        EXPECT_EQ(older.at(column), "") << column << ": not stored, so not a 0 that claims a count";
}

}  // namespace
}  // namespace warplab::app
