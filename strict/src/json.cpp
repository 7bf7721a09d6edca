#include "strict/json.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace warplab::strict {
namespace {

// nlohmann keeps the last of two equal keys without a word; a file with a field written twice
// is as ambiguous as one with a misspelt field, so the parse callback records the first repeat.
class DuplicateKeyFinder {
public:
    bool operator()(int /*depth*/, Json::parse_event_t event, Json& parsed) {
        using Event = Json::parse_event_t;
        switch (event) {
            case Event::object_start:
            case Event::array_start: frames_.push_back({childPath(), event == Event::array_start, 0, {}, {}}); break;
            case Event::object_end:
            case Event::array_end: frames_.pop_back(); break;
            case Event::key: {
                Frame& frame = frames_.back();
                frame.lastKey = parsed.get<std::string>();
                if (!frame.keys.insert(frame.lastKey).second && firstDuplicate_.empty())
                    firstDuplicate_ = joinPath(frame.path, frame.lastKey);
                break;
            }
            case Event::value:
                if (!frames_.empty() && frames_.back().isArray) ++frames_.back().nextIndex;
                break;
        }
        return true;
    }
    const std::string& firstDuplicate() const { return firstDuplicate_; }

private:
    struct Frame {
        std::string path;
        bool isArray;
        std::size_t nextIndex;
        std::set<std::string> keys;
        std::string lastKey;
    };

    // Path of a container that is just starting, from where its parent stands.
    std::string childPath() {
        if (frames_.empty()) return "";
        Frame& parent = frames_.back();
        if (parent.isArray) return elementPath(parent.path, parent.nextIndex++);
        return joinPath(parent.path, parent.lastKey);
    }

    std::vector<Frame> frames_;
    std::string firstDuplicate_;
};

// "[json.exception.name.id] message" -> "message": the id means nothing to a researcher.
std::string withoutLibraryPrefix(const std::string& what) {
    const auto end = what.find("] ");
    return what.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? what.substr(end + 2) : what;
}

const Json* find(const Json* parent, const char* key) {
    if (!parent) return nullptr;
    const auto it = parent->find(key);
    return it == parent->end() ? nullptr : &*it;
}

// "a", "b" or "c": how a message lists the allowed spellings.
std::string alternatives(const std::vector<const char*>& allowed) {
    std::string text;
    std::size_t i = 0;
    for (const char* value : allowed) {
        if (i > 0) text += i + 1 == allowed.size() ? " or " : ", ";
        text += std::string("\"") + value + "\"";
        ++i;
    }
    return text;
}

}  // namespace

std::string joinPath(const std::string& parent, const std::string& key) {
    if (parent.empty()) return key;
    return parent + (parent.back() == ')' ? " " : ".") + key;
}

std::string elementPath(const std::string& path, std::size_t index) { return path + "[" + std::to_string(index) + "]"; }

std::string describe(const Json& value) {
    std::string text = value.dump(-1, ' ', true, Json::error_handler_t::replace);
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    if (value.is_number() || value.is_null()) return text;
    return std::string(value.type_name()) + " " + text;
}

Reader::Reader(Source source) : source_(std::move(source)) {}

void Reader::fail(const std::string& path, const std::string& reason) const { source_.fail(path, reason); }

Json Reader::readObject() const { return parseObject(readFile(source_)); }

Json Reader::parseObject(const std::string& text) const {
    // Limits a file cannot drive past: the parser and the duplicate-key check recurse and keep
    // a path per level, so a few hundred kilobytes of '[' took a minute and gigabytes before,
    // and a hundred thousand levels overflowed the stack.
    if (text.size() > source_.maxBytes)
        fail("",
             "is " + std::to_string(text.size()) + " bytes, more than a " + source_.kind + " may be (" +
                 std::to_string(source_.maxBytes) + ")");
    int depth = 0, line = 1;
    bool inString = false, escaped = false;
    for (const char c : text) {
        if (c == '\n') ++line;
        // The JSON parser stops at a NUL as at the end of the text, so whatever follows one
        // (a second document, a binary tail) would be silently ignored.
        if (c == '\0')
            fail("",
                 "has a NUL byte at line " + std::to_string(line) + ": a " + source_.kind +
                     " is text, and nothing after it would be read");
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            if (++depth > kMaxNestingDepth)
                fail("",
                     "nested deeper than " + std::to_string(kMaxNestingDepth) + " levels at line " +
                         std::to_string(line));
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
    DuplicateKeyFinder finder;
    Json document;
    try {
        document = Json::parse(text, [&finder](int depth, Json::parse_event_t event, Json& parsed) {
            return finder(depth, event, parsed);
        });
    } catch (const Json::parse_error& e) {
        // what() is "[json.exception.parse_error.101] parse error at line L, column C: ...";
        // keep the position and the reason, drop the library's prefix.
        std::string reason = withoutLibraryPrefix(e.what());
        if (reason.rfind("parse error ", 0) == 0) reason.erase(0, 12);
        fail("", "malformed JSON " + reason);
    } catch (const Json::exception& e) {
        // Valid JSON the library cannot hold, such as 1e400 (out_of_range.406): the library
        // names the number but not where it is, so the line is found from the number's text.
        const std::string reason = withoutLibraryPrefix(e.what());
        const std::size_t open = reason.find('\''), close = reason.rfind('\'');
        std::string where;
        if (open != std::string::npos && close > open + 1) {
            const std::size_t at = text.find(reason.substr(open + 1, close - open - 1));
            if (at != std::string::npos)
                where = " at line " + std::to_string(1 + std::count(text.begin(), text.begin() + at, '\n'));
        }
        fail("", "unreadable JSON" + where + ", " + reason + " (beyond what a double holds)");
    }
    if (!finder.firstDuplicate().empty()) fail(finder.firstDuplicate(), "appears more than once");
    if (!document.is_object()) fail("", "the top level must be a JSON object, got " + describe(document));
    return document;
}

int Reader::formatVersion(const Json& document, int newest) const {
    const auto version = document.find("format_version");
    if (version == document.end()) fail("format_version", "is required but missing");
    if (!version->is_number_integer()) fail("format_version", "must be an integer, got " + describe(*version));
    if (version->is_number_unsigned() ? version->get<std::uint64_t>() > static_cast<std::uint64_t>(newest)
                                      : version->get<std::int64_t>() > newest)
        fail("format_version " + version->dump(),
             "is newer than this warplab supports (" + std::to_string(newest) + ")");
    if (version->get<std::int64_t>() < 1) fail("format_version", "must be at least 1, got " + version->dump());
    return version->get<int>();
}

void Reader::requireKnownKeys(const Json& object, const std::string& path,
                              const std::vector<const char*>& known) const {
    for (auto it = object.begin(); it != object.end(); ++it) {
        bool found = false;
        for (const char* key : known) found = found || it.key() == key;
        if (found) continue;
        std::string list;
        for (const char* key : known) list += std::string(list.empty() ? "" : ", ") + key;
        fail(joinPath(path, it.key()),
             "is not a known field (" + (path.empty() ? std::string("the top level") : path) + " may have " + list +
                 ")");
    }
}

const Json& Reader::required(const Json& parent, const std::string& path, const char* key) const {
    const Json* value = find(&parent, key);
    if (!value) fail(joinPath(path, key), "is required but missing");
    return *value;
}

const Json* Reader::object(const Json& parent, const std::string& path, const char* key) const {
    const Json* value = find(&parent, key);
    return value ? &objectAt(*value, joinPath(path, key)) : nullptr;
}

const Json* Reader::array(const Json* parent, const std::string& path, const char* key, const char* of,
                          bool allowEmpty) const {
    const Json* value = find(parent, key);
    return value ? &arrayAt(*value, joinPath(path, key), of, allowEmpty) : nullptr;
}

const Json& Reader::objectAt(const Json& value, const std::string& where) const {
    if (!value.is_object()) fail(where, "must be an object, got " + describe(value));
    return value;
}

const Json& Reader::arrayAt(const Json& value, const std::string& where, const char* of, bool allowEmpty) const {
    if (!value.is_array() || (value.empty() && !allowEmpty))
        fail(where,
             std::string(allowEmpty ? "must be an array of " : "must be a non-empty array of ") + of + ", got " +
                 describe(value));
    return value;
}

double Reader::numberAt(const Json& value, const std::string& where, NumberRange range) const {
    if (!value.is_number() || !std::isfinite(value.get<double>()) || !range.contains(value.get<double>()))
        fail(where, "must be a number " + range.text() + ", got " + describe(value));
    return value.get<double>();
}

std::int64_t Reader::integerAt(const Json& value, const std::string& where, std::int64_t low, std::int64_t high) const {
    // The parser holds a non-negative integer as unsigned, which may be beyond an int64.
    const bool inRange = value.is_number_unsigned()
        ? high >= 0 && value.get<std::uint64_t>() <= static_cast<std::uint64_t>(high) &&
            (low <= 0 || value.get<std::uint64_t>() >= static_cast<std::uint64_t>(low))
        : value.is_number_integer() && value.get<std::int64_t>() >= low && value.get<std::int64_t>() <= high;
    if (!inRange)
        fail(where,
             "must be an integer between " + std::to_string(low) + " and " + std::to_string(high) + ", got " +
                 describe(value));
    return value.get<std::int64_t>();
}

std::uint64_t Reader::unsignedAt(const Json& value, const std::string& where, std::uint64_t low,
                                 std::uint64_t high) const {
    if (!value.is_number_unsigned() || value.get<std::uint64_t>() < low || value.get<std::uint64_t>() > high)
        fail(where,
             "must be an integer between " + std::to_string(low) + " and " + std::to_string(high) + ", got " +
                 describe(value));
    return value.get<std::uint64_t>();
}

bool Reader::booleanAt(const Json& value, const std::string& where) const {
    if (!value.is_boolean()) fail(where, "must be true or false, got " + describe(value));
    return value.get<bool>();
}

std::string Reader::stringAt(const Json& value, const std::string& where) const {
    if (!value.is_string()) fail(where, "must be a string, got " + describe(value));
    return value.get<std::string>();
}

std::string Reader::line(const Json& value, const std::string& where, bool allowEmpty) const {
    bool ok = value.is_string();
    if (ok) {
        const auto& text = value.get_ref<const std::string&>();
        for (unsigned char c : text) ok = ok && c >= 0x20 && c != 0x7f;
        ok = ok && (allowEmpty || !text.empty()) && text.size() <= kLineLimit;
    }
    if (!ok)
        fail(where,
             std::string(allowEmpty ? "must be a single line" : "must be a non-empty single line") + " of at most " +
                 std::to_string(kLineLimit) + " bytes, got " + describe(value));
    return value.get<std::string>();
}

void Reader::number(const Json* parent, const std::string& path, const char* key, NumberRange range,
                    double& out) const {
    if (const Json* value = find(parent, key)) out = numberAt(*value, joinPath(path, key), range);
}

void Reader::integer(const Json* parent, const std::string& path, const char* key, int low, int high, int& out) const {
    if (const Json* value = find(parent, key))
        out = static_cast<int>(integerAt(*value, joinPath(path, key), low, high));
}

void Reader::boolean(const Json* parent, const std::string& path, const char* key, bool& out) const {
    if (const Json* value = find(parent, key)) out = booleanAt(*value, joinPath(path, key));
}

void Reader::string(const Json* parent, const std::string& path, const char* key, std::string& out) const {
    if (const Json* value = find(parent, key)) out = stringAt(*value, joinPath(path, key));
}

void Reader::choice(const Json* parent, const std::string& path, const char* key,
                    const std::vector<const char*>& allowed, std::string& out) const {
    const Json* value = find(parent, key);
    if (!value) return;
    if (value->is_string())
        for (const char* candidate : allowed)
            if (value->get<std::string>() == candidate) {
                out = candidate;
                return;
            }
    fail(joinPath(path, key), "must be " + alternatives(allowed) + ", got " + describe(*value));
}

void Reader::paragraph(const Json* parent, const std::string& path, const char* key, std::string& out) const {
    const Json* value = find(parent, key);
    if (!value) return;
    bool ok = value->is_string();
    if (ok) {
        const auto& text = value->get_ref<const std::string&>();
        for (unsigned char c : text) ok = ok && (c == '\n' || (c >= 0x20 && c != 0x7f));
        ok = ok && text.size() <= kParagraphLimit;
    }
    if (!ok)
        fail(joinPath(path, key),
             "must be a text of at most " + std::to_string(kParagraphLimit) +
                 " bytes without control characters other than line breaks, got " + describe(*value));
    out = value->get<std::string>();
}

void Reader::requireDistinct(const std::vector<std::string>& values,
                             const std::function<std::string(std::size_t)>& where) const {
    for (std::size_t i = 0; i < values.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (values[i] == values[j]) fail(where(i), "repeats \"" + values[i] + "\", already " + where(j));
}

}  // namespace warplab::strict
