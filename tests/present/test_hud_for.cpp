// What a question screen of the games becomes on the HUD: every kind's fields reach the HUD,
// the boxes scaled from display to frame pixels as the cursor is.
#include <gtest/gtest.h>

#include "game/game.h"
#include "present/frame_maker.h"

namespace warplab::present {
namespace {

game::ShownFrame asking(const game::QuestionPrompt& q) {
    game::ShownFrame shown;
    shown.blank = true;
    shown.question = q;
    return shown;
}

TEST(HudFor, ChoiceKeepsItsOptionsAndScalesItsBoxes) {
    game::QuestionPrompt q;
    q.kind = protocol::QuestionKind::Choice;
    q.prompt = "Which felt smoother?";
    q.boxLabels = {"the first", "the second", "no difference"};
    for (int i = 0; i < 3; ++i) q.boxes.emplace_back(100.0, 200.0 + 60.0 * i, 800.0, 50.0);
    q.highlighted = 2;
    const auto hud = hudFor(asking(q), 0.5, 0.25);
    ASSERT_TRUE(hud.question);
    const renderer::HudQuestion& r = *hud.question;
    EXPECT_EQ(r.kind, renderer::HudQuestion::Kind::Choice);
    EXPECT_EQ(r.prompt, "Which felt smoother?");
    EXPECT_EQ(r.boxLabels, q.boxLabels);
    ASSERT_EQ(r.boxes.size(), 3u);
    EXPECT_EQ(r.boxes[1], glm::vec4(50.0f, 65.0f, 400.0f, 12.5f));
    EXPECT_EQ(r.highlighted, 2);
    // End labels belong to a scale: a choice has none, whatever the prompt's defaults say.
    EXPECT_EQ(r.minLabel, "");
    EXPECT_EQ(r.maxLabel, "");
}

TEST(HudFor, TextCarriesWhatWasTypedIntoItsField) {
    game::QuestionPrompt q;
    q.kind = protocol::QuestionKind::Text;
    q.prompt = "Anything else?";
    q.boxes = {{200.0, 500.0, 1520.0, 80.0}};
    q.typed = "smooth, but laggy \xE2\x80\x94 ok";
    q.hint = "Type your answer, then press Enter";
    const auto hud = hudFor(asking(q), 1.0, 1.0);
    ASSERT_TRUE(hud.question);
    EXPECT_EQ(hud.question->kind, renderer::HudQuestion::Kind::Text);
    EXPECT_EQ(hud.question->typed, q.typed);
    ASSERT_EQ(hud.question->boxes.size(), 1u);
    EXPECT_TRUE(hud.question->boxLabels.empty());
    EXPECT_EQ(hud.question->hint, q.hint) << "the game's words on how to answer reach the screen";
}

TEST(HudFor, LikertShowsItsLabelsOrElseItsValues) {
    game::QuestionPrompt q;
    q.prompt = "I enjoyed this match";
    q.min = 0;
    q.max = 2;
    q.minLabel = "not at all";
    q.maxLabel = "very much";
    for (int i = 0; i < 3; ++i) q.boxes.emplace_back(100.0 * i, 500.0, 80.0, 80.0);
    auto hud = hudFor(asking(q), 1.0, 1.0);
    EXPECT_EQ(hud.question->kind, renderer::HudQuestion::Kind::Likert);
    EXPECT_EQ(hud.question->boxLabels, (std::vector<std::string>{"0", "1", "2"}));
    EXPECT_EQ(hud.question->minLabel, "not at all");
    EXPECT_EQ(hud.question->maxLabel, "very much");
    q.boxLabels = {"-1", "0", "+1"};
    hud = hudFor(asking(q), 1.0, 1.0);
    EXPECT_EQ(hud.question->boxLabels, q.boxLabels);
}

}  // namespace
}  // namespace warplab::present
