// What `warplab check` holds a machine's frame times against, per condition (cadence_check.h):
// the shortest interval between the new images its schedule shows, worked out by hand for a
// steady uneven cadence, a fill that makes every frame, a hitch and a jitter; and the verdict
// at the edge of it.
#include <gtest/gtest.h>

#include "cadence_check.h"
#include "condition/condition.h"

namespace warplab::live {
namespace {

condition::Condition at60(const std::string& fill = "hold") {
    condition::Condition c;
    c.name = "c60";
    c.renderHz = 60;
    c.fill = fill;
    return c;
}

TEST(CadenceCheck, SixtyOnA144HzDisplayAsksForTwoRefreshesAtItsShortest) {
    // Render i is shown at refresh ceil(2.4 i): 0, 3, 5, 8, 10, 12, ... 2 and 3 apart.
    const CadenceNeed need = cadenceNeed(at60(), 144.0);
    EXPECT_EQ(need.shortestFrames, 2);
    EXPECT_EQ(need.longestFrames, 3);
}

TEST(CadenceCheck, ThePresetsAskForTheirPeriodAndAFillForEveryFrame) {
    const CadenceNeed conv15 = cadenceNeed(condition::preset("conv15"), 120.0);
    EXPECT_EQ(conv15.shortestFrames, 8);
    EXPECT_EQ(conv15.longestFrames, 8);
    const CadenceNeed warp = cadenceNeed(condition::preset("warp15to120"), 120.0);
    EXPECT_EQ(warp.shortestFrames, 1);
    EXPECT_EQ(warp.longestFrames, 1);
}

TEST(CadenceCheck, AHitchLengthensOneIntervalAndJitterShortensSome) {
    condition::Condition hitch = at60();
    hitch.hitches = {100, 0.5, 0};
    const CadenceNeed stalled = cadenceNeed(hitch, 144.0);
    EXPECT_EQ(stalled.shortestFrames, 2);
    EXPECT_GE(stalled.longestFrames, 15);  // 100 ms is 14.4 refreshes, on top of the render's own
    condition::Condition jitter = at60();
    jitter.jitter = {condition::JitterShape::Normal, 4, 0};
    const CadenceNeed drawn = cadenceNeed(jitter, 144.0);
    // Intervals of 16.7 +- 12 ms: some new images a refresh apart, some 4.
    EXPECT_EQ(drawn.shortestFrames, 1);
    EXPECT_GE(drawn.longestFrames, 4);
}

TEST(CadenceCheck, TheP95MustFitTheShortestInterval) {
    const CadenceNeed need{2, 3};
    const CheckLine fits = cadenceLine("even60", need, 144.0, 13.8, 120);
    EXPECT_EQ(fits.verdict, Verdict::Ok);
    EXPECT_EQ(formatCheckLine(fits),
              "ok    cadence even60: its frames that make a new image take p95 13.8 ms over 120 frames, within the "
              "13.89 ms its schedule leaves the shortest of its intervals between new images (2 refreshes at 144 Hz; "
              "they run 2 to 3)");
    const CheckLine late = cadenceLine("even60", need, 144.0, 14.0, 120);
    EXPECT_EQ(late.verdict, Verdict::Fail);
    EXPECT_EQ(late.detail,
              "its frames that make a new image take p95 14.0 ms over 120 frames, longer than the 13.89 ms its "
              "schedule leaves the shortest of its intervals between new images (2 refreshes at 144 Hz; they run 2 "
              "to 3): its new images would reach the screen after the refreshes the schedule gives them");
}

}  // namespace
}  // namespace warplab::live
