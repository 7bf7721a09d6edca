// The conditions' frame schedules: what every displayed frame depicts, and the latencies that
// follow -- the table in the README is these numbers.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "condition/readme_latency_table.h"
#include "condition/schedule.h"

namespace warplab::condition {
namespace {

constexpr double kRefresh = 120.0;
constexpr double kFrame = 1.0 / kRefresh;

ConditionSchedule schedule(const std::string& id) { return ConditionSchedule(preset(id), kRefresh); }

// The nine published presets (DESIGN.md) come first, in this order, as protocols, logs and CSVs
// name them; a condition added to the table comes after them and needs no edit here.
TEST(Conditions, KnownIdsAndUnknownOnesNamed) {
    const std::vector<std::string> published{"conv15", "conv30", "conv60",      "conv120",       "lag50",
                                             "lag100", "lag200", "warp15to120", "bireproj15to60"};
    const std::vector<std::string> ids = presetNames();
    ASSERT_GE(ids.size(), published.size());
    EXPECT_EQ(std::vector<std::string>(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(published.size())),
              published);
    EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()).size(), ids.size()) << "an id used twice";
    try {
        preset("conv16");
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("conv16"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("warp15to120"), std::string::npos);
    }
}

// The condition ids a Markdown page's condition table names: the backticked words in the first cell of
// each row of the first table under the heading that starts with `heading`.
std::vector<std::string> documentedConditionIds(const std::string& page, const std::string& heading) {
    std::ifstream doc(std::string(WARPLAB_SOURCE_DIR) + "/" + page);
    EXPECT_TRUE(doc.good()) << page;
    std::vector<std::string> ids;
    bool inSection = false, inTable = false;
    for (std::string line; std::getline(doc, line);) {
        if (line.rfind("#", 0) == 0) {
            if (inSection) break;
            inSection = line.rfind(heading, 0) == 0;
            continue;
        }
        if (!inSection) continue;
        if (line.rfind("|", 0) != 0) {
            if (inTable) break;  // the table ended
            continue;
        }
        inTable = true;
        const std::string cell = line.substr(1, line.find('|', 1) - 1);
        for (std::size_t open = cell.find('`'); open != std::string::npos;) {
            const std::size_t close = cell.find('`', open + 1);
            if (close == std::string::npos) break;
            ids.push_back(cell.substr(open + 1, close - open - 1));
            open = cell.find('`', close + 1);
        }
    }
    EXPECT_FALSE(ids.empty()) << page << " has no mode table under \"" << heading << "\"";
    return ids;
}

// The pages people read describe exactly the conditions the table holds: a condition added to the table
// fails here until the README's latency table and docs/protocol.md's refresh table have its row,
// and a row for a condition that is gone fails too.
TEST(Conditions, ReadmeAndProtocolDocsDescribeEveryCondition) {
    const std::vector<std::string> ids = presetNames();
    const std::set<std::string> known(ids.begin(), ids.end());
    for (const auto& [page, heading] : std::vector<std::pair<std::string, std::string>>{
             {"README.md", "## Conditions and their latency"},
             {"docs/protocol.md", "## Conditions: presets and a protocol's own"}}) {
        SCOPED_TRACE(page + ", " + heading);
        const std::vector<std::string> documented = documentedConditionIds(page, heading);
        const std::set<std::string> named(documented.begin(), documented.end());
        for (const auto& id : ids) EXPECT_EQ(named.count(id), 1u) << "mode " << id << " has no row";
        for (const auto& id : documented) EXPECT_EQ(known.count(id), 1u) << "a row names " << id << ", no mode";
    }
}

// The README's latency cells are the schedule's ranges: each preset's row gives its view and
// scene latency as "A – B ms" (or "same as view"), which must be what `warplab conditions`
// prints for it at 120 Hz, to the 0.1 ms the README rounds to. (tests/games/click/test_click_game.cpp
// holds the same cells to a real run.)
TEST(Conditions, ReadmeLatencyCellsAreTheSchedulesRanges) {
    const readme::ReadmeLatencyTable table = readme::readmeLatencyTable();
    EXPECT_EQ(table.displayRatesHz.count(120.0), 1u) << "the table is for a 120 Hz display";
    for (const readme::ReadmeLatencyRow& row : table.rows) {
        const ConditionSummary s = summarize(preset(row.id), 120.0);
        EXPECT_NEAR(row.viewMinMs, s.viewS.min * 1000, 0.05) << row.id;
        EXPECT_NEAR(row.viewMaxMs, s.viewS.max * 1000, 0.05) << row.id;
        EXPECT_NEAR(row.sceneMinMs, s.sceneS.min * 1000, 0.05) << row.id;
        EXPECT_NEAR(row.sceneMaxMs, s.sceneS.max * 1000, 0.05) << row.id;
    }
    EXPECT_EQ(table.rows.size(), presets().size());
}

TEST(Conditions, CheckConditionNamesTheProblem) {
    EXPECT_EQ(ConditionTable().check("conv60", 60.0), "");
    EXPECT_NE(ConditionTable().check("conv120", 60.0).find("120"), std::string::npos);
    EXPECT_NE(ConditionTable().check("conv45", 60.0).find("unknown condition 'conv45'"), std::string::npos);
}

TEST(Conditions, RatesAboveTheRefreshAndLagsOfPartFramesAreRefused) {
    EXPECT_THROW(ConditionSchedule(preset("conv120"), 60.0), std::invalid_argument);
    EXPECT_NO_THROW(ConditionSchedule(preset("conv15"), 100.0));  // the uneven 6-7-7 cadence
    EXPECT_THROW(ConditionSchedule(preset("warp15to120"), 60.0), std::invalid_argument);
    EXPECT_THROW(ConditionSchedule(preset("lag50"), 90.0),
                 std::invalid_argument);  // 4.5 frames of lag
    EXPECT_NO_THROW(ConditionSchedule(preset("conv60"), 60.0));
    EXPECT_NO_THROW(ConditionSchedule(preset("bireproj15to60"), 60.0));
}

TEST(Conditions, Conventional15HoldsEachFrameForEightRefreshes) {
    const auto s = schedule("conv15");
    for (std::int64_t k = 0; k < 32; ++k) {
        const auto f = s.frame(k);
        const std::int64_t source = k / 8 * 8;
        EXPECT_EQ(f.kind, k % 8 == 0 ? FrameKind::Rendered : FrameKind::Held) << k;
        EXPECT_EQ(f.rendersNow, k % 8 == 0);
        EXPECT_EQ(f.samplesInput, k % 8 == 0);
        EXPECT_EQ(f.sourceIndex, source);
        EXPECT_DOUBLE_EQ(f.cameraTime, source * kFrame);
        EXPECT_DOUBLE_EQ(f.sceneTime, source * kFrame);
        EXPECT_DOUBLE_EQ(f.displayTime, k * kFrame);
    }
}

TEST(Conditions, Conventional120RendersEveryFrame) {
    const auto s = schedule("conv120");
    for (std::int64_t k = 0; k < 10; ++k) {
        EXPECT_EQ(s.frame(k).kind, FrameKind::Rendered);
        EXPECT_DOUBLE_EQ(s.frame(k).cameraTime, s.frame(k).displayTime);
    }
}

TEST(Conditions, LagShowsSixtyHertzFramesLate) {
    for (const auto& [id, frames] :
         std::vector<std::pair<std::string, int>>{{"lag50", 6}, {"lag100", 12}, {"lag200", 24}}) {
        const auto s = schedule(id);
        for (std::int64_t k = 0; k < 60; ++k) {
            const auto f = s.frame(k);
            const std::int64_t rendered = (k - frames) - (((k - frames) % 2) + 2) % 2;
            EXPECT_EQ(f.sourceIndex, rendered) << id << " " << k;
            EXPECT_DOUBLE_EQ(f.cameraTime, rendered * kFrame) << id << " " << k;
            EXPECT_EQ(f.rendersNow, k % 2 == 0);
            // Before the queue has anything from this schedule it shows what was queued before
            // the switch: times before zero, never NaN.
            EXPECT_TRUE(std::isfinite(f.cameraTime));
        }
    }
}

TEST(Conditions, WarpRendersEveryEighthAndWarpsToTheCurrentCameraInBetween) {
    const auto s = schedule("warp15to120");
    for (std::int64_t k = 0; k < 24; ++k) {
        const auto f = s.frame(k);
        EXPECT_EQ(f.kind, k % 8 == 0 ? FrameKind::Rendered : FrameKind::Warped);
        EXPECT_TRUE(f.samplesInput);
        EXPECT_EQ(f.sourceIndex, k / 8 * 8);
        EXPECT_DOUBLE_EQ(f.cameraTime, f.displayTime);
        EXPECT_DOUBLE_EQ(f.sceneTime, f.displayTime);
        EXPECT_DOUBLE_EQ(f.worldSampleTime, (k / 8 * 8) * kFrame);
    }
}

TEST(Conditions, BidirectionalRunsOneSourcePeriodBehindAtSixtyHertz) {
    const auto s = schedule("bireproj15to60");
    for (std::int64_t k = 8; k < 40; ++k) {
        const auto f = s.frame(k);
        const std::int64_t depicted = k / 2 * 2 - 8;
        EXPECT_DOUBLE_EQ(f.cameraTime, depicted * kFrame) << k;
        const bool iFrame = depicted % 8 == 0;
        // A repeated frame is held (docs/protocol.md, fill_hz: "its last frame is shown again"),
        // I-frame and B-frame alike, and made again as it was: the I-frame copied, or the same
        // B-frame interpolated again.
        EXPECT_EQ(f.kind, k % 2 == 1 ? FrameKind::Held : iFrame ? FrameKind::Rendered : FrameKind::Interpolated) << k;
        if (k % 2 == 1) {
            EXPECT_EQ(f.made, iFrame ? FrameKind::Held : FrameKind::Interpolated) << k;
        }
        EXPECT_EQ(f.sourceIndex, depicted / 8 * 8);
        EXPECT_EQ(f.nextSourceIndex, iFrame ? -1 : depicted / 8 * 8 + 8);
    }
}

struct Range {
    double min = 1e9, max = -1e9;
};

// Steps at 97 instants spread over two source cycles, off the frame grid.
Range latencies(const ConditionSchedule& s, bool view) {
    Range r;
    for (int i = 0; i < 97; ++i) {
        const double tau = 1.0 + (i + 0.5) / 97.0 * (16.0 * kFrame);
        const double l = view ? s.viewLatency(tau) : s.sceneLatency(tau);
        r.min = std::min(r.min, l);
        r.max = std::max(r.max, l);
    }
    return r;
}

// The README's latency table, checked: for each condition the shortest and longest time from a step
// (in the mouse, or in the target's motion) to the first displayed frame that shows it.
TEST(Conditions, LatencyTable) {
    struct Row {
        const char* id;
        double viewMinMs, viewMaxMs, sceneMinMs, sceneMaxMs;
    };
    const double f = 1000.0 / 120.0;  // one refresh in ms
    const Row rows[] = {
        {"conv15", 0, 8 * f, 0, 8 * f},
        {"conv30", 0, 4 * f, 0, 4 * f},
        {"conv60", 0, 2 * f, 0, 2 * f},
        {"conv120", 0, f, 0, f},
        {"lag50", 50, 50 + 2 * f, 50, 50 + 2 * f},
        {"lag100", 100, 100 + 2 * f, 100, 100 + 2 * f},
        {"lag200", 200, 200 + 2 * f, 200, 200 + 2 * f},
        {"warp15to120", 0, f, 0, 8 * f},
        {"bireproj15to60", 8 * f, 10 * f, 2 * f, 10 * f},
    };
    for (const auto& row : rows) {
        const auto s = schedule(row.id);
        const Range view = latencies(s, true), scene = latencies(s, false);
        // The exact ranges `warplab conditions` prints are the table's, to the last bit or so.
        EXPECT_NEAR(s.viewLatencyRange().min * 1000.0, row.viewMinMs, 1e-9) << row.id;
        EXPECT_NEAR(s.viewLatencyRange().max * 1000.0, row.viewMaxMs, 1e-9) << row.id;
        EXPECT_NEAR(s.sceneLatencyRange().min * 1000.0, row.sceneMinMs, 1e-9) << row.id;
        EXPECT_NEAR(s.sceneLatencyRange().max * 1000.0, row.sceneMaxMs, 1e-9) << row.id;
        // Steps fall strictly between frames, so the extremes are approached, not reached:
        // within one sample spacing (16 frames / 97) of the bounds.
        const double slack = 16.0 * f / 97.0 + 1e-6;
        EXPECT_NEAR(view.min * 1000.0, row.viewMinMs, slack) << row.id;
        EXPECT_NEAR(view.max * 1000.0, row.viewMaxMs, slack) << row.id;
        EXPECT_NEAR(scene.min * 1000.0, row.sceneMinMs, slack) << row.id;
        EXPECT_NEAR(scene.max * 1000.0, row.sceneMaxMs, slack) << row.id;
        EXPECT_GE(view.min, row.viewMinMs / 1000.0 - 1e-9) << row.id;
        EXPECT_LE(view.max, row.viewMaxMs / 1000.0 + 1e-9) << row.id;
    }
}

}  // namespace
}  // namespace warplab::condition
