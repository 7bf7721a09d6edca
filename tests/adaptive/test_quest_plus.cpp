// QUEST+ against a brute-force computation written out here from Watson (2017), and against a
// simulated observer whose psychometric function is known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "adaptive/psychometric.h"
#include "adaptive/quest_plus.h"
#include "physics/splitmix.h"

namespace warplab::adaptive {
namespace {

// The classic Weibull of the stimulus in two-interval forced choice, written out.
double weibull2ifc(double x, double t, double b, double l) {
    return 0.5 + (0.5 - l) * (1.0 - std::exp(-std::pow(x / t, b)));
}

TEST(QuestPlus, PosteriorAndNextLevelEqualABruteForceComputation) {
    QuestPlusSettings s;
    s.stimuli = {1, 2, 4, 8};
    s.thresholds = {1.5, 3, 6};
    s.slopes = {1, 3};
    s.lapses = {0, 0.05};
    for (int i = 0; i < 12; ++i) s.prior.push_back(1.0 + i);  // not uniform, so its order matters
    QuestPlus quest(s);

    // The same by hand: the posterior as nested loops, threshold outermost.
    std::vector<double> post(s.prior);
    double sum = 0;
    for (double w : post) sum += w;
    for (double& w : post) w /= sum;
    const auto p = [&](std::size_t level, std::size_t i) {
        const std::size_t t = i / 4, b = (i / 2) % 2, l = i % 2;
        return weibull2ifc(s.stimuli[level], s.thresholds[t], s.slopes[b], s.lapses[l]);
    };
    const std::vector<bool> answers = {true, false, true, true, false, true};
    for (const bool answer : answers) {
        std::size_t best = 0;
        double least = 1e300;
        for (std::size_t level = 0; level < s.stimuli.size(); ++level) {
            double expected = 0;
            for (const bool r : {true, false}) {
                double pr = 0;
                for (std::size_t i = 0; i < post.size(); ++i) pr += post[i] * (r ? p(level, i) : 1 - p(level, i));
                double h = 0;
                for (std::size_t i = 0; i < post.size(); ++i) {
                    const double q = post[i] * (r ? p(level, i) : 1 - p(level, i)) / pr;
                    if (q > 0) h -= q * std::log(q);
                }
                expected += pr * h;
            }
            EXPECT_NEAR(quest.expectedEntropy(level), expected, 1e-12) << "level " << level;
            if (expected < least) least = expected, best = level;
        }
        ASSERT_EQ(quest.next(), best);
        double total = 0;
        for (std::size_t i = 0; i < post.size(); ++i) total += post[i] *= answer ? p(best, i) : 1 - p(best, i);
        for (double& w : post) w /= total;
        quest.update(best, answer);
        for (std::size_t i = 0; i < post.size(); ++i) EXPECT_NEAR(quest.posterior()[i], post[i], 1e-12) << i;
    }
    EXPECT_EQ(quest.trials(), answers.size());

    // The threshold's marginal: its mean and the grid values where the cumulative mass reaches
    // 2.5 % and 97.5 %.
    double mean = 0;
    std::vector<double> mass(3, 0.0);
    for (std::size_t i = 0; i < post.size(); ++i) mass[i / 4] += post[i];
    for (std::size_t t = 0; t < 3; ++t) mean += mass[t] * s.thresholds[t];
    EXPECT_NEAR(quest.threshold().mean, mean, 1e-12);
    std::size_t low = 0, high = 0;
    for (double c = mass[0]; c < 0.025; c += mass[++low]) {}
    for (double c = mass[0]; c < 0.975; c += mass[++high]) {}
    EXPECT_EQ(quest.threshold().low, s.thresholds[low]);
    EXPECT_EQ(quest.threshold().high, s.thresholds[high]);
}

// A simulated observer of known threshold, slope and lapse, answering from its function with
// seeded chance: QUEST+ finds its threshold inside the 95 % credible interval in most runs.
TEST(QuestPlus, RecoversAKnownObserversThreshold) {
    const PsychometricFunction f;  // Weibull of the stimulus, 2IFC
    const double trueThreshold = 17.0, trueSlope = 3.0, trueLapse = 0.02;
    QuestPlusSettings s;
    s.function = f;
    for (int k = 0; k < 20; ++k) s.stimuli.push_back(2.0 * std::pow(40.0, k / 19.0));  // 2 to 80 ms
    for (int k = 0; k < 24; ++k) s.thresholds.push_back(2.0 * std::pow(40.0, k / 23.0));
    s.slopes = {1, 2, 3, 4, 6};
    s.lapses = {0, 0.02, 0.05};
    int inside = 0;
    std::vector<double> errors;
    for (std::uint64_t seed = 1; seed <= 50; ++seed) {
        QuestPlus quest(s);
        std::uint64_t chance = seed * 0x9e3779b97f4a7c15ULL;
        for (int trial = 0; trial < 64; ++trial) {
            const std::size_t level = quest.next();
            const double p = f.probability(s.stimuli[level], trueThreshold, trueSlope, trueLapse);
            quest.update(level, physics::uniform01(chance) < p);
        }
        const Estimate t = quest.threshold();
        inside += t.low <= trueThreshold && trueThreshold <= t.high;
        errors.push_back(std::abs(std::log(t.mean / trueThreshold)));
        EXPECT_LT(t.low, t.high) << "seed " << seed;
    }
    EXPECT_GE(inside, 42) << "of 50 runs";
    std::nth_element(errors.begin(), errors.begin() + 25, errors.end());
    EXPECT_LT(errors[25], 0.25) << "median |log(estimate / true)|";
}

TEST(QuestPlus, RefusesGridsItCannotUse) {
    QuestPlusSettings s;
    s.stimuli = {1, 2};
    s.thresholds = {1, 2};
    s.slopes = {2};
    s.lapses = {0};
    EXPECT_NO_THROW(QuestPlus{s});
    QuestPlusSettings bad = s;
    bad.prior = {1, 2, 3};
    EXPECT_THROW(QuestPlus{bad}, std::invalid_argument);
    bad = s;
    bad.prior = {0, 0};
    EXPECT_THROW(QuestPlus{bad}, std::invalid_argument);
    bad = s;
    bad.thresholds = {2, 1};
    EXPECT_THROW(QuestPlus{bad}, std::invalid_argument);
    bad = s;
    bad.slopes.clear();
    EXPECT_THROW(QuestPlus{bad}, std::invalid_argument);
    bad = s;
    bad.stimuli = {0, 1};  // the log scale has no 0
    EXPECT_THROW(QuestPlus{bad}, std::domain_error);
    QuestPlus quest(s);
    EXPECT_THROW(quest.update(2, true), std::out_of_range);
}

// ---------------------------------------------------------------- the psychometric function

TEST(PsychometricFunction, IsTheStatedFormulaAndItsInverse) {
    const PsychometricFunction weibullLog;
    EXPECT_DOUBLE_EQ(weibullLog.probability(7.0, 10.0, 2.5, 0.03), weibull2ifc(7.0, 10.0, 2.5, 0.03));
    PsychometricFunction logistic{Shape::Logistic, Scale::Linear, 0.5};
    // At the threshold a logistic is half way between the guess rate and 1 - lapse.
    EXPECT_DOUBLE_EQ(logistic.probability(4.0, 4.0, 1.7, 0.1), 0.5 + 0.4 / 2);
    EXPECT_DOUBLE_EQ(logistic.probability(5.0, 4.0, 2.0, 0.0), 0.5 + 0.5 / (1 + std::exp(-2.0)));
    for (const Shape shape : {Shape::Logistic, Shape::Weibull})
        for (const Scale scale : {Scale::Linear, Scale::Log}) {
            const PsychometricFunction f{shape, scale, 0.5};
            for (const double pc : {55.0, 70.7, 75.0, 90.0}) {
                const double x = f.stimulusAt(pc, 12.0, 2.0, 0.04);
                EXPECT_NEAR(f.probability(x, 12.0, 2.0, 0.04), pc / 100.0, 1e-12) << pc;
            }
            EXPECT_THROW(f.stimulusAt(50.0, 12.0, 2.0, 0.04), std::domain_error);
            EXPECT_THROW(f.stimulusAt(97.0, 12.0, 2.0, 0.04), std::domain_error);  // above 1 - lapse
        }
    // Far from the threshold nothing overflows.
    EXPECT_EQ(weibullLog.probability(1e6, 1.0, 50.0, 0.0), 1.0);
    EXPECT_EQ(logistic.probability(-1e6, 1.0, 50.0, 0.0), 0.5);
}

}  // namespace
}  // namespace warplab::adaptive
