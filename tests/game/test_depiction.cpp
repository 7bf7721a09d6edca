// What a condition shows, through a game's two hooks: a warp frame is the source's state moved
// on by the move hook, a B-frame the blend of its I-frames. Checked against a world whose true
// motion is known (a constant velocity: extrapolation and interpolation are then exact up to
// rounding), against the schedule's own account of the frame, and against the arithmetic the
// games did before the depiction was decided in one place, bit for bit.
#include <cmath>
#include <cstdint>
#include <optional>

#include <gtest/gtest.h>

#include "game/depiction.h"
#include "condition/schedule.h"

namespace warplab::game {
namespace {

// A point moving at a constant velocity: the oracle for both hooks.
struct Point {
    double x = 0.0, v = 0.0;
};
constexpr double kX0 = 0.37, kV = -2.9;  // metres, metres per second
Point trueAt(double t) { return {kX0 + kV * t, kV}; }

Point moveBy(Point p, double dt) {
    p.x = p.x + p.v * dt;
    return p;
}
Point blendOf(const Point& a, const Point& b, double weight, double) { return {a.x + (b.x - a.x) * weight, a.v}; }

// The world timed on the session clock (as the shooter's target), or on the schedule's (as
// the click game's match, recorded from its first frame).
std::optional<Point> worldAt(std::int64_t frame, const SchedulePlacement& at, WorldClock clock) {
    const std::int64_t since = clock == WorldClock::Session ? frame : frame - at.start;
    return trueAt(static_cast<double>(since) / at.refreshHz);
}

std::optional<Point> shownAt(const condition::ConditionSchedule& schedule, std::int64_t k, const SchedulePlacement& at,
                             WorldClock clock) {
    const WorldDepiction d = depictWorld(schedule.condition(), schedule.frame(k), at, clock);
    return depictedState<Point>(
        d, [&](std::int64_t frame) { return worldAt(frame, at, clock); }, moveBy, blendOf);
}

TEST(Depiction, WarpFramesAreTheSourceMovedOnByTheMoveHook) {
    const condition::ConditionSchedule warp(condition::preset("warp15to120"), 120.0);
    for (const WorldClock clock : {WorldClock::Session, WorldClock::Schedule}) {
        const SchedulePlacement at{1237, 120.0};
        for (std::int64_t k = 0; k < 64; ++k) {
            const condition::ScheduledFrame f = warp.frame(k);
            const WorldDepiction d = depictWorld(warp.condition(), f, at, clock);
            ASSERT_EQ(d.how, Depicted::Extrapolated) << k;
            // The latest 15 Hz render (every 8th display frame) is the source, moved on to the
            // display instant.
            EXPECT_EQ(d.frame, at.start + k / 8 * 8) << k;
            EXPECT_EQ(d.depictedFrame, at.start + k) << k;
            EXPECT_NEAR(d.dt, (k % 8) / 120.0, 1e-12) << k;
            // A constant velocity continues exactly: the frame shows where the point really is.
            const double t = static_cast<double>(clock == WorldClock::Session ? at.start + k : k) / 120.0;
            EXPECT_NEAR(shownAt(warp, k, at, clock)->x, trueAt(t).x, 1e-12) << k;
        }
    }
}

TEST(Depiction, BFramesAreTheBlendOfTheirIFramesOneIFramePeriodLate) {
    const condition::ConditionSchedule bireproj(condition::preset("bireproj15to60"), 60.0);
    for (const WorldClock clock : {WorldClock::Session, WorldClock::Schedule}) {
        const SchedulePlacement at{905, 60.0};
        for (std::int64_t k = 4; k < 64; ++k) {
            const WorldDepiction d = depictWorld(bireproj.condition(), bireproj.frame(k), at, clock);
            const std::int64_t depicted = k - 4;  // one 15 Hz I-frame period behind
            EXPECT_EQ(d.depictedFrame, at.start + depicted) << k;
            if (depicted % 4 == 0) {
                EXPECT_EQ(d.how, Depicted::AsSampled) << k;
                EXPECT_EQ(d.frame, at.start + depicted) << k;
                continue;
            }
            ASSERT_EQ(d.how, Depicted::Interpolated) << k;
            EXPECT_EQ(d.frame, at.start + depicted / 4 * 4) << k;
            EXPECT_EQ(d.nextFrame, d.frame + 4) << k;
            EXPECT_NEAR(d.weight, (depicted % 4) / 4.0, 1e-12) << k;
            EXPECT_NEAR(d.spanS, 4.0 / 60.0, 1e-12) << k;
            if (clock == WorldClock::Schedule) {
                EXPECT_EQ(d.weight, (depicted % 4) / 4.0) << "whole frames, exact";
            }
            // Linear motion blends to exactly where the point was at the depicted instant.
            const double t = static_cast<double>(clock == WorldClock::Session ? at.start + depicted : depicted) / 60.0;
            EXPECT_NEAR(shownAt(bireproj, k, at, clock)->x, trueAt(t).x, 1e-12) << k;
        }
    }
}

TEST(Depiction, HeldAndLaggedFramesShowTheStateAsSampled) {
    const SchedulePlacement at{40, 60.0};
    const condition::ConditionSchedule conv15(condition::preset("conv15"), 60.0),
        lag50(condition::preset("lag50"), 60.0);
    for (std::int64_t k = 0; k < 24; ++k) {
        const WorldDepiction held = depictWorld(conv15.condition(), conv15.frame(k), at, WorldClock::Session);
        EXPECT_EQ(held.how, Depicted::AsSampled);
        EXPECT_EQ(held.frame, at.start + k / 4 * 4) << k;
        const WorldDepiction lagged = depictWorld(lag50.condition(), lag50.frame(k), at, WorldClock::Schedule);
        EXPECT_EQ(lagged.how, Depicted::AsSampled);
        EXPECT_EQ(lagged.frame, at.start + k - 3) << k;  // 50 ms at 60 Hz
    }
}

// The arithmetic each game did itself before, verbatim but for names: the shooter's warp
// and B-frames on the session clock, the click game's on the schedule's.
double oldShooter(const condition::ConditionSchedule& schedule, const condition::ScheduledFrame& f,
                  std::int64_t start) {
    const double refresh = schedule.refreshHz();
    auto global = [&](double localTime) {
        return static_cast<double>(start + std::llround(localTime * refresh)) / refresh;
    };
    auto targetAt = [&](double time) { return trueAt(time).x; };
    switch (schedule.condition().fillKind()) {
        case condition::Fill::Blend: break;  // no preset blends
        case condition::Fill::Hold: return targetAt(global(f.sceneTime));
        case condition::Fill::Warp: {
            const double source = global(f.worldSampleTime);
            return targetAt(source) + trueAt(source).v * (global(f.sceneTime) - source);
        }
        case condition::Fill::Bireproj: {
            const double depicted = global(f.sceneTime);
            if (f.nextSourceIndex < 0) return targetAt(depicted);
            const double t0 = static_cast<double>(start + f.sourceIndex) / refresh;
            const double t1 = static_cast<double>(start + f.nextSourceIndex) / refresh;
            const double p0 = targetAt(t0), p1 = targetAt(t1);
            const double a = (depicted - t0) / (t1 - t0);
            return p0 + (p1 - p0) * a;
        }
    }
    return 0.0;
}
double oldClick(const condition::ConditionSchedule& schedule, const condition::ScheduledFrame& f) {
    const double refresh = schedule.refreshHz();
    auto at = [&](std::int64_t localFrame) { return trueAt(static_cast<double>(localFrame) / refresh); };
    auto frameOf = [&](double localTime) { return std::llround(localTime * refresh); };
    switch (schedule.condition().fillKind()) {
        case condition::Fill::Blend: break;  // no preset blends
        case condition::Fill::Hold: return at(frameOf(f.sceneTime)).x;
        case condition::Fill::Warp: {
            const double dt = f.sceneTime - f.worldSampleTime;
            const Point p = at(frameOf(f.worldSampleTime));
            return p.x + p.v * dt;
        }
        case condition::Fill::Bireproj: {
            if (f.nextSourceIndex < 0) return at(frameOf(f.sceneTime)).x;
            const Point before = at(f.sourceIndex), after = at(f.nextSourceIndex);
            const double a = static_cast<double>(std::llround(f.sceneTime * refresh) - f.sourceIndex) /
                static_cast<double>(f.nextSourceIndex - f.sourceIndex);
            return before.x + (after.x - before.x) * a;
        }
    }
    return 0.0;
}

TEST(Depiction, EachClockKeepsTheArithmeticItsGameDidBitForBit) {
    for (const double refresh : {60.0, 120.0}) {
        for (const std::string& id : condition::presetNames()) {
            if (!condition::ConditionTable().check(id, refresh).empty()) continue;
            const condition::ConditionSchedule schedule(condition::preset(id), refresh);
            for (const std::int64_t start : {0, 1, 37, 4321, 987654}) {
                const SchedulePlacement at{start, refresh};
                for (std::int64_t k = 0; k < 200; ++k) {
                    const condition::ScheduledFrame f = schedule.frame(k);
                    EXPECT_EQ(shownAt(schedule, k, at, WorldClock::Session)->x, oldShooter(schedule, f, start))
                        << id << " at " << refresh << " Hz, start " << start << ", frame " << k;
                    EXPECT_EQ(shownAt(schedule, k, at, WorldClock::Schedule)->x, oldClick(schedule, f))
                        << id << " at " << refresh << " Hz, start " << start << ", frame " << k;
                }
            }
        }
    }
}

TEST(Depiction, AnInputReadsClickWaitsForTheNextFrameThatReadsInput) {
    const condition::ConditionSchedule conv15(condition::preset("conv15"), 60.0);
    ClickGate waits(true), atOnce(false);
    // Pressed at frame 1; conv15 at 60 Hz reads its input at frames 0, 4, 8, ...
    for (std::int64_t k = 0; k < 8; ++k) {
        EXPECT_EQ(waits.pass(k == 1, conv15.frame(k)), k == 4) << k;
        EXPECT_EQ(atOnce.pass(k == 1, conv15.frame(k)), k == 1) << k;
    }
    // Disarmed, a press is dropped rather than kept for later.
    EXPECT_FALSE(waits.pass(true, conv15.frame(1), false));
    EXPECT_FALSE(waits.pass(false, conv15.frame(4)));
}

}  // namespace
}  // namespace warplab::game
