#include "json_fields.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <utility>

namespace warplab::protocol::detail {
namespace {

// nlohmann keeps the last of two equal keys without a word; a protocol with a field written
// twice is as ambiguous as a misspelt one, so the parse callback records the first repeat.
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

std::string formatNumber(double value) {
    char buffer[32];
    if (value == std::floor(value) && std::abs(value) < 1e15) {
        std::snprintf(buffer, sizeof buffer, "%.0f", value);
        return buffer;
    }
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
        if (std::strtod(buffer, nullptr) == value) break;
    }
    return buffer;
}

std::string joinPath(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
}

std::string elementPath(const std::string& path, std::size_t index) { return path + "[" + std::to_string(index) + "]"; }

std::string describe(const Json& value) {
    std::string text = value.dump(-1, ' ', true);
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    if (value.is_number() || value.is_null()) return text;
    return std::string(value.type_name()) + " " + text;
}

bool wholeMultiple(double value, double unit) {
    const double ratio = value / unit;
    const double whole = std::round(ratio);
    return whole >= 1 && std::abs(ratio - whole) <= 1e-9;
}

Json headerJson(int formatVersion, const std::string& name, const std::string& description, const std::string& game) {
    Json header;
    header[kHeaderKeys[0]] = formatVersion;
    header[kHeaderKeys[1]] = name;
    header[kHeaderKeys[2]] = description;
    header[kHeaderKeys[3]] = game;
    return header;
}

std::string canonicalText(const Json& document) {
    return document.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

bool NumberRange::contains(double v) const {
    return (lowOpen ? v > low : v >= low) && (highOpen ? v < high : v <= high);
}

std::string NumberRange::text() const {
    const std::string lo = formatNumber(low), hi = formatNumber(high);
    if (!lowOpen && !highOpen) return "between " + lo + " and " + hi;
    return (lowOpen ? "greater than " : "at least ") + lo + (highOpen ? " and less than " : " and at most ") + hi;
}

Reader::Reader(std::string source) : source_(std::move(source)) {}

Reader::Reader(std::string source, ModeCheck modes) : source_(std::move(source)), modes_(std::move(modes)) {
    if (!modes_) throw std::invalid_argument("protocol parser: the ModeCheck is empty; pass condition::checkMode");
}

void Reader::fail(const std::string& path, const std::string& reason) const {
    throw ProtocolError("protocol '" + source_ + "': " + path + " " + reason);
}

Json Reader::parseObject(const std::string& text) const {
    const std::string prefix = "protocol '" + source_ + "': ";
    // Limits a file cannot drive past: the parser and the duplicate-key check recurse and keep
    // a path per level, so a few hundred kilobytes of '[' took a minute and gigabytes before.
    // A real protocol is a few kilobytes and four levels deep.
    if (text.size() > kMaxProtocolBytes)
        throw ProtocolError(prefix + "is " + std::to_string(text.size()) + " bytes, more than a protocol may be (" +
                            std::to_string(kMaxProtocolBytes) + ")");
    int depth = 0, line = 1;
    bool inString = false, escaped = false;
    for (const char c : text) {
        if (c == '\n') ++line;
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
                throw ProtocolError(prefix + "nested deeper than " + std::to_string(kMaxNestingDepth) +
                                    " levels at line " + std::to_string(line));
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
        throw ProtocolError(prefix + "malformed JSON " + reason);
    } catch (const Json::exception& e) {
        // Valid JSON the library cannot hold, such as 1e400 (out_of_range.406).
        throw ProtocolError(prefix + "unreadable JSON, " + withoutLibraryPrefix(e.what()));
    }
    if (!finder.firstDuplicate().empty()) fail(finder.firstDuplicate(), "appears more than once");
    if (!document.is_object())
        throw ProtocolError(prefix + "the top level must be a JSON object, got " + describe(document));
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

std::string Reader::game(const Json& document) const {
    if (!document.contains("game")) fail("game", "is required but missing");
    std::string game;
    string(&document, "", "game", game);
    return game;
}

void Reader::requireGame(const Json& document, const std::string& expected) const {
    if (game(document) != expected)
        fail("game",
             "must be \"" + expected + "\" for a " + expected + " protocol, got " + describe(document.at("game")));
}

void Reader::nameAndDescription(const Json& document, std::string& name, std::string& description) const {
    if (!document.contains("name")) fail("name", "is required but missing");
    name = line(document.at("name"), "name");
    string(&document, "", "description", description);
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

const Json* Reader::object(const Json& parent, const std::string& path, const char* key) const {
    const auto it = parent.find(key);
    if (it == parent.end()) return nullptr;
    if (!it->is_object()) fail(joinPath(path, key), "must be an object, got " + describe(*it));
    return &*it;
}

const Json* Reader::array(const Json* parent, const std::string& path, const char* key, const char* of,
                          bool allowEmpty) const {
    const Json* value = find(parent, key);
    if (!value) return nullptr;
    if (!value->is_array() || (value->empty() && !allowEmpty))
        fail(joinPath(path, key),
             std::string(allowEmpty ? "must be an array of " : "must be a non-empty array of ") + of + ", got " +
                 describe(*value));
    return value;
}

void Reader::number(const Json* parent, const std::string& path, const char* key, NumberRange range,
                    double& out) const {
    const Json* value = find(parent, key);
    if (!value) return;
    if (!value->is_number() || !std::isfinite(value->get<double>()) || !range.contains(value->get<double>()))
        fail(joinPath(path, key), "must be a number " + range.text() + ", got " + describe(*value));
    out = value->get<double>();
}

void Reader::integer(const Json* parent, const std::string& path, const char* key, int low, int high, int& out) const {
    const Json* value = find(parent, key);
    if (!value) return;
    const bool inRange = value->is_number_unsigned()
        ? value->get<std::uint64_t>() <= static_cast<std::uint64_t>(high) &&
            static_cast<std::int64_t>(value->get<std::uint64_t>()) >= low
        : value->is_number_integer() && value->get<std::int64_t>() >= low && value->get<std::int64_t>() <= high;
    if (!inRange)
        fail(joinPath(path, key),
             "must be an integer between " + std::to_string(low) + " and " + std::to_string(high) + ", got " +
                 describe(*value));
    out = static_cast<int>(value->get<std::int64_t>());
}

void Reader::boolean(const Json* parent, const std::string& path, const char* key, bool& out) const {
    const Json* value = find(parent, key);
    if (!value) return;
    if (!value->is_boolean()) fail(joinPath(path, key), "must be true or false, got " + describe(*value));
    out = value->get<bool>();
}

void Reader::string(const Json* parent, const std::string& path, const char* key, std::string& out) const {
    const Json* value = find(parent, key);
    if (!value) return;
    if (!value->is_string()) fail(joinPath(path, key), "must be a string, got " + describe(*value));
    out = value->get<std::string>();
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

std::string Reader::line(const Json& value, const std::string& where) const {
    bool ok = value.is_string();
    if (ok) {
        const auto& text = value.get_ref<const std::string&>();
        for (unsigned char c : text) ok = ok && c >= 0x20 && c != 0x7f;
        ok = ok && !text.empty() && text.size() <= kLineLimit;
    }
    if (!ok)
        fail(where,
             "must be a non-empty single line of at most " + std::to_string(kLineLimit) + " bytes, got " +
                 describe(value));
    return value.get<std::string>();
}

void Reader::modeId(const Json* parent, const std::string& path, const char* key, std::string& out) const {
    const Json* value = find(parent, key);
    if (!value) return;
    if (!value->is_string()) fail(joinPath(path, key), "must be a mode id (a string), got " + describe(*value));
    out = value->get<std::string>();
}

void Reader::modeList(const Json* parent, const std::string& path, const char* key,
                      std::vector<std::string>& out) const {
    const Json* list = array(parent, path, key, "mode ids");
    if (!list) return;
    const std::string where = joinPath(path, key);
    std::vector<std::string> ids;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const Json& id = (*list)[i];
        if (!id.is_string()) fail(elementPath(where, i), "must be a mode id (a string), got " + describe(id));
        ids.push_back(id.get<std::string>());
    }
    requireDistinct(ids, [&where](std::size_t i) { return elementPath(where, i); });
    out = std::move(ids);
}

void Reader::requireMode(const std::string& where, const std::string& id, double refreshHz) const {
    const std::string reason = modes_(id, refreshHz);
    if (!reason.empty()) fail(where, "is \"" + id + "\": " + reason);
}

void Reader::requireModes(const std::string& path, const std::vector<std::string>& ids, double refreshHz) const {
    for (std::size_t i = 0; i < ids.size(); ++i) requireMode(elementPath(path, i), ids[i], refreshHz);
}

void Reader::requireDistinct(const std::vector<std::string>& values,
                             const std::function<std::string(std::size_t)>& where) const {
    for (std::size_t i = 0; i < values.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (values[i] == values[j]) fail(where(i), "repeats \"" + values[i] + "\", already " + where(j));
}

}  // namespace warplab::protocol::detail
