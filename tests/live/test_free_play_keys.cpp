// Free play's keys without a window: the digits reach the first nine conditions, the steps reach
// every condition of a list of any length, passing over those the display cannot run.
#include <gtest/gtest.h>

#include "free_play_keys.h"
#include "condition/schedule.h"

namespace warplab::live {
namespace {

// Eleven conditions, more than the digits can name.
const std::vector<std::string> kEleven = {"m1", "m2", "m3", "m4", "m5", "m6", "m7", "m8", "m9", "m10", "m11"};
bool all(const std::string&) { return true; }

std::string after(const std::string& condition, const std::string& keys,
                  const std::function<bool(const std::string&)>& runs = all) {
    return applyFreePlayKeys({condition, 0}, keys, kEleven, runs).condition;
}

TEST(FreePlayKeys, DigitsPickTheFirstNineConditions) {
    EXPECT_EQ(after("m5", "1"), "m1");
    EXPECT_EQ(after("m1", "9"), "m9");
    EXPECT_EQ(after("m1", "0"), "m1");  // no tenth digit
    EXPECT_EQ(after("m1", "93"), "m3");  // in the order pressed
}

TEST(FreePlayKeys, StepsReachTheConditionsPastTheNinthAndWrapAround) {
    EXPECT_EQ(after("m9", "]"), "m10");
    EXPECT_EQ(after("m9", "]]"), "m11");
    EXPECT_EQ(after("m11", "]"), "m1");
    EXPECT_EQ(after("m1", "["), "m11");
    EXPECT_EQ(after("m10", "[["), "m8");
    EXPECT_EQ(after("m9", "]["), "m9");
    std::string condition = "m1";  // every condition, once, then the first again
    for (std::size_t i = 1; i <= kEleven.size(); ++i) {
        condition = after(condition, "]");
        EXPECT_EQ(condition, kEleven[i % kEleven.size()]);
    }
}

TEST(FreePlayKeys, StepsPassOverConditionsTheDisplayCannotRun) {
    const auto notTenOrOne = [](const std::string& m) { return m != "m10" && m != "m1"; };
    EXPECT_EQ(after("m9", "]", notTenOrOne), "m11");
    EXPECT_EQ(after("m11", "]", notTenOrOne), "m2");
    EXPECT_EQ(after("m2", "[", notTenOrOne), "m11");
    // Nothing else runs: the condition stays.
    EXPECT_EQ(after("m4", "]", [](const std::string& m) { return m == "m4"; }), "m4");
    EXPECT_EQ(after("m4", "[", [](const std::string&) { return false; }), "m4");
    // A digit still picks a condition that cannot run, so the game says why it refuses it.
    EXPECT_EQ(after("m4", "1", notTenOrOne), "m1");
}

TEST(FreePlayKeys, AConditionOutsideTheListStepsFromItsEnds) {
    EXPECT_EQ(after("custom", "]"), "m1");
    EXPECT_EQ(after("custom", "["), "m11");
}

TEST(FreePlayKeys, UAndDChangeTheLevelNotBelowZero) {
    EXPECT_EQ(applyFreePlayKeys({"m1", 0}, "uuu", kEleven, all).level, 3);
    EXPECT_EQ(applyFreePlayKeys({"m1", 1}, "ddd", kEleven, all).level, 0);
    EXPECT_EQ(applyFreePlayKeys({"m1", 2}, "ud]", kEleven, all).condition, "m2");
}

// The published conditions on the click game's 60 Hz display: conv120 and warp15to120 need 120 Hz.
TEST(FreePlayKeys, TheConditionTableAt60HzSkipsWhatNeeds120) {
    const auto conditions = condition::presetNames();
    const auto at60 = [](const std::string& m) { return condition::ConditionTable().check(m, 60.0).empty(); };
    EXPECT_EQ(applyFreePlayKeys({"lag200", 0}, "]", conditions, at60).condition, "bireproj15to60");
    EXPECT_EQ(applyFreePlayKeys({"bireproj15to60", 0}, "]", conditions, at60).condition, "conv15");
    EXPECT_EQ(applyFreePlayKeys({"conv60", 0}, "]", conditions, at60).condition, "lag50");
    EXPECT_EQ(applyFreePlayKeys({"lag50", 0}, "[", conditions, at60).condition, "conv60");
}

}  // namespace
}  // namespace warplab::live
