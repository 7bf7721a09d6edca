// The transformed up-down staircase (Levitt 1971) and the method of constant stimuli.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "adaptive/psychometric.h"
#include "adaptive/staircase.h"
#include "physics/splitmix.h"

namespace warplab::adaptive {
namespace {

StaircaseSettings tenLevels() {
    StaircaseSettings s;
    for (int k = 1; k <= 10; ++k) s.stimuli.push_back(10.0 * k);
    s.start = 7;
    s.steps = {2, 1};  // a coarse step until the first reversal, then one level
    return s;
}

TEST(Staircase, OneUpTwoDownStepsAndTurnsAsLevittsRuleSays) {
    Staircase s(tenLevels());
    // Two right: harder (lower) by 2; one wrong: easier, a reversal, now by 1; and so on.
    const std::vector<bool> answers = {true, true, true, true, false, true, true, false, false, true, true};
    const std::vector<std::size_t> levels = {7, 7, 5, 5, 3, 4, 4, 3, 4, 5, 5};
    for (std::size_t i = 0; i < answers.size(); ++i) {
        ASSERT_EQ(s.next(), levels[i]) << "trial " << i;
        s.update(answers[i]);
    }
    EXPECT_EQ(s.next(), 4u);
    EXPECT_EQ(s.reversals(), (std::vector<std::size_t>{3, 4, 3, 5}));
    EXPECT_DOUBLE_EQ(s.threshold(2), (40.0 + 60.0) / 2);
    EXPECT_TRUE(std::isnan(s.threshold(5)));
    EXPECT_EQ(s.trials(), answers.size());
}

TEST(Staircase, StaysWithinItsLevelsAndHarderMeansLowerOnlyWhenHigherIsEasier) {
    StaircaseSettings settings = tenLevels();
    settings.start = 1;
    Staircase down(settings);
    for (int i = 0; i < 8; ++i) down.update(true);
    EXPECT_EQ(down.next(), 0u);
    settings.higherIsEasier = false;  // e.g. a frame rate: higher is harder to tell from the reference
    Staircase up(settings);
    for (int i = 0; i < 40; ++i) up.update(true);
    EXPECT_EQ(up.next(), 9u);
    settings.start = 10;
    EXPECT_THROW(Staircase{settings}, std::invalid_argument);
    settings = tenLevels();
    settings.down = 0;
    EXPECT_THROW(Staircase{settings}, std::invalid_argument);
}

// A simulated observer of known function: 1-up-2-down settles near its 70.7 % point.
TEST(Staircase, SettlesNearTheSeventyPercentPointOfAKnownObserver) {
    const PsychometricFunction f;
    StaircaseSettings settings;
    for (int k = 0; k < 30; ++k) settings.stimuli.push_back(2.0 * std::pow(40.0, k / 29.0));
    settings.start = 25;
    settings.steps = {3, 1};
    const double target = f.stimulusAt(100.0 * std::sqrt(0.5), 17.0, 3.0, 0.0);
    std::vector<double> logErrors;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        Staircase s(settings);
        std::uint64_t chance = seed;
        for (int trial = 0; trial < 120; ++trial)
            s.update(physics::uniform01(chance) < f.probability(settings.stimuli[s.next()], 17.0, 3.0, 0.0));
        ASSERT_GE(s.reversals().size(), 8u) << "seed " << seed;
        logErrors.push_back(std::log(s.threshold(8) / target));
    }
    double mean = 0;
    for (double e : logErrors) mean += e / logErrors.size();
    EXPECT_LT(std::abs(mean), 0.12) << "mean log(estimate / 70.7 % point) over 20 runs";
}

TEST(ConstantStimuli, EachLevelItsRepeatsInASeededOrder) {
    const auto order = constantStimuliOrder(7, 5, 42);
    ASSERT_EQ(order.size(), 35u);
    for (std::size_t level = 0; level < 7; ++level)
        EXPECT_EQ(std::count(order.begin(), order.end(), level), 5) << level;
    EXPECT_EQ(constantStimuliOrder(7, 5, 42), order);
    EXPECT_NE(constantStimuliOrder(7, 5, 43), order);
    EXPECT_FALSE(std::is_sorted(order.begin(), order.end()));
    EXPECT_THROW(constantStimuliOrder(7, 0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace warplab::adaptive
