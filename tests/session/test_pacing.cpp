// The pacing summary against a frame-time sequence worked out by hand: counts of shown, late and
// skipped display frames per mode, the median, nearest-rank 95th percentile and maximum of the
// shown frames' times, and the frames over budget; and its JSON form read back.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "session/pacing.h"

namespace warplab::session {
namespace {

FrameRecord frame(const char* mode, double ms, int missed = 0, const char* kind = "rendered") {
    FrameRecord f;
    f.mode = mode;
    f.kind = kind;
    f.frameMs = ms;
    f.missedVsyncs = missed;
    return f;
}

// conv60 at 60 Hz (16.67 ms budget): twenty frames of 1..20 ms, then one 50 ms frame that
// missed two vsyncs and the two display frames it skipped; a screen frame; conv30's frames
// without measured times (as headless).
std::vector<FrameRecord> sequence() {
    std::vector<FrameRecord> frames;
    for (int ms = 1; ms <= 20; ++ms) frames.push_back(frame("conv60", ms));
    frames.push_back(frame("conv60", 50.0, 2));
    frames.push_back(frame("conv60", 0.0, 0, kSkippedFrameKind));
    frames.push_back(frame("conv60", 0.0, 0, kSkippedFrameKind));
    frames.push_back(frame("", 16.0, 0, "screen"));
    frames.push_back(frame("conv30", 0.0));
    frames.push_back(frame("conv30", 0.0));
    return frames;
}

TEST(Pacing, SummarisesAKnownSequence) {
    const auto pacing = summarizePacing(sequence(), 60.0);
    ASSERT_EQ(pacing.size(), 3u);  // the modes in order of appearance, then the screens
    const ModePacing& a = pacing[0];
    EXPECT_EQ(a.mode, "conv60");
    EXPECT_EQ(a.shown, 21);
    EXPECT_EQ(a.late, 1);
    EXPECT_EQ(a.skipped, 2);
    EXPECT_DOUBLE_EQ(a.budgetMs, 1000.0 / 60.0);
    // 1..20 and 50: the 11th of 21 is 11; the 95th percentile the ceil(0.95 * 21) = 20th, 20.
    EXPECT_DOUBLE_EQ(a.medianMs, 11.0);
    EXPECT_DOUBLE_EQ(a.p95Ms, 20.0);
    EXPECT_DOUBLE_EQ(a.maxMs, 50.0);
    // Over 1.1 budgets (18.33 ms): 19, 20 and 50.
    EXPECT_EQ(a.overBudget, 3);
    const ModePacing& b = pacing[1];
    EXPECT_EQ(b.mode, "conv30");
    EXPECT_EQ(b.shown, 2);
    EXPECT_TRUE(std::isnan(b.medianMs));  // nothing measured: no number, not 0
    EXPECT_TRUE(std::isnan(b.maxMs));
    const ModePacing& screens = pacing[2];
    EXPECT_EQ(screens.mode, "");
    EXPECT_EQ(screens.shown, 1);
    EXPECT_DOUBLE_EQ(screens.medianMs, 16.0);
}

TEST(Pacing, AnEvenCountTakesTheMeanOfTheMiddleTwo) {
    const auto pacing = summarizePacing({frame("m", 2.0), frame("m", 4.0), frame("m", 10.0), frame("m", 6.0)}, 100.0);
    ASSERT_EQ(pacing.size(), 1u);
    EXPECT_DOUBLE_EQ(pacing[0].medianMs, 5.0);
    EXPECT_DOUBLE_EQ(pacing[0].p95Ms, 10.0);
    EXPECT_EQ(pacing[0].overBudget, 0);  // 10 ms is one budget at 100 Hz: on time
}

TEST(Pacing, TheStoredTextReadsBack) {
    const auto pacing = summarizePacing(sequence(), 60.0);
    std::vector<ModePacing> read;
    ASSERT_TRUE(parsePacing(pacingText(pacing), read));
    ASSERT_EQ(read.size(), pacing.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        EXPECT_EQ(read[i].mode, pacing[i].mode);
        EXPECT_EQ(read[i].shown, pacing[i].shown);
        EXPECT_EQ(read[i].late, pacing[i].late);
        EXPECT_EQ(read[i].skipped, pacing[i].skipped);
        EXPECT_EQ(read[i].overBudget, pacing[i].overBudget);
        for (auto m : {&ModePacing::medianMs, &ModePacing::p95Ms, &ModePacing::maxMs, &ModePacing::budgetMs}) {
            if (std::isnan(pacing[i].*m))
                EXPECT_TRUE(std::isnan(read[i].*m));
            else
                EXPECT_EQ(read[i].*m, pacing[i].*m);
        }
    }
    EXPECT_FALSE(parsePacing("{}", read));
    EXPECT_FALSE(parsePacing("[{\"shown\": 3}]", read));
}

TEST(Pacing, TheReportNamesEachModeAndTheBudget) {
    const std::string report = pacingReport(summarizePacing(sequence(), 60.0));
    EXPECT_NE(report.find("every 16.67 ms"), std::string::npos) << report;
    EXPECT_NE(report.find("conv60: 21 shown (54.8 a second of 60), 1 late (4.3 %), 2 skipped (8.7 %); frame time "
                          "median 11.0 ms, p95 20.0, "
                          "max 50.0"),
              std::string::npos)
        << report;
    EXPECT_NE(report.find("(screens): 1 shown"), std::string::npos) << report;
}

}  // namespace
}  // namespace warplab::session
