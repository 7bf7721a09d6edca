#include "game/question_bot.h"

namespace warplab::game {

bool BotQuestionReader::ready(const ShownFrame& shown) {
    if (!shown.question) {
        index_ = -1;
        return false;
    }
    if (shown.question->index != index_ || shown.frame != lastFrame_ + 1) {
        index_ = shown.question->index;
        since_ = shown.time;
        typed_ = false;
    }
    lastFrame_ = shown.frame;
    return shown.time - since_ >= readS_;
}

FrameInput BotQuestionReader::answer(const ShownFrame& shown, int value) {
    const QuestionPrompt& question = *shown.question;
    FrameInput input;
    if (question.kind == protocol::QuestionKind::Text) {
        if (!typed_)
            input.text = kBotTextAnswer;
        else
            input.keys = kKeyEnter;
        typed_ = true;
        return input;
    }
    if (value >= 1 && value <= 9) {
        input.keys = digitKey(value);
        return input;
    }
    const int box = question.kind == protocol::QuestionKind::Likert ? value - question.min : value - 1;
    if (box < 0 || box >= static_cast<int>(question.boxes.size())) return input;
    const glm::dvec4 b = question.boxes[static_cast<std::size_t>(box)];
    if (question.highlighted == box) {
        input.buttons = kButtonLeft;
        return input;
    }
    const glm::dvec2 centre(b.x + b.z * 0.5, b.y + b.w * 0.5);
    input.mouseDx = (centre.x - shown.cursor.x) / pixelsPerCount_;
    input.mouseDy = (centre.y - shown.cursor.y) / pixelsPerCount_;
    return input;
}

int BotQuestionReader::choiceFor(const QuestionPrompt& question) {
    const int n = static_cast<int>(question.boxes.size());
    return n > 0 ? 1 + question.index % n : 1;
}

}  // namespace warplab::game
