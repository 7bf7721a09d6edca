#include "json_fields.h"

#include <algorithm>
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
        // The JSON parser stops at a NUL as at the end of the text, so whatever follows one
        // (a second document, a binary tail) would be silently ignored.
        if (c == '\0')
            throw ProtocolError(prefix + "has a NUL byte at line " + std::to_string(line) +
                                ": a protocol is text, and nothing after it would be read");
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
        throw ProtocolError(prefix + "unreadable JSON" + where + ", " + reason + " (beyond what a double holds)");
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
    used_.insert(id);
    const std::string reason = conditions_.check(id, refreshHz);
    if (!reason.empty()) fail(where, "is \"" + id + "\": " + reason);
}

namespace {

// Condition names appear in CSV cells, file names and on a status line.
constexpr std::size_t kConditionNameLimit = 40;
bool conditionNameChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
        c == '.' || c == '+';
}
constexpr int kMaxDefinedConditions = 64;
const std::vector<const char*> kConditionKeys{"description", "render_hz", "lag_frames", "lag_ms",
                                              "fill",        "fill_hz",   "late_warp"};

// The parts in words, for a message about a preset.
std::string partsText(const condition::Condition& c) {
    std::string text = "render_hz " + condition::number(c.renderHz);
    text += c.lagFrames ? ", lag_frames " + std::to_string(*c.lagFrames) : ", lag_ms " + condition::number(c.lagMs);
    text += ", fill " + c.fill;
    if (c.fillHz) text += ", fill_hz " + condition::number(*c.fillHz);
    return text + ", late_warp " + condition::lateWarpName(c.lateWarp);
}

}  // namespace

std::vector<condition::Condition> Reader::conditions(const Json& document, int formatVersion, int since) {
    std::vector<condition::Condition> defined;
    const auto it = document.find("conditions");
    if (it == document.end()) return defined;
    if (formatVersion < since)
        fail("conditions",
             "is new in format_version " + std::to_string(since) + ", but this file is format_version " +
                 std::to_string(formatVersion));
    const Json* object = this->object(document, "", "conditions");
    if (object->size() > static_cast<std::size_t>(kMaxDefinedConditions))
        fail("conditions",
             "defines " + std::to_string(object->size()) + " conditions, more than a protocol may (" +
                 std::to_string(kMaxDefinedConditions) + ")");
    for (const auto& [name, value] : object->items()) {
        const std::string path = joinPath("conditions", name);
        if (name.empty() || name.size() > kConditionNameLimit ||
            !std::all_of(name.begin(), name.end(), conditionNameChar))
            fail(path,
                 "is not a condition name: 1 to " + std::to_string(kConditionNameLimit) +
                     " letters, digits and - _ . + (it appears in CSVs and file names)");
        if (!value.is_object())
            fail(path,
                 "must be an object of the condition's parts (render_hz, lag_frames or lag_ms, fill, fill_hz, "
                 "late_warp, description), got " +
                     describe(value));
        requireKnownKeys(value, path, kConditionKeys);
        condition::Condition c;
        c.name = name;
        // "" is the default written out (writeConditions leaves it out).
        if (value.contains("description"))
            c.description = line(value["description"], joinPath(path, "description"), /*allowEmpty=*/true);
        if (!value.contains("render_hz"))
            fail(joinPath(path, "render_hz"), "is required: conventional renders per second");
        number(&value, path, "render_hz", {0, true, kRefreshLimitHz, false}, c.renderHz);
        if (value.contains("lag_frames") && value.contains("lag_ms"))
            fail(joinPath(path, "lag_ms"), "and lag_frames are two ways to give the added latency; give one");
        if (value.contains("lag_frames")) {
            int frames = 0;
            integer(&value, path, "lag_frames", 0, condition::kMaxLagFrames, frames);
            c.lagFrames = frames;
        }
        number(&value, path, "lag_ms", {0, false, 1000, false}, c.lagMs);
        std::vector<const char*> fills;
        for (const auto& f : condition::fillSpellings()) fills.push_back(f.name);
        choice(&value, path, "fill", fills, c.fill);
        if (value.contains("fill_hz")) {
            double hz = 0;
            number(&value, path, "fill_hz", {0, true, kRefreshLimitHz, false}, hz);
            c.fillHz = hz;
        }
        std::vector<const char*> lateWarps;
        for (const auto w : condition::lateWarps()) lateWarps.push_back(condition::lateWarpName(w));
        std::string lateWarp = "none";
        choice(&value, path, "late_warp", lateWarps, lateWarp);
        c.lateWarp = *condition::lateWarpNamed(lateWarp);
        if (const condition::Condition* preset = condition::findPreset(name); preset && !preset->sameParts(c))
            fail(path,
                 "shadows the preset " + name + " with other parts (the preset's: " + partsText(*preset) +
                     "); give the condition another name");
        defined.push_back(c);
    }
    conditions_ = condition::ConditionTable(defined);
    return defined;
}

void Reader::requireConditionsRun(double refreshHz) const {
    for (const auto& c : conditions_.defined())
        if (const auto p = condition::problem(c, refreshHz)) {
            const std::string path = joinPath("conditions", c.name);
            fail(p->part.empty() ? path : joinPath(path, p->part), p->reason);
        }
}

void Reader::requireConditionsUsed() const {
    for (const auto& c : conditions_.defined())
        if (!used_.count(c.name))
            fail(joinPath("conditions", c.name),
                 "is defined but no field names it (a condition list or mode field); remove it or use it");
}

void writeConditions(Json& document, const std::vector<condition::Condition>& defined) {
    if (defined.empty()) return;
    Json& all = document["conditions"];
    for (const auto& c : defined) {
        Json& o = all[c.name];
        if (!c.description.empty()) o["description"] = c.description;
        o["render_hz"] = c.renderHz;
        if (c.lagFrames)
            o["lag_frames"] = *c.lagFrames;
        else
            o["lag_ms"] = c.lagMs;
        o["fill"] = c.fill;
        if (c.fillHz) o["fill_hz"] = *c.fillHz;
        o["late_warp"] = condition::lateWarpName(c.lateWarp);
    }
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
