#include "protocol/questions.h"

namespace warplab::protocol {

bool Question::operator==(const Question& o) const {
    return id == o.id && kind == o.kind && prompt == o.prompt && min == o.min && max == o.max &&
        minLabel == o.minLabel && maxLabel == o.maxLabel && options == o.options && maxLength == o.maxLength;
}

std::vector<Question> yangRatingQuestions() {
    auto likert = [](const char* id, const char* prompt) {
        Question q;
        q.id = id;
        q.prompt = prompt;
        return q;
    };
    return {likert("enjoyed", "I enjoyed playing this game"), likert("difficult", "This game was difficult to play"),
            likert("responsive", "This game was responsive to my input"), likert("smooth", "The animation was smooth")};
}

}  // namespace warplab::protocol
