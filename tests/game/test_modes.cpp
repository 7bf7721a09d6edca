// The modes' frame schedules: what every displayed frame depicts, and the latencies that
// follow -- the table in the README is these numbers.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "game/modes.h"
#include "renderer/upconvert.h"

namespace warplab::game {
namespace {

constexpr double kRefresh = 120.0;
constexpr double kFrame = 1.0 / kRefresh;

ModeSchedule schedule(const std::string& id) { return ModeSchedule(modeSpec(id), kRefresh); }

TEST(Modes, KnownIdsAndUnknownOnesNamed) {
    EXPECT_EQ(modeIds(), (std::vector<std::string>{"conv15", "conv30", "conv60", "conv120", "lag50", "lag100",
                                                    "lag200", "warp15to120", "bireproj15to60"}));
    try {
        modeSpec("conv16");
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("conv16"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("warp15to120"), std::string::npos);
    }
}

// Every mode must be drawable: the frames a mode makes between its renders use the method it
// names, and held or rendered frames are copied by hold120 (app/frame_maker.cpp, which
// replay --render and the simulated participant's eye both draw with).
TEST(Modes, EveryModeNamesAMethodTheRendererHas) {
    const auto methods = renderer::methodNames();
    auto has = [&](const std::string& name) { return std::find(methods.begin(), methods.end(), name) != methods.end(); };
    EXPECT_TRUE(has("hold120"));
    for (const auto& id : modeIds()) {
        const ModeSpec& mode = modeSpec(id);
        if (mode.upconversion == Upconversion::None) {
            EXPECT_TRUE(mode.method.empty()) << id << " makes no frames between renders";
            continue;
        }
        EXPECT_TRUE(has(mode.method)) << id << " names method '" << mode.method << "', which the renderer lacks";
    }
    EXPECT_EQ(modeSpec("bireproj15to60").method, "bireproj");
}

TEST(Modes, CheckModeNamesTheProblem) {
    EXPECT_EQ(checkMode("conv60", 60.0), "");
    EXPECT_NE(checkMode("conv120", 60.0).find("120"), std::string::npos);
    EXPECT_NE(checkMode("conv45", 60.0).find("unknown mode 'conv45'"), std::string::npos);
}

TEST(Modes, RefreshMustBeAWholeMultipleOfTheRates) {
    EXPECT_THROW(ModeSchedule(modeSpec("conv15"), 100.0), std::invalid_argument);
    EXPECT_THROW(ModeSchedule(modeSpec("warp15to120"), 60.0), std::invalid_argument);
    EXPECT_THROW(ModeSchedule(modeSpec("lag50"), 90.0), std::invalid_argument);  // 4.5 frames of lag
    EXPECT_NO_THROW(ModeSchedule(modeSpec("conv60"), 60.0));
    EXPECT_NO_THROW(ModeSchedule(modeSpec("bireproj15to60"), 60.0));
}

TEST(Modes, Conventional15HoldsEachFrameForEightRefreshes) {
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

TEST(Modes, Conventional120RendersEveryFrame) {
    const auto s = schedule("conv120");
    for (std::int64_t k = 0; k < 10; ++k) {
        EXPECT_EQ(s.frame(k).kind, FrameKind::Rendered);
        EXPECT_DOUBLE_EQ(s.frame(k).cameraTime, s.frame(k).displayTime);
    }
}

TEST(Modes, LagShowsSixtyHertzFramesLate) {
    for (const auto& [id, frames] : std::vector<std::pair<std::string, int>>{{"lag50", 6}, {"lag100", 12}, {"lag200", 24}}) {
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

TEST(Modes, WarpRendersEveryEighthAndWarpsToTheCurrentCameraInBetween) {
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

TEST(Modes, BidirectionalRunsOneSourcePeriodBehindAtSixtyHertz) {
    const auto s = schedule("bireproj15to60");
    for (std::int64_t k = 8; k < 40; ++k) {
        const auto f = s.frame(k);
        const std::int64_t depicted = k / 2 * 2 - 8;
        EXPECT_DOUBLE_EQ(f.cameraTime, depicted * kFrame) << k;
        const bool iFrame = depicted % 8 == 0;
        if (k % 2 == 1) EXPECT_EQ(f.kind, FrameKind::Held);
        else EXPECT_EQ(f.kind, iFrame ? FrameKind::Rendered : FrameKind::Interpolated) << k;
        EXPECT_EQ(f.sourceIndex, depicted / 8 * 8);
        EXPECT_EQ(f.nextSourceIndex, iFrame ? -1 : depicted / 8 * 8 + 8);
    }
}

struct Range {
    double min = 1e9, max = -1e9;
};

// Steps at 97 instants spread over two source cycles, off the frame grid.
Range latencies(const ModeSchedule& s, bool view) {
    Range r;
    for (int i = 0; i < 97; ++i) {
        const double tau = 1.0 + (i + 0.5) / 97.0 * (16.0 * kFrame);
        const double l = view ? s.viewLatency(tau) : s.sceneLatency(tau);
        r.min = std::min(r.min, l);
        r.max = std::max(r.max, l);
    }
    return r;
}

// The README's latency table, checked: for each mode the shortest and longest time from a step
// (in the mouse, or in the target's motion) to the first displayed frame that shows it.
TEST(Modes, LatencyTable) {
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
}  // namespace warplab::game
