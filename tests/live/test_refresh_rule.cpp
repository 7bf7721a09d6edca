// How a live session takes the display's refresh (refresh_rule.h), without a window: what
// `warplab run` refuses and `warplab check` fails, and the words both use.
#include <gtest/gtest.h>

#include "refresh_rule.h"
#include "runner/session_runner.h"

namespace warplab::live {
namespace {

std::unique_ptr<game::Study> shipped(const std::string& name) {
    return runner::loadRunStudy(std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name + ".json", "");
}

TEST(RefreshRule, HalfAHertzIsTheSameRefreshAndNoneIsAMismatch) {
    EXPECT_FALSE(refreshMismatch(120.0, 120.0));
    EXPECT_FALSE(refreshMismatch(59.94, 60.0));
    EXPECT_TRUE(refreshMismatch(60.0, 120.0));
    EXPECT_TRUE(refreshMismatch(0.0, 120.0)) << "a display that reports no rate may run at any";
}

TEST(RefreshRule, AProtocolThatRefusesAWrongRefreshRefusesAnUnknownOneUnlessAllowed) {
    const auto thesis = shipped("shooter-thesis"), quick = shipped("shooter-quick");
    ASSERT_FALSE(thesis->warnsOnRefreshMismatch());
    ASSERT_TRUE(quick->warnsOnRefreshMismatch());
    EXPECT_FALSE(refusesRefresh(120.0, *thesis, false));
    EXPECT_TRUE(refusesRefresh(60.0, *thesis, false));
    EXPECT_TRUE(refusesRefresh(0.0, *thesis, false));
    EXPECT_FALSE(refusesRefresh(0.0, *thesis, true)) << "--allow-refresh-mismatch";
    EXPECT_FALSE(refusesRefresh(0.0, *quick, false)) << "the quick protocols warn";
    EXPECT_FALSE(refusesRefresh(60.0, *quick, false));
}

TEST(RefreshRule, TheSentenceSaysWhatTheDisplayReportsAndWhatToDo) {
    EXPECT_EQ(refreshText(60.0, 120.0, "p.json", true),
              "the display runs at 60 Hz but protocol 'p.json' needs 120 Hz; set the display to 120 Hz (or pass "
              "--allow-refresh-mismatch for a pilot)");
    EXPECT_EQ(refreshText(60.0, 120.0, "p.json", false),
              "the display runs at 60 Hz but protocol 'p.json' needs 120 Hz");
    EXPECT_EQ(refreshText(0.0, 120.0, "p.json", true),
              "the display reports no refresh rate, so it cannot be checked against the 120 Hz that protocol "
              "'p.json' needs; set the display to 120 Hz on a system that reports it (or pass "
              "--allow-refresh-mismatch for a pilot)");
}

}  // namespace
}  // namespace warplab::live
