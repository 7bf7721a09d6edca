// The pacing summary against a frame-time sequence worked out by hand: counts of shown, late and
// skipped display frames per condition, the median, nearest-rank 95th percentile and maximum of the
// shown frames' times, and the frames over budget; and its JSON form read back.
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "session/pacing.h"

namespace warplab::session {
namespace {

FrameRecord frame(const char* condition, double ms, int missed = 0, const char* kind = "rendered") {
    FrameRecord f;
    f.condition = condition;
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
    ASSERT_EQ(pacing.size(), 3u);  // the conditions in order of appearance, then the screens
    const ConditionPacing& a = pacing[0];
    EXPECT_EQ(a.condition, "conv60");
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
    const ConditionPacing& b = pacing[1];
    EXPECT_EQ(b.condition, "conv30");
    EXPECT_EQ(b.shown, 2);
    EXPECT_TRUE(std::isnan(b.medianMs));  // nothing measured: no number, not 0
    EXPECT_TRUE(std::isnan(b.maxMs));
    const ConditionPacing& screens = pacing[2];
    EXPECT_EQ(screens.condition, "");
    EXPECT_EQ(screens.shown, 1);
    EXPECT_DOUBLE_EQ(screens.medianMs, 16.0);
}

// 60 fps on 144 Hz: new images 3, 2, 3, 2, 2 refreshes apart, the rest held, every frame on
// time; then the machine falls behind twice: a held frame a refresh late (its image was the
// one on screen, so nothing was late) whose lost slot held a new image, and a new image a
// refresh late. Only that new image is late; the schedule's unevenness is not.
TEST(Pacing, LateCountsOnlyNewImagesThatMissedTheirRefresh) {
    const double b = 1000.0 / 144.0;
    const std::set<std::int64_t> newImages{0, 3, 5, 8, 10, 12, 15, 17, 20, 22, 24, 27, 29, 32};
    PacingTally tally;
    for (std::int64_t k = 0; k <= 32; ++k) {
        FrameRecord f = frame("conv60on144", b, 0, newImages.count(k) ? "rendered" : "held");
        f.frame = k;
        if (k == 26 || k == 29) {  // a refresh late
            f.missedVsyncs = 1;
            f.frameMs = 2 * b;
        }
        const std::string scheduled = f.kind;
        if (k == 27 || k == 30) {  // the slots they took
            f.kind = kSkippedFrameKind;
            f.frameMs = 0.0;
        }
        tally.add(f, scheduled);
    }
    const auto pacing = tally.summary(144.0);
    ASSERT_EQ(pacing.size(), 1u);
    const ConditionPacing& p = pacing[0];
    EXPECT_EQ(p.shown, 31);
    EXPECT_EQ(p.skipped, 2);
    EXPECT_EQ(p.late, 1);  // frame 29; not 26, which was held
    EXPECT_EQ(p.newImages, 14);  // frame 27 too, though never shown
    EXPECT_NEAR(p.intendedP95Ms, 3 * b, 1e-9);
    EXPECT_NEAR(p.intendedMaxMs, 3 * b, 1e-9);
    // From 24 to 29, 27 never shown: 25, 26 (two refreshes), 28, 29 (two); the 12th of 12.
    EXPECT_NEAR(p.shownP95Ms, 6 * b, 1e-9);
    EXPECT_NEAR(p.shownMaxMs, 6 * b, 1e-9);
    const std::string report = pacingReport(pacing);
    EXPECT_NE(report.find("1 late (3.0 %), 2 skipped (6.1 %)"), std::string::npos) << report;
    EXPECT_NE(report.find("; new images 14, intended p95 20.8 ms, max 20.8, shown p95 41.7, max 41.7"),
              std::string::npos)
        << report;
}

// The gap between two runs of a condition (another condition's frames, a feedback pause) is no interval
// of its cadence; without measured times (headless) nothing was shown to measure.
TEST(Pacing, IntervalsStayWithinARunOfTheConditionsFrames) {
    std::vector<FrameRecord> frames;
    const char* conditions[] = {"a", "a", "b", "b", "a", "a", "a", "a"};
    const char* kinds[] = {"rendered", "rendered", "rendered", "rendered", "rendered", "frozen", "held", "rendered"};
    for (int k = 0; k < 8; ++k) {
        frames.push_back(frame(conditions[k], 0.0, 0, kinds[k]));
        frames.back().frame = k;
    }
    const auto pacing = summarizePacing(frames, 100.0);
    ASSERT_EQ(pacing.size(), 2u);
    EXPECT_EQ(pacing[0].newImages, 4);
    EXPECT_DOUBLE_EQ(pacing[0].intendedMaxMs, 10.0);  // 0 to 1 only: not 1 to 4, nor across the freeze
    EXPECT_TRUE(std::isnan(pacing[0].shownMaxMs));
    EXPECT_DOUBLE_EQ(pacing[1].intendedMaxMs, 10.0);
}

// What a session stored before the new images were kept reads as it was: its counts, and no
// intervals rather than zero ones.
TEST(Pacing, ASummaryStoredBeforeNewImagesReadsAsItWas) {
    std::vector<ConditionPacing> read;
    ASSERT_TRUE(parsePacing(R"([{"mode":"conv60","shown":21,"late":4,"skipped":2,"median_ms":11.0,"p95_ms":20.0,)"
                            R"("max_ms":50.0,"budget_ms":16.666,"over_budget":3}])",
                            read));
    ASSERT_EQ(read.size(), 1u);
    EXPECT_EQ(read[0].late, 4);
    EXPECT_FALSE(read[0].newImages.has_value()) << "not counted, rather than none counted";
    EXPECT_TRUE(std::isnan(read[0].intendedP95Ms));
    EXPECT_TRUE(std::isnan(read[0].shownMaxMs));
    EXPECT_EQ(pacingReport(read).find("new images"), std::string::npos);
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
    std::vector<ConditionPacing> read;
    ASSERT_TRUE(parsePacing(pacingText(pacing), read));
    ASSERT_EQ(read.size(), pacing.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        EXPECT_EQ(read[i].condition, pacing[i].condition);
        EXPECT_EQ(read[i].shown, pacing[i].shown);
        EXPECT_EQ(read[i].late, pacing[i].late);
        EXPECT_EQ(read[i].skipped, pacing[i].skipped);
        EXPECT_EQ(read[i].overBudget, pacing[i].overBudget);
        EXPECT_EQ(read[i].newImages, pacing[i].newImages);
        for (auto m : {&ConditionPacing::medianMs, &ConditionPacing::p95Ms, &ConditionPacing::maxMs,
                       &ConditionPacing::budgetMs, &ConditionPacing::intendedP95Ms, &ConditionPacing::intendedMaxMs,
                       &ConditionPacing::shownP95Ms, &ConditionPacing::shownMaxMs}) {
            if (std::isnan(pacing[i].*m))
                EXPECT_TRUE(std::isnan(read[i].*m));
            else
                EXPECT_EQ(read[i].*m, pacing[i].*m);
        }
    }
    EXPECT_FALSE(parsePacing("{}", read));
    EXPECT_FALSE(parsePacing("[{\"shown\": 3}]", read));
}

TEST(Pacing, TheReportNamesEachConditionAndTheBudget) {
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
