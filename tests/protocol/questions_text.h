// A question list spelt out field by field, so that a test comparing two lists shows which
// field differs instead of the bytes gtest prints for a struct it cannot print.
#pragma once

#include <string>
#include <vector>

#include "protocol/questions.h"

namespace warplab::protocol::test {

inline std::string questionsText(const std::vector<Question>& questions) {
    static const char* const kinds[] = {"likert", "choice", "text"};
    std::string text;
    for (const Question& q : questions) {
        text += "{id=" + q.id + " kind=" + kinds[static_cast<int>(q.kind)] + " prompt=" + q.prompt +
            " min=" + std::to_string(q.min) + " max=" + std::to_string(q.max) + " min_label=" + q.minLabel +
            " max_label=" + q.maxLabel + " options=[";
        for (const std::string& option : q.options) text += option + ";";
        text += "] max_length=" + std::to_string(q.maxLength) + "}\n";
    }
    return text;
}

}  // namespace warplab::protocol::test
