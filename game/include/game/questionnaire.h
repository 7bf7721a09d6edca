// For the games' modules: the question screens every game shows after a block of play (the click
// game after each match, the shooter after each block of its test), one question at a time,
// from the protocol's list (protocol/questions.h). The games own when a list opens and what the
// answers' events are about; this owns the screens' layout, what answers, and the answer.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "game/game.h"
#include "game/results.h"
#include "protocol/questions.h"
#include "session/rows.h"

namespace warplab::game {

// How long a question is on screen before a press answers it. The games take presses, not
// held buttons, but a double click is two presses: its second one, at most a double-click
// interval (100-500 ms, the desktop defaults) after the first, lands on the question the first
// press brought up. Reading a question takes longer than that, so a press within this time is
// the previous answer's gesture, and is dropped rather than taken for an answer. Text typed
// within it is dropped too: the digit that answered the previous question also arrives as text.
inline constexpr double kAnswerSettleS = 0.5;

struct Answer {
    int questionIndex = 0;
    std::optional<int> value;  // Likert: the value; choice: the option's number from 1
    std::string text;  // choice: the option; text: what was typed
    const char* answeredWith = "key";  // "key", "mouse" or "typed"
    double answerS = 0.0;  // from the first frame that showed the question to the answering one
};

// Where typed input leaves an answer: `typed` appended to `answer`, each kTextBackspace taking
// back the last character; what is not valid UTF-8, control characters and whatever would take
// the answer past maxBytes are dropped, so an answer is always a line of valid UTF-8.
std::string editedAnswer(std::string answer, const std::string& typed, std::size_t maxBytes);

// An answer event as export's row: "answer" events, and the "rating" events of click files older
// than format 4 (a Likert answer without id or timing). The kind and the scale are the stored
// protocol's `questions`; the block's name and whether it is scored are the caller's to set.
// nullopt for any other event.
std::optional<AnswerResult> answerResult(const session::EventRecord& event,
                                         const std::vector<protocol::Question>& questions);

class Questionnaire {
public:
    // legacyLayout: the Likert row exactly as the click game's rating screens before format 4
    // laid it out (their recorded clicks replay on it), not shrunk to fit the display's width.
    Questionnaire(std::vector<protocol::Question> questions, double refreshHz, const DisplaySize& display,
                  bool legacyLayout);

    bool empty() const { return questions_.empty(); }
    const std::vector<protocol::Question>& questions() const { return questions_; }
    // The first question is shown from the frame after `frame`.
    void open(std::int64_t frame);
    // Every question of the list opened last has been answered.
    bool answeredAll() const { return next_ >= questions_.size(); }
    // The screen of the question up now, with the cursor at `cursor` (display pixels).
    QuestionPrompt prompt(glm::dvec2 cursor) const;
    // Frame `frame`'s input on the screen `shown` (prompt() of this frame): the answer it
    // gives, if it gives one; the next question is shown from the next frame. A text
    // question's screen is updated to show what this frame typed.
    std::optional<Answer> step(std::int64_t frame, QuestionPrompt& shown, std::uint32_t pressedKeys, bool click,
                               const std::string& typed);
    // An answer as an "answer" event's detail: question_index, question_id, kind, prompt, value
    // (Likert, choice), text (choice, text), answered_with, answer_s.
    nlohmann::json answerDetail(const Answer& answer) const;

private:
    std::vector<protocol::Question> questions_;
    double refreshHz_;
    DisplaySize display_;
    bool legacyLayout_;
    std::size_t next_ = 0;
    std::int64_t shownSince_ = 0;  // the first frame showing questions_[next_]
    std::string typed_;  // the text question's answer so far
};

}  // namespace warplab::game
