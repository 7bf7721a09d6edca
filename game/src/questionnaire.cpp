#include "game/questionnaire.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "game/event_detail.h"

namespace warplab::game {
namespace {

using protocol::QuestionKind;

// The length of the UTF-8 sequence that `lead` starts, 0 for a byte no sequence starts with.
std::size_t sequenceLength(unsigned char lead) {
    if (lead < 0x80) return 1;
    if (lead >= 0xC2 && lead <= 0xDF) return 2;
    if (lead >= 0xE0 && lead <= 0xEF) return 3;
    if (lead >= 0xF0 && lead <= 0xF4) return 4;
    return 0;
}

// Whether text[at, at + length) is one well-formed UTF-8 character (no overlong forms, no
// surrogates, nothing above U+10FFFF: what nlohmann::json will write without throwing).
bool wellFormed(const std::string& text, std::size_t at, std::size_t length) {
    if (length == 0 || at + length > text.size()) return false;
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[at + i]); };
    for (std::size_t i = 1; i < length; ++i)
        if ((byte(i) & 0xC0) != 0x80) return false;
    if (length == 3 && byte(0) == 0xE0 && byte(1) < 0xA0) return false;  // overlong
    if (length == 3 && byte(0) == 0xED && byte(1) >= 0xA0) return false;  // surrogate
    if (length == 4 && byte(0) == 0xF0 && byte(1) < 0x90) return false;  // overlong
    if (length == 4 && byte(0) == 0xF4 && byte(1) >= 0x90) return false;  // above U+10FFFF
    return true;
}

bool inside(glm::dvec2 p, const glm::dvec4& box) {
    return p.x >= box.x && p.x < box.x + box.z && p.y >= box.y && p.y < box.y + box.w;
}

// The keys that answer a Likert question: the digits of its values from 1 to 9 (step() reads
// them). Empty when none of its values is a digit key.
std::pair<int, int> likertKeys(const protocol::Question& q) { return {std::max(1, q.min), std::min(9, q.max)}; }

// What answers a question, said under it: what step() takes, in the participant's words.
std::string answerHint(const protocol::Question& q) {
    switch (q.kind) {
        case QuestionKind::Likert: {
            const auto [low, high] = likertKeys(q);
            if (low > high) return "Click a box to answer";
            if (low == q.min && high == q.max)
                return "Click a box, or press " + std::to_string(low) + "\u2013" + std::to_string(high) + ", to answer";
            return "Click a box, or press " + std::to_string(low) + "\u2013" + std::to_string(high) +
                " for those values, to answer";
        }
        case QuestionKind::Choice:
            return q.options.size() <= 9 ? "Click an option, or press its number, to answer"
                                         : "Click an option, or press the number of one of the first nine, to answer";
        case QuestionKind::Text: return "Type your answer, then press Enter";
    }
    return "";
}

}  // namespace

std::string editedAnswer(std::string answer, const std::string& typed, std::size_t maxBytes) {
    for (std::size_t i = 0; i < typed.size();) {
        const auto lead = static_cast<unsigned char>(typed[i]);
        if (typed[i] == kTextBackspace) {
            // Back over continuation bytes to the character's first byte.
            while (!answer.empty() && (static_cast<unsigned char>(answer.back()) & 0xC0) == 0x80) answer.pop_back();
            if (!answer.empty()) answer.pop_back();
            ++i;
            continue;
        }
        const std::size_t length = sequenceLength(lead);
        if (!wellFormed(typed, i, length)) {
            ++i;  // a stray byte: skip it, and resynchronise on the next
            continue;
        }
        const bool control = length == 1 && (lead < 0x20 || lead == 0x7F);
        if (!control && answer.size() + length <= maxBytes) answer.append(typed, i, length);
        i += length;
    }
    return answer;
}

std::optional<AnswerResult> answerResult(const session::EventRecord& e,
                                         const std::vector<protocol::Question>& questions) {
    const bool legacy = e.type == "rating";
    if (!legacy && e.type != "answer") return std::nullopt;
    const EventDetail d(e.detailJson);
    AnswerResult r;
    r.block = e.phase;
    r.blockIndex = e.trial;
    r.condition = e.condition;
    r.time = e.eventTime;
    r.questionIndex = static_cast<int>(d.integer(legacy ? "statement_index" : "question_index", 0));
    r.questionId = d.text("question_id");
    r.prompt = d.text(legacy ? "statement" : "prompt");
    const std::int64_t missing = std::numeric_limits<std::int64_t>::min();
    if (const std::int64_t v = d.integer("value", missing); v != missing) r.value = static_cast<int>(v);
    r.text = d.text("text");
    r.answeredWith = d.text("answered_with");
    r.answerS = d.number("answer_s");
    const bool known = r.questionIndex >= 0 && static_cast<std::size_t>(r.questionIndex) < questions.size();
    const protocol::Question q = known ? questions[static_cast<std::size_t>(r.questionIndex)] : protocol::Question{};
    r.kind = legacy ? "likert" : d.text("kind", protocol::nameOf(q.kind));
    // The scale offered: a Likert question's ends, a choice's 1..n.
    if (q.kind == protocol::QuestionKind::Choice) {
        r.scaleMin = 1;
        r.scaleMax = static_cast<int>(q.options.size());
    } else {
        r.scaleMin = q.min;
        r.scaleMax = q.max;
    }
    return r;
}

Questionnaire::Questionnaire(std::vector<protocol::Question> questions, double refreshHz, const DisplaySize& display,
                             bool legacyLayout)
    : questions_(std::move(questions)),
      refreshHz_(refreshHz),
      display_(display),
      legacyLayout_(legacyLayout),
      next_(questions_.size()) {}

void Questionnaire::open(std::int64_t frame) {
    next_ = 0;
    shownSince_ = frame + 1;
    typed_.clear();
}

QuestionPrompt Questionnaire::prompt(glm::dvec2 cursor) const {
    const protocol::Question& q = questions_.at(next_);
    QuestionPrompt r;
    r.kind = q.kind;
    r.prompt = q.prompt;
    r.index = static_cast<int>(next_);
    r.count = static_cast<int>(questions_.size());
    const double w = display_.width, h = display_.height;
    switch (q.kind) {
        case QuestionKind::Likert: {
            r.min = q.min;
            r.max = q.max;
            r.minLabel = q.minLabel;
            r.maxLabel = q.maxLabel;
            // A row of square boxes across the middle, a tenth of the height each, half a box
            // apart; narrower where the row would not fit the width.
            const int n = q.max - q.min + 1;
            double size = h / 10.0;
            if (!legacyLayout_) size = std::min(size, 0.9 * w / (1.5 * n - 0.5));
            const double gap = size / 2.0;
            const double left = w * 0.5 - (n * size + (n - 1) * gap) * 0.5;
            for (int i = 0; i < n; ++i) {
                r.boxes.emplace_back(left + i * (size + gap), h * 0.5, size, size);
                r.boxLabels.push_back(std::to_string(q.min + i));
            }
            break;
        }
        case QuestionKind::Choice: {
            // A list down the lower half, one wide box per option, numbered as its digit key.
            const double n = static_cast<double>(q.options.size());
            const double pitch = std::min(h / 12.0, 0.45 * h / n);
            const double boxW = std::min(0.6 * w, 12.0 * pitch * 1.4);
            for (std::size_t i = 0; i < q.options.size(); ++i) {
                r.boxes.emplace_back(w * 0.5 - boxW * 0.5, h * 0.47 + static_cast<double>(i) * pitch, boxW,
                                     pitch * 0.8);
                r.boxLabels.push_back(q.options[i]);
            }
            break;
        }
        case QuestionKind::Text:
            r.boxes.emplace_back(w * 0.2, h * 0.5, w * 0.6, h / 12.0);
            r.typed = typed_;
            break;
    }
    r.hint = answerHint(q);
    if (q.kind != QuestionKind::Text)
        for (std::size_t i = 0; i < r.boxes.size(); ++i)
            if (inside(cursor, r.boxes[i])) r.highlighted = static_cast<int>(i);
    return r;
}

std::optional<Answer> Questionnaire::step(std::int64_t frame, QuestionPrompt& shown, std::uint32_t pressedKeys,
                                          bool click, const std::string& typed) {
    // A press during the settle time is dropped, not kept for later: what answers is a press
    // made after it, so a double click or a double tap answers once.
    if (static_cast<double>(frame - shownSince_) < kAnswerSettleS * refreshHz_) return std::nullopt;
    const protocol::Question& q = questions_.at(next_);
    Answer a;
    a.questionIndex = static_cast<int>(next_);
    a.answerS = static_cast<double>(frame - shownSince_) / refreshHz_;
    switch (q.kind) {
        case QuestionKind::Likert: {
            int keyed = 0;
            const auto [low, high] = likertKeys(q);
            for (int v = low; v <= high; ++v)
                if (pressedKeys & digitKey(v)) keyed = v;
            if (keyed != 0)
                a.value = keyed;
            else if (click && shown.highlighted >= 0)
                a.value = q.min + shown.highlighted, a.answeredWith = "mouse";
            break;
        }
        case QuestionKind::Choice: {
            int keyed = 0;
            for (int v = 1; v <= static_cast<int>(q.options.size()) && v <= 9; ++v)
                if (pressedKeys & digitKey(v)) keyed = v;
            if (keyed != 0)
                a.value = keyed;
            else if (click && shown.highlighted >= 0)
                a.value = shown.highlighted + 1, a.answeredWith = "mouse";
            if (a.value) a.text = q.options.at(static_cast<std::size_t>(*a.value - 1));
            break;
        }
        case QuestionKind::Text:
            typed_ = editedAnswer(typed_, typed, static_cast<std::size_t>(q.maxLength));
            shown.typed = typed_;
            if (pressedKeys & kKeyEnter) {
                a.text = typed_;
                a.answeredWith = "typed";
                typed_.clear();
                ++next_;
                shownSince_ = frame + 1;
                return a;
            }
            return std::nullopt;
    }
    if (!a.value) return std::nullopt;
    ++next_;
    shownSince_ = frame + 1;
    return a;
}

nlohmann::json Questionnaire::answerDetail(const Answer& a) const {
    const protocol::Question& q = questions_.at(static_cast<std::size_t>(a.questionIndex));
    nlohmann::json d{{"question_index", a.questionIndex}, {"question_id", q.id},
                     {"kind", protocol::nameOf(q.kind)},  {"prompt", q.prompt},
                     {"answered_with", a.answeredWith},   {"answer_s", a.answerS}};
    if (a.value) d["value"] = *a.value;
    if (q.kind != QuestionKind::Likert) d["text"] = a.text;
    return d;
}

}  // namespace warplab::game
