// Frame pacing and latency as distributions (condition/pacing_stats.h): the presets give the
// numbers anyone would expect of them, the latency quantiles agree with the latency function
// sampled densely, and the least and greatest latencies are the schedule's ranges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "condition/pacing_stats.h"

namespace warplab::condition {
namespace {

Condition paced(double renderHz) {
    Condition c;
    c.name = "paced";
    c.renderHz = renderHz;
    return c;
}

Condition preset(const std::string& name) {
    const Condition* c = findPreset(name);
    EXPECT_NE(c, nullptr) << name;
    return c ? *c : Condition{};
}

std::vector<double> sortedUnique(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }), v.end());
    return v;
}

TEST(PacingStats, PercentileIsTheNearestRank) {
    std::vector<double> v;
    for (int i = 20; i >= 1; --i) v.push_back(i);
    EXPECT_EQ(percentile(v, 95), 19);
    EXPECT_EQ(percentile(v, 50), 10);
    EXPECT_EQ(percentile(v, 99), 20);
    EXPECT_EQ(percentile(v, 100), 20);
    EXPECT_EQ(percentile(v, 1), 1);
    EXPECT_TRUE(std::isnan(percentile({}, 95)));
}

TEST(PacingStats, Conv120At120HzShowsEveryRefreshNewAndNeverStutters) {
    const PacingStats s = pacingStats(ConditionSchedule(preset("conv120"), 120));
    EXPECT_DOUBLE_EQ(s.frameTimes.meanFps, 120);
    EXPECT_EQ(s.frames.frameTimeS.size(), 1199u);  // 1200 new images over 10 s
    for (const double t : s.frames.frameTimeS) EXPECT_NEAR(t * 1000, 8.333333, 1e-5);
    EXPECT_NEAR(s.frameTimes.low1Fps, 120, 1e-9);
    EXPECT_NEAR(s.frameTimes.low5Fps, 120, 1e-9);
    EXPECT_NEAR(s.frameTimes.maxS * 120, 1, 1e-9);
    EXPECT_EQ(s.frameTimes.stutters, 0);
}

TEST(PacingStats, Conv15At120HzIsFifteenFramesASecond) {
    const PacingStats s = pacingStats(ConditionSchedule(preset("conv15"), 120));
    EXPECT_DOUBLE_EQ(s.frameTimes.meanFps, 15);
    EXPECT_EQ(sortedUnique(s.frames.frameTimeS).size(), 1u);
    EXPECT_NEAR(s.frameTimes.medianS * 1000, 66.666667, 1e-5);
    EXPECT_NEAR(s.frameTimes.low1Fps, 15, 1e-9);
    EXPECT_EQ(s.frameTimes.stutters, 0);
}

// A fill's frames are new images too: warped every refresh, interpolated at its fill rate.
TEST(PacingStats, AFillsFramesCountAsNewImages) {
    const PacingStats warp = pacingStats(ConditionSchedule(preset("warp15to120"), 120));
    EXPECT_DOUBLE_EQ(warp.frameTimes.meanFps, 120);
    EXPECT_NEAR(warp.frameTimes.maxS * 120, 1, 1e-9);
    const PacingStats bireproj = pacingStats(ConditionSchedule(preset("bireproj15to60"), 120));
    EXPECT_DOUBLE_EQ(bireproj.frameTimes.meanFps, 60);
    EXPECT_NEAR(bireproj.frameTimes.maxS * 60, 1, 1e-9);
}

// 3, 2, 3, 2, 2 refreshes: 13.9 ms three times in five, 20.8 ms twice, a mean of exactly 60.
TEST(PacingStats, SixtyOn144HzHasTwoFrameTimesAndAMeanOfExactlySixty) {
    const PacingStats s = pacingStats(ConditionSchedule(paced(60), 144));
    EXPECT_DOUBLE_EQ(s.frameTimes.meanFps, 60);
    const std::vector<double> times = sortedUnique(s.frames.frameTimeS);
    ASSERT_EQ(times.size(), 2u);
    EXPECT_NEAR(times[0] * 144, 2, 1e-9);
    EXPECT_NEAR(times[1] * 144, 3, 1e-9);
    EXPECT_NEAR(s.frameTimes.medianS * 144, 2, 1e-9);
    EXPECT_NEAR(s.frameTimes.p95S * 144, 3, 1e-9);
    EXPECT_NEAR(s.frameTimes.low5Fps, 48, 1e-9);
    EXPECT_EQ(s.frameTimes.stutters, 0);
}

// Each hitch is one frame time of a render interval plus the stall: one stutter each.
TEST(PacingStats, AHitchingConditionStuttersOncePerHitchInTheHorizon) {
    Condition c = paced(60);
    c.hitches.ms = 50;
    c.hitches.everyS = 0.75;
    const PacingStats s = pacingStats(ConditionSchedule(c, 120));
    const double start = static_cast<double>(s.firstFrame) / 120;
    // The hitches whose stalled render and the one before it are both shown in the horizon.
    int hitches = 0;
    for (int k = 1; k * 0.75 < start + s.horizonS; ++k)
        hitches += k * 0.75 > start + 0.02 && k * 0.75 + 0.1 < start + s.horizonS;
    EXPECT_GE(hitches, 12);
    EXPECT_EQ(s.frameTimes.stutters, hitches);
    EXPECT_NEAR(s.frameTimes.maxS * 1000, 66.67, 0.01);  // 16.7 ms and 50 ms, whole refreshes
    EXPECT_LT(s.frameTimes.meanFps, 60);
}

// The conditions the distributions are checked on: every preset, uneven, jittered, hitching.
std::vector<std::pair<Condition, double>> variety() {
    std::vector<std::pair<Condition, double>> out;
    for (const Condition& c : presets()) out.emplace_back(c, 120);
    out.emplace_back(paced(60), 144);
    Condition jittered = paced(60);
    jittered.jitter = {JitterShape::Lognormal, 6.0, 0.0};
    out.emplace_back(jittered, 144);
    Condition hitching = paced(90);
    hitching.hitches.ms = 40;
    hitching.hitches.ratePerS = 1.5;
    out.emplace_back(hitching, 144);
    Condition warped = paced(30);
    warped.fill = "warp-full";
    warped.fillHz = 72;
    warped.jitter = {JitterShape::Normal, 3.0, 0.0};
    out.emplace_back(warped, 144);
    return out;
}

TEST(PacingStats, LeastAndGreatestLatencyAreTheScheduleRanges) {
    for (const auto& [c, refresh] : variety()) {
        const ConditionSchedule schedule(c, refresh);
        const PacingStats s = pacingStats(schedule);
        EXPECT_NEAR(s.viewS.min, schedule.viewLatencyRange().min, 1e-9) << c.name;
        EXPECT_NEAR(s.viewS.max, schedule.viewLatencyRange().max, 1e-9) << c.name;
        EXPECT_NEAR(s.sceneS.min, schedule.sceneLatencyRange().min, 1e-9) << c.name;
        EXPECT_NEAR(s.sceneS.max, schedule.sceneLatencyRange().max, 1e-9) << c.name;
        EXPECT_LE(s.viewS.min, s.viewS.median);
        EXPECT_LE(s.viewS.median, s.viewS.p95);
        EXPECT_LE(s.viewS.p95, s.viewS.max);
    }
}

// The oracle: the latency of steps at evenly spaced instants over the horizon, from
// ConditionSchedule::viewLatency / sceneLatency one step at a time, then sorted.
TEST(PacingStats, LatencyQuantilesAgreeWithTheLatencyFunctionSampledDensely) {
    for (const auto& [c, refresh] : variety()) {
        const ConditionSchedule schedule(c, refresh);
        const PacingStats s = pacingStats(schedule);
        // Steps fall between the first and the last instant the horizon's frames depict.
        const auto spans = schedule.viewLatencySpans(s.firstFrame, s.firstFrame + std::llround(s.horizonS * refresh));
        const auto scene = schedule.sceneLatencySpans(s.firstFrame, s.firstFrame + std::llround(s.horizonS * refresh));
        auto sampled = [&](bool view, double from, double to) {
            constexpr int kSamples = 12000;
            std::vector<double> v;
            for (int i = 0; i < kSamples; ++i) {
                const double tau = from + (to - from) * (i + 0.5) / kSamples;
                v.push_back(view ? schedule.viewLatency(tau) : schedule.sceneLatency(tau));
            }
            std::sort(v.begin(), v.end());
            return v;
        };
        // The exact q-quantile lies between the sorted samples around rank q n (both sides: where
        // the latency jumps, a whole range of values is the quantile) to within a sampling step:
        // 0.3 ms is a few (10 s / 12000 samples = 0.83 ms between steps, spread over the spans).
        constexpr double kToleranceS = 0.3e-3;
        auto expectQuantile = [&](double exact, const std::vector<double>& v, double q, const char* what) {
            const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size()));
            EXPECT_GE(exact, v[k - 1] - kToleranceS) << c.name << " " << what;
            EXPECT_LE(exact, v[k] + kToleranceS) << c.name << " " << what;
        };
        const auto view = sampled(true, spans.front().from, spans.back().to);
        expectQuantile(s.viewS.median, view, 0.5, "view median");
        expectQuantile(s.viewS.p95, view, 0.95, "view p95");
        const auto world = sampled(false, scene.front().from, scene.back().to);
        expectQuantile(s.sceneS.median, world, 0.5, "scene median");
        expectQuantile(s.sceneS.p95, world, 0.95, "scene p95");
    }
}

// A step at a uniform instant of a 15 fps hold waits 0 to 66.7 ms for the next render: the
// median half of that, the 95th percentile 95 % of it.
TEST(PacingStats, Conv15ViewLatencyIsUniformOverTheRenderPeriod) {
    const PacingStats s = pacingStats(ConditionSchedule(preset("conv15"), 120));
    EXPECT_NEAR(s.viewS.min, 0, 1e-9);
    EXPECT_NEAR(s.viewS.median * 1000, 1000.0 / 30, 1e-6);
    EXPECT_NEAR(s.viewS.p95 * 1000, 0.95 * 1000.0 / 15, 1e-6);
    EXPECT_NEAR(s.viewS.max * 1000, 1000.0 / 15, 1e-6);
}

}  // namespace
}  // namespace warplab::condition
