// For the games' modules: how the scripted bots (shooter_bot.h, click_bot.h) answer a question screen
// by the keyboard. Bots are scripted players for tests and pilots, not models of anyone: they
// give a fixed, documented answer (docs/protocol.md, "Questions").
#pragma once

#include <cstdint>
#include <string>

#include "game/game.h"

namespace warplab::game {

// What a bot types as its answer to a text question.
inline constexpr const char* kBotTextAnswer = "typed by a bot";

class BotQuestionReader {
public:
    // pixelsPerCount: how far the cursor moves on a question screen per mouse count.
    BotQuestionReader(double readS, double pixelsPerCount) : readS_(readS), pixelsPerCount_(pixelsPerCount) {}
    // Called with every frame the bot sees. True when the frame asks a question the bot has read
    // for readS: a question is new when its index changes or a question screen opens.
    bool ready(const ShownFrame& shown);
    // The answer to shown.question: `value` (a Likert value, or a choice's option number) as its
    // digit key, or where no digit gives it (a Likert scale reaching below 1 or above 9) by
    // moving the cursor onto its box and clicking; for a text question kBotTextAnswer typed in
    // one frame and Enter in the next.
    FrameInput answer(const ShownFrame& shown, int value);
    // The option a bot chooses in a choice question: the first for the first question, the
    // second for the second, and so on round the options.
    static int choiceFor(const QuestionPrompt& question);

private:
    double readS_, pixelsPerCount_;
    int index_ = -1;
    std::int64_t lastFrame_ = -2;
    double since_ = 0.0;
    bool typed_ = false;
};

// When a scripted bot presses Enter on a prompt (ShownFrame::promptsEnter: the supervisor's, an
// instruction screen's): once it has been up `afterS`. Another prompt straight after one is
// told by its text, so the key is let go and pressed anew.
class BotPromptReader {
public:
    bool pressesEnter(const ShownFrame& shown, double afterS) {
        if (!shown.promptsEnter) {
            since_ = -1.0;
            return false;
        }
        if (since_ < 0.0 || shown.phaseText != text_) since_ = shown.time;
        text_ = shown.phaseText;
        return shown.time - since_ >= afterS;
    }

private:
    double since_ = -1.0;
    std::string text_;  // the prompt's phase text, to tell one prompt from the next
};

}  // namespace warplab::game
