// Questions a participant answers on screen after a block of play (docs/protocol.md,
// "Questions"): the click game asks its list after every match, the shooter after each block of
// its test. Three kinds, as post-block questionnaires in the field have them: a Likert scale with
// labelled ends, one choice of several, and a line of free text typed on screen. Both games'
// parsers read the list with the same reader (readQuestions), so a question means the same in
// every protocol.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "protocol/study_protocol.h"

namespace warplab::protocol {

enum class QuestionKind : std::uint8_t { Likert, Choice, Text };
template <>
struct EnumNames<QuestionKind> {
    static constexpr EnumName<QuestionKind> list[] = {
        {QuestionKind::Likert, "likert"}, {QuestionKind::Choice, "choice"}, {QuestionKind::Text, "text"}};
};

// Bounds no questionnaire needs to exceed (docs/protocol.md says why each exists).
inline constexpr int kScaleLimit = 100;  // either end of a Likert scale, in magnitude
inline constexpr int kMaxScalePoints = 11;  // 0-10 is the widest scale the field uses; its boxes fit a row
inline constexpr int kMaxChoiceOptions = 9;  // each answered by its digit key, 1-9
inline constexpr int kMaxQuestions = 20;  // a list asked after every block
inline constexpr int kMaxTextAnswerBytes = 200;  // a line typed on screen, UTF-8

struct Question {
    std::string id;  // names the question in answers.csv; unique within the list, [A-Za-z0-9_]
    QuestionKind kind = QuestionKind::Likert;
    std::string prompt;  // the statement or question, one line
    // Likert: the answers min..max, both included; the labels shown under the two ends ("" for
    // none: a scale may be shown as numbers alone).
    int min = 1, max = 7;
    std::string minLabel = "strongly disagree", maxLabel = "strongly agree";
    // Choice: the options, answered 1..n (by digit or by clicking one).
    std::vector<std::string> options;
    // Text: at most this many bytes are taken; Enter ends the answer.
    int maxLength = kMaxTextAnswerBytes;

    bool operator==(const Question& other) const;
    bool operator!=(const Question& other) const { return !(*this == other); }
};

// The click game's four statements of Yang et al. (seed 000 section 8), rated 1-7: its
// questions after every match unless a protocol lists its own.
std::vector<Question> yangRatingQuestions();

}  // namespace warplab::protocol
