#include "protocol/questions_json.h"

#include <algorithm>
#include <cstddef>
#include <optional>

namespace warplab::protocol::fields {
namespace {

using Q = Question;
using K = Keys<Q>;

// An id names the question in every answer row (answers.csv) and becomes a column or a factor
// level in an analysis: short, and safe as an identifier in R, pandas and a spreadsheet.
constexpr std::size_t kIdLimit = 40;
bool idChar(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

// A question's key, and the one kind it belongs to (none: every question has it). A key of
// another kind is an error rather than ignored: a Likert "options" is a slip that would
// otherwise ask a different question than the one the researcher wrote.
struct Field {
    Key<Q> key;
    std::optional<QuestionKind> only;
};

Key<Q> required(const char* name, Key<Q> key) {
    auto read = key.read;
    key.read = [name, read](const Reader& r, const Json* o, const std::string& path, Q& q) {
        if (!o->contains(name)) r.fail(joinPath(path, name), "is required but missing");
        read(r, o, path, q);
    };
    return key;
}

void readId(const Reader& r, const Json* o, const std::string& path, Q& q) {
    const Json& value = o->at("id");
    const bool ok = value.is_string() && !value.get_ref<const std::string&>().empty() &&
        value.get_ref<const std::string&>().size() <= kIdLimit &&
        std::all_of(value.get_ref<const std::string&>().begin(), value.get_ref<const std::string&>().end(), idChar);
    if (!ok)
        r.fail(joinPath(path, "id"),
               "must be 1 to " + std::to_string(kIdLimit) +
                   " letters, digits and underscores (it names the answers in answers.csv), got " + describe(value));
    q.id = value.get<std::string>();
}

void readOptions(const Reader& r, const Json* o, const std::string& path, Q& q) {
    const Json* list = r.array(o, path, "options", "options", true);
    if (!list) return;
    const std::string where = joinPath(path, "options");
    if (list->size() < 2 || list->size() > static_cast<std::size_t>(kMaxChoiceOptions))
        r.fail(where,
               "must list 2 to " + std::to_string(kMaxChoiceOptions) +
                   " options (one is no choice; each is answered by its digit key), got " +
                   std::to_string(list->size()));
    std::vector<std::string> options;
    for (std::size_t i = 0; i < list->size(); ++i) options.push_back(r.line((*list)[i], elementPath(where, i)));
    r.requireDistinct(options, [&where](std::size_t i) { return elementPath(where, i); });
    q.options = std::move(options);
}

// A label under an end of the scale: one line, or "" for none.
template <class Get>
Key<Q> label(const char* name, Get get) {
    return K::make(name, get, [name, get](const Reader& r, const Json* o, const std::string& path, Q& q) {
        if (o->contains(name)) get(q) = r.line(o->at(name), joinPath(path, name), true);
    });
}

// Every key of a question once: the common ones, then each kind's, in the documented order.
const std::vector<Field>& fields() {
    static const std::vector<Field> list = [] {
        const auto line = [](const char* name, auto get) {
            return K::make(name, get, [name, get](const Reader& r, const Json* o, const std::string& path, Q& q) {
                get(q) = r.line(o->at(name), joinPath(path, name));
            });
        };
        return std::vector<Field>{
            {required("id", K::make("id", at(&Q::id), readId)), {}},
            {K::choice("kind", at(&Q::kind)), {}},
            {required("prompt", line("prompt", at(&Q::prompt))), {}},
            {K::integer("min", at(&Q::min), -kScaleLimit, kScaleLimit), QuestionKind::Likert},
            {K::integer("max", at(&Q::max), -kScaleLimit, kScaleLimit), QuestionKind::Likert},
            {label("min_label", at(&Q::minLabel)), QuestionKind::Likert},
            {label("max_label", at(&Q::maxLabel)), QuestionKind::Likert},
            {K::make("options", at(&Q::options), readOptions), QuestionKind::Choice},
            {K::integer("max_length", at(&Q::maxLength), 1, kMaxTextAnswerBytes), QuestionKind::Text},
        };
    }();
    return list;
}

Question readQuestion(const Reader& r, const Json& item, const std::string& where) {
    r.requireKnownKeys(item, where, questionKeyNames());
    Question q;
    // "kind" precedes every key that belongs to one kind, so q.kind is final when they are read.
    for (const Field& f : fields()) {
        if (f.only && *f.only != q.kind && item.contains(f.key.name))
            r.fail(joinPath(where, f.key.name),
                   std::string("is only for a ") + nameOf(*f.only) + " question; this one is " + nameOf(q.kind));
        f.key.read(r, &item, where, q);
    }
    // Relations between the question's keys, once each holds its final value.
    switch (q.kind) {
        case QuestionKind::Likert:
            if (q.min >= q.max)
                r.fail(joinPath(where, "min"),
                       "must be less than " + joinPath(where, "max") + " (" + std::to_string(q.max) + "), got " +
                           std::to_string(q.min));
            if (q.max - q.min + 1 > kMaxScalePoints)
                r.fail(joinPath(where, "max"),
                       "gives the scale " + std::to_string(q.max - q.min + 1) + " answers (" + std::to_string(q.min) +
                           " to " + std::to_string(q.max) + "), more than a scale may offer (" +
                           std::to_string(kMaxScalePoints) + ")");
            break;
        case QuestionKind::Choice:
            if (q.options.empty()) r.fail(joinPath(where, "options"), "is required for a choice question but missing");
            break;
        case QuestionKind::Text: break;
    }
    return q;
}

}  // namespace

std::vector<const char*> questionKeyNames() {
    std::vector<const char*> names;
    for (const Field& f : fields()) names.push_back(f.key.name);
    return names;
}

void readQuestions(const Reader& r, const Json* parent, const std::string& path, const char* key,
                   std::vector<Question>& out) {
    const Json* list = r.array(parent, path, key, "questions", true);
    if (!list) return;
    const std::string at = joinPath(path, key);
    if (list->size() > static_cast<std::size_t>(kMaxQuestions))
        r.fail(at,
               "lists " + std::to_string(list->size()) + " questions, more than a list asked after every block may (" +
                   std::to_string(kMaxQuestions) + ")");
    std::vector<Question> read;
    std::vector<std::string> ids;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const Json& item = (*list)[i];
        const std::string where = elementPath(at, i);
        if (!item.is_object()) r.fail(where, "must be an object, got " + describe(item));
        read.push_back(readQuestion(r, item, where));
        ids.push_back(read.back().id);
    }
    r.requireDistinct(ids, [&at](std::size_t i) { return elementPath(at, i) + ".id"; });
    out = std::move(read);
}

Json questionsJson(const std::vector<Question>& questions) {
    Json list = Json::array();
    for (const Question& q : questions) {
        Json item = Json::object();
        for (const Field& f : fields())
            if (!f.only || *f.only == q.kind) f.key.write(item, q);
        list.push_back(item);
    }
    return list;
}

}  // namespace warplab::protocol::fields
