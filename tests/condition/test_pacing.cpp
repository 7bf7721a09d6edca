// Render instants as data: any render rate up to the refresh, seeded jitter and hitches, each
// render shown at the first refresh at or after it -- and the presets exactly as they were.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "condition/reference_schedule.h"
#include "condition/render_frames.h"
#include "condition/schedule.h"

namespace warplab::condition {
namespace {

Condition steady(double renderHz, const std::string& fill = "hold") {
    Condition c;
    c.name = "paced";
    c.renderHz = renderHz;
    c.fill = fill;
    return c;
}

std::vector<std::int64_t> intervals(const std::vector<std::int64_t>& frames) {
    std::vector<std::int64_t> out;
    for (std::size_t i = 1; i < frames.size(); ++i) out.push_back(frames[i] - frames[i - 1]);
    return out;
}

// Every preset at every refresh it ran at before, over minutes of frames and the frames before
// a schedule starts (what a lag or bidirectional queue held): every field the same.
TEST(Pacing, PresetsExpandToTheScheduleTheyHadFrameByFrame) {
    int compared = 0;
    for (const Condition& c : presets())
        for (double refresh : {30.0, 60.0, 120.0, 240.0, 480.0, 59.94, 119.88}) {
            const auto period = wholeRatio(refresh, c.renderHz);
            if (!period || problem(c, refresh)) continue;
            if (c.fillHz && (!wholeRatio(refresh, *c.fillHz) || *period % *wholeRatio(refresh, *c.fillHz) != 0))
                continue;
            EXPECT_EQ(reference::firstDifference(c, refresh, -3000, 40000), "");
            ++compared;
        }
    EXPECT_GE(compared, 30);
}

// A vsync'd 60 fps game on a 144 Hz display: each render at the first refresh at or after
// i / 60 s, so 2 or 3 refreshes apart, 2.4 on average.
TEST(Pacing, SixtyOnOneFortyFourShowsTwoThreeCadenceOfMeanExactlyTwoPointFour) {
    const ConditionSchedule s(steady(60), 144);
    const std::vector<std::int64_t> frames = renderFrames(s, 1440);  // 10 s
    ASSERT_EQ(frames.front(), 0);
    ASSERT_EQ(frames.back(), 1440);
    ASSERT_EQ(frames.size(), 601u);  // 600 intervals of 10 s at 60 fps
    std::int64_t sum = 0;
    for (const std::int64_t d : intervals(frames)) {
        EXPECT_TRUE(d == 2 || d == 3) << d;
        sum += d;
    }
    EXPECT_EQ(sum * 5, 600 * 12);  // a mean of exactly 12 / 5
    EXPECT_EQ(std::vector<std::int64_t>(frames.begin(), frames.begin() + 6),
              (std::vector<std::int64_t>{0, 3, 5, 8, 10, 12}));
    // Held frames show the latest render; the camera is the one read at it.
    for (std::int64_t k = 0; k < 300; ++k) {
        const ScheduledFrame f = s.frame(k);
        EXPECT_EQ(f.sourceIndex, *std::prev(std::upper_bound(frames.begin(), frames.end(), k))) << k;
        EXPECT_DOUBLE_EQ(f.cameraTime, static_cast<double>(f.sourceIndex) / 144) << k;
    }
    EXPECT_NEAR(s.viewLatencyRange().min * 144, 0, 1e-9);
    EXPECT_NEAR(s.viewLatencyRange().max * 144, 3, 1e-9);
}

TEST(Pacing, OtherRatesTheRefreshDoesNotDivideRun) {
    struct Case {
        double render, refresh;
        std::int64_t shorter, longer;
    };
    for (const Case c : {Case{50, 120, 2, 3}, Case{90, 144, 1, 2}, Case{100, 240, 2, 3}, Case{60, 165, 2, 3},
                         Case{15, 144, 9, 10}, Case{120, 144, 1, 2}}) {
        const ConditionSchedule s(steady(c.render), c.refresh);
        const auto frames = renderFrames(s, static_cast<std::int64_t>(c.refresh) * 10);
        EXPECT_EQ(static_cast<double>(frames.size() - 1), c.render * 10) << c.render << " on " << c.refresh;
        for (const std::int64_t d : intervals(frames))
            EXPECT_TRUE(d == c.shorter || d == c.longer) << c.render << " on " << c.refresh << ": " << d;
    }
    EXPECT_THROW(ConditionSchedule(steady(145), 144), std::invalid_argument);
}

double sampleSdMs(const std::vector<std::int64_t>& frameIntervals, double refreshHz) {
    double mean = 0, sq = 0;
    for (const auto d : frameIntervals) mean += static_cast<double>(d);
    mean /= static_cast<double>(frameIntervals.size());
    for (const auto d : frameIntervals) sq += (static_cast<double>(d) - mean) * (static_cast<double>(d) - mean);
    return std::sqrt(sq / static_cast<double>(frameIntervals.size() - 1)) * 1000.0 / refreshHz;
}

// Jittered intervals are the seed's: the same seed, the same cadence; another seed, another.
// Their SD, measured on a 1000 Hz display so that showing them at whole refreshes adds little
// (a millisecond's rounding: about 0.4 ms in quadrature), is within 6 % of the one asked.
TEST(Pacing, JitterIsTheSeedsAndHasTheSdAsked) {
    constexpr double kRefresh = 1000;
    struct Case {
        JitterShape shape;
        double sdMs, rangeMs, expectedSdMs;
    };
    for (const Case c : {Case{JitterShape::Normal, 4, 0, 4 * 0.9866}, Case{JitterShape::Lognormal, 12, 0, 12 * 0.985},
                         Case{JitterShape::Uniform, 0, 16, 16 / std::sqrt(12.0)}}) {
        Condition j = steady(60);
        j.jitter = {c.shape, c.sdMs, c.rangeMs};
        const ConditionSchedule a(j, kRefresh, 7), b(j, kRefresh, 7), other(j, kRefresh, 8);
        const auto frames = renderFrames(a, 200000);  // 200 s, some 12000 renders
        EXPECT_EQ(frames, renderFrames(b, 200000));
        EXPECT_NE(frames, renderFrames(other, 200000));
        const double sd = sampleSdMs(intervals(frames), kRefresh);
        EXPECT_NEAR(sd, c.expectedSdMs, 0.06 * c.expectedSdMs) << jitterShapeName(c.shape);
        // Normal draws beyond 3 SD are drawn again (some 30 of these 12000 would lie beyond),
        // so no interval is farther from the mean than that and a refresh of rounding.
        if (c.shape == JitterShape::Normal) {
            const std::vector<std::int64_t> each = intervals(frames);
            const auto [shortest, longest] = std::minmax_element(each.begin(), each.end());
            EXPECT_LE(static_cast<double>(*longest), 1000.0 / 60 + 3 * c.sdMs + 1);
            EXPECT_GE(static_cast<double>(*shortest), 1000.0 / 60 - 3 * c.sdMs - 1);
        }
        // The mean rate stays render_hz (log-normal's cut tail lowers its mean interval a little).
        EXPECT_NEAR(static_cast<double>(frames.size() - 1) / 200.0, 60.0, 60.0 * 0.01) << jitterShapeName(c.shape);
    }
}

// A 100 ms hitch every 2 s at 60 fps on 144 Hz: one long interval just after each 2 s mark,
// as long as a render interval plus the hitch, and none elsewhere.
TEST(Pacing, PeriodicHitchesStallTheRenderDueWhenEachFalls) {
    Condition c = steady(60);
    c.hitches.ms = 100;
    c.hitches.everyS = 2;
    const ConditionSchedule s(c, 144, 1);
    const auto frames = renderFrames(s, 144 * 11);
    std::vector<double> stalls;  // the instants the long intervals start
    for (std::size_t i = 1; i < frames.size(); ++i) {
        const std::int64_t d = frames[i] - frames[i - 1];
        if (d > 3) {
            EXPECT_GE(d, 14 + 2);  // 100 ms is 14.4 refreshes, on top of the interval it stalls
            EXPECT_LE(d, 15 + 3);
            stalls.push_back(static_cast<double>(frames[i - 1]) / 144);
        }
    }
    ASSERT_EQ(stalls.size(), 5u);
    for (std::size_t n = 0; n < stalls.size(); ++n) {
        // Hitches fall on the display's clock, every 2 s, whatever the stalls before them.
        const double due = 2.0 * static_cast<double>(n + 1);
        EXPECT_NEAR(stalls[n], due, 1.0 / 60 + 1.0 / 144) << n;
    }
}

TEST(Pacing, RandomHitchesComeAtTheirRate) {
    Condition c = steady(60);
    c.hitches.ms = 50;
    c.hitches.ratePerS = 0.5;
    const ConditionSchedule s(c, 120, 3);
    const auto frames = renderFrames(s, 120 * 400);
    int stalls = 0;
    for (const auto d : intervals(frames)) stalls += d > 3;
    // 400 s: 200 expected, SD 14.
    EXPECT_GT(stalls, 155);
    EXPECT_LT(stalls, 245);
    // The seed's: the same seed, the same stalls; another seed, others.
    EXPECT_EQ(frames, renderFrames(ConditionSchedule(c, 120, 3), 120 * 400));
    EXPECT_NE(frames, renderFrames(ConditionSchedule(c, 120, 4), 120 * 400));
}

// Hitches that fall during a stall merge with it: the render after a stall waits only for a
// hitch falling in its own interval. 100 ms hitches at 4 a second: one falls within a stall a
// third of the time (1 - e^-0.4), within a 60 fps interval after it 6 % of the time (1 - e^-1/15).
TEST(Pacing, HitchesFallingDuringAStallMergeWithIt) {
    Condition c = steady(60);
    c.hitches.ms = 100;
    c.hitches.ratePerS = 4;
    const auto frameIntervals = intervals(renderFrames(ConditionSchedule(c, 1000, 9), 1000 * 200));
    int stalls = 0, stallAfterStall = 0;
    for (std::size_t i = 0; i < frameIntervals.size(); ++i) {
        if (frameIntervals[i] < 100) continue;
        ++stalls;
        stallAfterStall += i + 1 < frameIntervals.size() && frameIntervals[i + 1] >= 100;
    }
    EXPECT_GT(stalls, 400);  // some 600 in 200 s
    EXPECT_LT(stallAfterStall, stalls / 6) << stallAfterStall << " of " << stalls;
}

// Warp fills from the latest render at every refresh; bidirectional reprojection plays each
// render interval once the render that ends it has arrived, however long that took.
TEST(Pacing, FillsWorkOverUnevenRenders) {
    Condition warp = steady(60, "warp-sparse8");
    warp.hitches = {100, 1, 0};
    const ConditionSchedule w(warp, 144, 5);
    const auto frames = renderFrames(w, 144 * 4);
    for (std::int64_t k = 0; k < 144 * 4; ++k) {
        const ScheduledFrame f = w.frame(k);
        EXPECT_EQ(f.sourceIndex, *std::prev(std::upper_bound(frames.begin(), frames.end(), k))) << k;
        EXPECT_DOUBLE_EQ(f.cameraTime, static_cast<double>(k) / 144) << k;
        EXPECT_EQ(f.kind, f.rendersNow ? FrameKind::Rendered : FrameKind::Warped) << k;
    }
    Condition bi = steady(60, "bireproj");
    bi.hitches = {100, 1, 0};
    const ConditionSchedule b(bi, 144, 5);
    double lastDepicted = -1e9;
    int interpolated = 0, heldAtRender = 0;
    for (std::int64_t k = 0; k < 144 * 4; ++k) {
        const ScheduledFrame f = b.frame(k);
        EXPECT_GE(f.sceneTime, lastDepicted) << k;  // never backwards
        lastDepicted = f.sceneTime;
        if (f.nextSourceIndex >= 0) {
            ++interpolated;
            // Between two consecutive renders, shown only once the later one exists.
            EXPECT_LE(f.nextSourceIndex, k) << k;
            EXPECT_EQ(b.cadence().firstAfter(f.sourceIndex), f.nextSourceIndex) << k;
            EXPECT_GT(f.sceneTime * 144, static_cast<double>(f.sourceIndex) - 1e-9) << k;
            EXPECT_LT(f.sceneTime * 144, static_cast<double>(f.nextSourceIndex)) << k;
        } else if (k > 0 && f.kind == FrameKind::Held) {
            ++heldAtRender;  // waiting through a hitch for the next render
        }
    }
    EXPECT_GT(interpolated, 100);
    EXPECT_GT(heldAtRender, 10);
    EXPECT_NO_THROW(b.viewLatencyRange());
}

std::string problemOf(const Condition& c, double refreshHz) {
    const auto p = problem(c, refreshHz);
    return p ? p->part + ": " + p->reason : "";
}

// The published upconversion presets on a 144 Hz display: their fill rates (120, 60 Hz) do not
// divide it, so the fill makes its frames at the first refresh at or after each of its
// instants, as renders are shown; every frame the schedule shows new is a render or such a
// fill frame, and nothing else.
TEST(Pacing, AFillTheRefreshDoesNotDivideMakesItsFramesUnevenly) {
    for (const char* name : {"warp15to120", "bireproj15to60"}) {
        const Condition& c = preset(name);
        ASSERT_EQ(problem(c, 144.0), std::nullopt) << name;
        const ConditionSchedule s(c, 144.0);
        const double fillFrames = 144.0 / *c.fillHz, renderFrames = 144.0 / c.renderHz;
        std::set<std::int64_t> expected;
        for (std::int64_t i = 0; i * fillFrames < 2000; ++i)
            expected.insert(static_cast<std::int64_t>(std::ceil(static_cast<double>(i) * fillFrames - 1e-7)));
        for (std::int64_t i = 0; i * renderFrames < 2000; ++i)
            expected.insert(static_cast<std::int64_t>(std::ceil(static_cast<double>(i) * renderFrames - 1e-7)));
        // Bidirectional reprojection plays a render interval once its later render exists: its
        // new frames are those instants, after the first interval it cannot yet play.
        const std::int64_t from = c.fillKind() == Fill::Bireproj ? 10 : 0;
        std::vector<std::int64_t> shown, wanted;
        for (std::int64_t k = from; k < 1900; ++k) {
            if (s.frame(k).kind != FrameKind::Held) shown.push_back(k);
            if (expected.count(k)) wanted.push_back(k);
        }
        EXPECT_EQ(shown, wanted) << name;
        // The fill's frames are 1 or 2 refreshes apart (120 Hz) or 2 or 3 (60 Hz): 1.2 and 2.4
        // on average.
        EXPECT_NEAR(static_cast<double>(shown.size()) / static_cast<double>(1900 - from) * fillFrames, 1.0, 0.01)
            << name;
    }
}

TEST(Pacing, ParametersOutOfRangeNameTheKeyAndWhatIsAllowed) {
    Condition c = steady(60);
    c.jitter = {JitterShape::Normal, 6, 0};
    EXPECT_EQ(problemOf(c, 144),
              "frame_time_jitter.sd_ms: is 6 ms; a normal jitter's SD must be above 0 and at most a third of the "
              "mean render interval (16.6667 ms at render_hz 60), so intervals stay positive (\"lognormal\" allows "
              "wider)");
    c.jitter = {JitterShape::Lognormal, 0, 0};
    EXPECT_EQ(problemOf(c, 144).rfind("frame_time_jitter.sd_ms: is 0 ms", 0), 0u);
    c.jitter = {JitterShape::Uniform, 0, 40};
    EXPECT_EQ(problemOf(c, 144).rfind("frame_time_jitter.range_ms: is 40 ms", 0), 0u);
    c.jitter = {};
    c.hitches = {600, 0.5, 0};
    EXPECT_EQ(problemOf(c, 144),
              "hitches.ms: is 600 ms, not shorter than its period (every_s 0.5 s); a hitch must end before the next "
              "is due");
    c.hitches = {100, 2, 1};
    EXPECT_EQ(problemOf(c, 144).rfind("hitches: needs one of every_s", 0), 0u);
    c.hitches = {100, 0, 20};
    EXPECT_EQ(problemOf(c, 144).rfind("hitches.ms: is 100 ms, not shorter than its mean period", 0), 0u);
    c.hitches = {5000, 10, 0};
    EXPECT_EQ(problemOf(c, 1000).rfind("hitches.ms: looks back", 0), 0u);
    c.hitches = {100, 2, 0};
    EXPECT_EQ(problemOf(c, 144), "");
}

}  // namespace
}  // namespace warplab::condition
