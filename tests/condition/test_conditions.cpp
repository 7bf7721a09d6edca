// Conditions as data: the presets expand to exactly the schedules the compiled-in conditions had,
// composed conditions (other rates, lags in frames, fills, late warp) get their timing from the
// same schedule, and an impossible combination is refused naming the part and why.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "condition/schedule.h"

namespace warplab::condition {
namespace {

// The frame schedule of the nine conditions before they were composed from parts, verbatim but for
// names: the oracle the presets must reproduce frame by frame.
struct OldCondition {
    double renderRateHz, lagMs;
    enum { None, Warp, Bidirectional } upconversion;
    double upconvertedRateHz;
};
std::int64_t floorTo(std::int64_t k, std::int64_t period) { return k - ((k % period) + period) % period; }
ScheduledFrame oldFrame(const OldCondition& m, double refreshHz, std::int64_t k) {
    const std::int64_t renderPeriod = std::llround(refreshHz / m.renderRateHz);
    const std::int64_t lagFrames = std::llround(m.lagMs * refreshHz / 1000.0);
    const std::int64_t bPeriod =
        m.upconversion == OldCondition::Bidirectional ? std::llround(refreshHz / m.upconvertedRateHz) : 1;
    ScheduledFrame f;
    f.index = k;
    f.displayTime = static_cast<double>(k) / refreshHz;
    f.rendersNow = floorTo(k, renderPeriod) == k;
    auto time = [&](std::int64_t frame) { return static_cast<double>(frame) / refreshHz; };
    switch (m.upconversion) {
        case OldCondition::None: {
            const std::int64_t shown = floorTo(k - lagFrames, renderPeriod);
            f.sourceIndex = shown;
            f.kind = shown == k - lagFrames ? FrameKind::Rendered : FrameKind::Held;
            f.cameraTime = f.sceneTime = f.worldSampleTime = time(shown);
            f.samplesInput = f.rendersNow;
            break;
        }
        case OldCondition::Warp: {
            f.sourceIndex = floorTo(k, renderPeriod);
            f.kind = f.rendersNow ? FrameKind::Rendered : FrameKind::Warped;
            f.cameraTime = f.sceneTime = f.displayTime;
            f.worldSampleTime = time(f.sourceIndex);
            f.samplesInput = true;
            break;
        }
        case OldCondition::Bidirectional: {
            const std::int64_t depicted = floorTo(k, bPeriod) - renderPeriod;
            f.sourceIndex = floorTo(depicted, renderPeriod);
            const bool onIFrame = f.sourceIndex == depicted;
            f.nextSourceIndex = onIFrame ? -1 : f.sourceIndex + renderPeriod;
            const bool newFrame = floorTo(k, bPeriod) == k;
            f.kind = !newFrame ? FrameKind::Held : (onIFrame ? FrameKind::Rendered : FrameKind::Interpolated);
            f.cameraTime = f.sceneTime = time(depicted);
            f.worldSampleTime = time(onIFrame ? f.sourceIndex : f.nextSourceIndex);
            f.samplesInput = newFrame;
            break;
        }
    }
    return f;
}

TEST(Conditions, EveryPresetExpandsToTheScheduleItReplaced) {
    const std::vector<std::pair<std::string, OldCondition>> old = {
        {"conv15", {15, 0, OldCondition::None, 0}},
        {"conv30", {30, 0, OldCondition::None, 0}},
        {"conv60", {60, 0, OldCondition::None, 0}},
        {"conv120", {120, 0, OldCondition::None, 0}},
        {"lag50", {60, 50, OldCondition::None, 0}},
        {"lag100", {60, 100, OldCondition::None, 0}},
        {"lag200", {60, 200, OldCondition::None, 0}},
        {"warp15to120", {15, 0, OldCondition::Warp, 120}},
        {"bireproj15to60", {15, 0, OldCondition::Bidirectional, 60}},
    };
    ASSERT_EQ(presets().size(), old.size());
    int compared = 0;
    // The refreshes the shipped protocols and every stored session use.
    for (const double refresh : {60.0, 120.0}) {
        for (const auto& [name, condition] : old) {
            if (!ConditionTable().check(name, refresh).empty()) continue;
            const ConditionSchedule schedule(preset(name), refresh);
            for (std::int64_t k = -50; k < 400; ++k) {
                const ScheduledFrame a = schedule.frame(k), b = oldFrame(condition, refresh, k);
                SCOPED_TRACE(name + " at " + std::to_string(refresh) + " Hz, frame " + std::to_string(k));
                // Bidirectional reprojection's repeated frames (B-frames shown twice on a 120 Hz
                // display) are held, as they were, but were drawn as the I-frame before; they are
                // made as the same B-frame again. Everything the scoring reads is unchanged.
                const bool repeatedBFrame = condition.upconversion == OldCondition::Bidirectional &&
                    b.kind == FrameKind::Held && b.nextSourceIndex != -1;
                EXPECT_EQ(a.kind, b.kind);
                EXPECT_EQ(a.made, repeatedBFrame ? FrameKind::Interpolated : b.kind);
                EXPECT_EQ(a.index, b.index);
                EXPECT_EQ(a.displayTime, b.displayTime);  // bit for bit
                EXPECT_EQ(a.cameraTime, b.cameraTime);
                EXPECT_EQ(a.sceneTime, b.sceneTime);
                EXPECT_EQ(a.worldSampleTime, b.worldSampleTime);
                EXPECT_EQ(a.rendersNow, b.rendersNow);
                EXPECT_EQ(a.samplesInput, b.samplesInput);
                EXPECT_EQ(a.sourceIndex, b.sourceIndex);
                EXPECT_EQ(a.nextSourceIndex, b.nextSourceIndex);
                ++compared;
            }
        }
    }
    EXPECT_EQ(compared, (7 + 9) * 450);  // 60 Hz runs seven presets, 120 Hz all nine
}

Condition composed(double renderHz, int lagFrames, const std::string& fill, LateWarp lateWarp) {
    Condition c;
    c.name = "composed";
    c.renderHz = renderHz;
    c.lagFrames = lagFrames;
    c.fill = fill;
    c.lateWarp = lateWarp;
    return c;
}

// Kim et al.'s condition: 60 Hz rendering with 5 frames of queue (10 display frames at 120 Hz).
TEST(Conditions, LateWarpShowsTheMouseAtTheNextFrameAndTheWorldAfterTheLag) {
    const double refresh = 120, f = 1000.0 / refresh;
    for (const LateWarp late : {LateWarp::None, LateWarp::Rotation, LateWarp::Depth}) {
        SCOPED_TRACE(lateWarpName(late));
        const ConditionSchedule s(composed(60, 10, "hold", late), refresh);
        const auto view = s.viewLatencyRange(), scene = s.sceneLatencyRange();
        if (late == LateWarp::None) {
            EXPECT_NEAR(view.min * 1000, 10 * f, 1e-9);
            EXPECT_NEAR(view.max * 1000, 12 * f, 1e-9);
        } else {
            EXPECT_NEAR(view.min * 1000, 0, 1e-9);
            EXPECT_NEAR(view.max * 1000, f, 1e-9);
        }
        // A change of the world's motion waits for a render to leave the queue, late warp or not.
        EXPECT_NEAR(scene.min * 1000, 10 * f, 1e-9);
        EXPECT_NEAR(scene.max * 1000, 12 * f, 1e-9);
        for (std::int64_t k = 0; k < 48; ++k) {
            const ScheduledFrame fr = s.frame(k);
            const std::int64_t source = floorTo(k - 10, 2);
            EXPECT_EQ(fr.sourceIndex, source) << k;
            EXPECT_DOUBLE_EQ(fr.worldSampleTime, source / refresh) << k;
            EXPECT_EQ(fr.rendersNow, k % 2 == 0) << k;
            if (late == LateWarp::None) {
                EXPECT_DOUBLE_EQ(fr.cameraTime, source / refresh);
                EXPECT_EQ(fr.kind, source == k - 10 ? FrameKind::Rendered : FrameKind::Held);
                continue;
            }
            EXPECT_TRUE(fr.samplesInput);
            EXPECT_EQ(fr.kind, FrameKind::Warped) << k;
            EXPECT_DOUBLE_EQ(fr.cameraTime, fr.displayTime) << k;
            EXPECT_DOUBLE_EQ(fr.sceneTime, late == LateWarp::Depth ? fr.displayTime : source / refresh) << k;
        }
    }
    EXPECT_EQ(composed(60, 10, "hold", LateWarp::Rotation).warpMethod(), kRotationLateWarpMethod);
    EXPECT_EQ(composed(60, 10, "hold", LateWarp::Depth).warpMethod(), kDepthLateWarpMethod);
    EXPECT_EQ(composed(60, 10, "warp-full", LateWarp::Depth).warpMethod(), "warp-full");
    EXPECT_TRUE(composed(60, 10, "hold", LateWarp::Depth).movesWorld());
    EXPECT_FALSE(composed(60, 10, "hold", LateWarp::Rotation).movesWorld());
}

// Other displays and fill rates: a 144 Hz display rendering at 36 Hz and warping at 72 Hz
// shows each warped frame twice: once warped, then held (made again by the warp).
TEST(Conditions, AFillAtItsOwnRateRepeatsItsFrames) {
    Condition c = composed(36, 0, "warp-sparse8", LateWarp::None);
    c.fillHz = 72;
    const ConditionSchedule s(c, 144);
    for (std::int64_t k = 0; k < 24; ++k) {
        const ScheduledFrame f = s.frame(k);
        EXPECT_EQ(f.sourceIndex, k / 4 * 4) << k;
        EXPECT_DOUBLE_EQ(f.cameraTime, static_cast<double>(k / 2 * 2) / 144) << k;
        EXPECT_EQ(f.samplesInput, k % 2 == 0) << k;
        EXPECT_EQ(f.kind, k % 4 == 0 ? FrameKind::Rendered : k % 4 == 2 ? FrameKind::Warped : FrameKind::Held) << k;
        EXPECT_EQ(f.made, k % 4 < 2 ? (k % 4 == 0 ? FrameKind::Rendered : FrameKind::Held) : FrameKind::Warped) << k;
    }
    EXPECT_NEAR(s.viewLatencyRange().max * 144, 2, 1e-9);
    EXPECT_NEAR(s.sceneLatencyRange().max * 144, 4, 1e-9);
    c.fillHz = 48;  // not a whole multiple of 36
    EXPECT_THROW(ConditionSchedule(c, 144), std::invalid_argument);
}

std::string problemOf(const Condition& c, double refreshHz) {
    const auto p = problem(c, refreshHz);
    return p ? p->part + ": " + p->reason : "";
}

TEST(Conditions, ImpossibleCombinationsNameThePartAndWhatIsAllowed) {
    EXPECT_EQ(problemOf(composed(60, 10, "hold", LateWarp::Rotation), 120), "");
    // A render rate above the refresh, or one the refresh does not divide.
    EXPECT_EQ(problemOf(composed(240, 0, "hold", LateWarp::None), 120).rfind("render_hz: is 240 Hz", 0), 0u);
    EXPECT_NE(problemOf(composed(240, 0, "hold", LateWarp::None), 120).find("above the refresh"), std::string::npos);
    EXPECT_NE(problemOf(composed(240, 0, "hold", LateWarp::None), 120).find("allowed: up to 120 Hz"),
              std::string::npos);
    // Any rate up to it runs, evenly or not.
    EXPECT_EQ(problemOf(composed(50, 0, "hold", LateWarp::None), 120), "");
    EXPECT_EQ(problemOf(composed(120, 0, "hold", LateWarp::None), 120), "");
    // A negative lag; a lag in ms that is not whole frames names the nearest two that are.
    EXPECT_EQ(problemOf(composed(60, -1, "hold", LateWarp::None), 120), "lag_frames: must be at least 0, got -1");
    Condition ms = composed(30, 0, "hold", LateWarp::None);
    ms.lagFrames.reset();
    ms.lagMs = 60;
    EXPECT_EQ(problemOf(ms, 120),
              "lag_ms: is 60 ms, which is 7.2 frames at 120 Hz, not a whole number; the nearest that are: 58.3333 ms "
              "(7 frames) and 66.6667 ms (8 frames), or give lag_frames");
    ms.lagMs = 62.5;
    EXPECT_EQ(problemOf(ms, 240), "");
    // A fill above the refresh, or not a multiple of a render rate that divides the refresh;
    // one the refresh does not divide runs unevenly, as renders do.
    Condition fill = composed(15, 0, "warp-sparse8", LateWarp::None);
    fill.fillHz = 50;
    EXPECT_EQ(problemOf(fill, 120), "");
    fill.fillHz = 150;
    EXPECT_EQ(problemOf(fill, 120),
              "fill_hz: is 150 Hz, above the refresh (120 Hz): a display shows at most one new frame per refresh; "
              "allowed: up to 120 Hz");
    fill.fillHz = 40;
    EXPECT_EQ(problemOf(fill, 120), "fill_hz: the fill's rate (40 Hz) must be a whole multiple of render_hz (15 Hz)");
    Condition hold = composed(60, 0, "hold", LateWarp::None);
    hold.fillHz = 120;
    EXPECT_EQ(problemOf(hold, 120).rfind("fill_hz: is for a fill that makes frames", 0), 0u);
    // Late warp re-projects one frame; bidirectional reprojection and a blend show two.
    EXPECT_EQ(problemOf(composed(15, 0, "bireproj", LateWarp::Rotation), 60).rfind("late_warp: must be \"none\"", 0),
              0u);
    EXPECT_EQ(problemOf(composed(15, 0, "blend", LateWarp::Depth), 60).rfind("late_warp: must be \"none\"", 0), 0u);
    EXPECT_EQ(problemOf(composed(15, 0, "smear", LateWarp::None), 60).rfind("fill: must be one of hold, warp-full", 0),
              0u);
    // More look-back than a game's history keeps; the longest lag_frames fits at ordinary rates.
    EXPECT_EQ(problemOf(composed(60, kMaxLagFrames, "hold", LateWarp::None), 60), "");
    EXPECT_EQ(
        problemOf(composed(0.1, kMaxLagFrames, "hold", LateWarp::None), 120).rfind("lag_frames: looks back 2880", 0),
        0u);
}

// A rate is the rate it runs at: a hair off one that fits the refresh would run as that one,
// so it is refused naming both (29.97 Hz on a 59.94 Hz display fits to the last bit).
TEST(Conditions, ARateAHairOffOneThatFitsIsRefused) {
    EXPECT_EQ(problemOf(composed(59.999999999, 0, "hold", LateWarp::None), 120),
              "render_hz: is 59.999999999 Hz, which a 120 Hz display can only run as 60 Hz (every 2nd display frame); "
              "write 60");
    EXPECT_EQ(problemOf(composed(120.0000001, 0, "hold", LateWarp::None), 120),
              "render_hz: is 120.0000001 Hz, which a 120 Hz display can only run as 120 Hz (every display frame); "
              "write 120");
    EXPECT_EQ(problemOf(composed(29.97, 0, "hold", LateWarp::None), 59.94), "");
    EXPECT_EQ(problemOf(composed(144.0 / 7.0, 0, "hold", LateWarp::None), 144), "");
    Condition fill = composed(15, 0, "warp-sparse8", LateWarp::None);
    fill.fillHz = 119.9999999999;
    EXPECT_EQ(
        problemOf(fill, 120).rfind("fill_hz: is 119.9999999999 Hz, which a 120 Hz display can only run as 120 Hz", 0),
        0u);
    EXPECT_EQ(wholeRatio(120, 59.999999999), std::nullopt);
    EXPECT_EQ(wholeRatio(120, 60), 2);
    EXPECT_EQ(wholeRatio(480, 60), 8);  // the click game's physics steps per frame
}

// docs/protocol.md gives the limits a definition's lag is held to: what the parser allows and
// what a game's history keeps, as the constants say.
TEST(Conditions, TheProtocolPageStatesTheLagLimits) {
    std::ifstream in(std::string(WARPLAB_SOURCE_DIR) + "/docs/protocol.md");
    std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (char& c : page)
        if (c == '\n') c = ' ';
    const std::string lagRow =
        "| `lag_frames` | integer | display frames | 0 | 0\u2013" + std::to_string(kMaxLagFrames) + " |";
    EXPECT_NE(page.find(lagRow), std::string::npos) << "docs/protocol.md should have: " << lagRow;
    const std::string lookBack = "may look back at most " + std::to_string(kMaxLookBackFrames) + " display frames";
    EXPECT_NE(page.find(lookBack), std::string::npos) << "docs/protocol.md should say: " << lookBack;
}

TEST(Conditions, TheTableFindsPresetsThenTheProtocolsOwn) {
    Condition mine = composed(60, 10, "hold", LateWarp::Rotation);
    mine.name = "mine";
    const ConditionTable table({mine});
    EXPECT_EQ(table.at("mine").lateWarp, LateWarp::Rotation);
    EXPECT_EQ(table.at("conv15").renderHz, 15);
    EXPECT_EQ(table.names().back(), "mine");
    EXPECT_EQ(table.names().size(), presets().size() + 1);
    EXPECT_NE(table.check("yours", 120).find("unknown condition 'yours' (known: conv15"), std::string::npos);
    EXPECT_NE(table.check("yours", 120).find(", mine)"), std::string::npos);
    EXPECT_EQ(table.check("mine", 120), "");
    EXPECT_EQ(table.check("mine", 100), "");
    EXPECT_NE(table.check("mine", 50).find("condition mine: render_hz is 60 Hz, above the refresh"), std::string::npos);
}

}  // namespace
}  // namespace warplab::condition
