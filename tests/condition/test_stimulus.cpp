// A discrimination task's stimulus dimensions: the condition at a level, and what a display can
// show of it.
#include <gtest/gtest.h>

#include <stdexcept>

#include "condition/condition.h"
#include "condition/stimulus.h"

namespace warplab::condition {
namespace {

TEST(Stimulus, ALagLevelIsTheReferenceWithThatManyFramesOfQueue) {
    Condition reference = preset("conv120");
    reference.lateWarp = LateWarp::Rotation;  // the late-warp staircase's reference keeps its warp
    const Condition c = varied(reference, Dimension::LagFrames, 3);
    EXPECT_EQ(c.name, "conv120@lag_frames=3");
    EXPECT_EQ(lagFramesAt(c, 120), 3);
    EXPECT_EQ(c.lateWarp, LateWarp::Rotation);
    EXPECT_EQ(c.renderHz, 120);
    EXPECT_FALSE(problem(c, 120));
    // A reference with lag in milliseconds has it replaced, not added to.
    const Condition fromLag = varied(preset("lag50"), Dimension::LagFrames, 1);
    EXPECT_EQ(lagFramesAt(fromLag, 60), 1);
    EXPECT_EQ(fromLag.lagMs, 0.0);  // what conditions.csv would report as its added lag
    EXPECT_EQ(varied(reference, Dimension::LagFrames, 0).lagFrames, 0);
    for (const double bad : {2.5, -1.0, double(kMaxLagFrames) + 1})
        EXPECT_THROW(varied(reference, Dimension::LagFrames, bad), std::invalid_argument) << bad;
}

TEST(Stimulus, ARateOrJitterLevelIsWhatTheDisplayDecidesItCanShow) {
    const Condition conv = preset("conv120");
    const Condition slow = varied(conv, Dimension::RenderHz, 45);
    EXPECT_EQ(slow.renderHz, 45);
    EXPECT_FALSE(problem(slow, 120)) << "an uneven cadence runs";
    const auto above = problem(varied(conv, Dimension::RenderHz, 144), 120);
    ASSERT_TRUE(above);
    EXPECT_EQ(above->part, "render_hz");
    EXPECT_THROW(varied(conv, Dimension::RenderHz, 0), std::invalid_argument);

    const Condition jittered = varied(preset("conv60"), Dimension::JitterSdMs, 4);
    EXPECT_EQ(jittered.jitter.shape, JitterShape::Normal);
    EXPECT_EQ(jittered.jitter.sdMs, 4);
    EXPECT_EQ(jittered.name, "conv60@frame_time_jitter.sd_ms=4");
    EXPECT_TRUE(varied(preset("conv60"), Dimension::JitterSdMs, 0).steadyPacing());
    EXPECT_THROW(varied(conv, Dimension::JitterSdMs, -1), std::invalid_argument);
}

TEST(Stimulus, DimensionsAreNamedByTheConditionsOwnKeys) {
    for (const DimensionSpelling& d : dimensionSpellings()) {
        EXPECT_EQ(dimensionNamed(d.name), d.dimension);
        EXPECT_STREQ(dimensionName(d.dimension), d.name);
    }
    EXPECT_EQ(dimensionSpellings().size(), 3u);
    EXPECT_FALSE(dimensionNamed("lag_ms"));
}

}  // namespace
}  // namespace warplab::condition
