#include "protocol/shooter_protocol.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <set>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

namespace warplab::protocol {
namespace {

// Ordered so that toJson keeps the documented field order and errors name the first culprit
// in file order rather than in alphabetical order.
using Json = nlohmann::ordered_json;

// Bounds that no study needs to exceed; they exist so a slip of the keyboard (an extra zero, a
// minus sign) is caught before a participant sits down, not to constrain designs.
constexpr int kLevelLimit = 120;           // v0 * 2^20: far beyond any hittable speed
constexpr int kTargetsLimit = 100000;
constexpr int kShotsLimit = 10000;
constexpr double kDurationLimitS = 86400;  // a day
constexpr double kSpeedLimit = 100;        // m/s at level 0
constexpr double kMousePerCountLimit = 0.1;
constexpr double kRadiusLimit = 3;         // well under half the 8 m high clear cross-section

// What a mode needs of the display, written arithmetically so protocol need not depend on
// game: the refresh must be a whole multiple of every rate the mode runs at, and a lag must
// be a whole number of frames. Mirrors game::ModeSchedule's checks, tolerance included, so a
// protocol that validates here never fails there.
struct ModeNeeds {
    std::string_view id;
    double rateHz;  // the fastest rate the mode runs at; every slower one divides it
    double lagMs;
};
constexpr ModeNeeds kModeNeeds[] = {
    {"conv15", 15, 0},      {"conv30", 30, 0},         {"conv60", 60, 0},
    {"conv120", 120, 0},    {"lag50", 60, 50},         {"lag100", 60, 100},
    {"lag200", 60, 200},    {"warp15to120", 120, 0},   {"bireproj15to60", 60, 0},
};
static_assert(std::size(kModeNeeds) == kKnownModes.size(), "every known mode needs its rates");

bool wholeMultiple(double value, double unit) {
    const double ratio = value / unit;
    const double whole = std::round(ratio);
    return whole >= 1 && std::abs(ratio - whole) <= 1e-9;
}

// Shortest text that reads back as the same double; integers without a decimal point.
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

std::string knownModeList() {
    std::string list;
    for (std::string_view id : kKnownModes) {
        if (!list.empty()) list += ", ";
        list += id;
    }
    return list;
}

// The offending value as the user wrote it, short and ASCII so a message stays one line.
std::string describe(const Json& value) {
    std::string text = value.dump(-1, ' ', true);
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    if (value.is_number() || value.is_null()) return text;
    return std::string(value.type_name()) + " " + text;
}

struct NumberRange {
    double low;
    bool lowOpen;
    double high;
    bool highOpen;

    bool contains(double v) const {
        return (lowOpen ? v > low : v >= low) && (highOpen ? v < high : v <= high);
    }
    std::string text() const {
        const std::string lo = formatNumber(low), hi = formatNumber(high);
        if (!lowOpen && !highOpen) return "between " + lo + " and " + hi;
        return (lowOpen ? "greater than " : "at least ") + lo +
               (highOpen ? " and less than " : " and at most ") + hi;
    }
};

// Parser state that knows the file name, so every message starts the same way.
class Reader {
public:
    explicit Reader(std::string source) : source_(std::move(source)) {}

    [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
        throw ProtocolError("protocol '" + source_ + "': " + path + " " + reason);
    }

    // Unknown keys are errors: a misspelt field would otherwise silently take its default.
    void requireKnownKeys(const Json& object, const std::string& path,
                          std::initializer_list<const char*> known) const {
        for (auto it = object.begin(); it != object.end(); ++it) {
            bool found = false;
            for (const char* key : known) found = found || it.key() == key;
            if (found) continue;
            std::string list;
            for (const char* key : known) list += std::string(list.empty() ? "" : ", ") + key;
            fail(joinPath(path, it.key()),
                 "is not a known field (" + (path.empty() ? std::string("the top level") : path) +
                     " may have " + list + ")");
        }
    }

    // A nested object; absent means every field in it takes its default.
    const Json* object(const Json& parent, const std::string& path, const char* key) const {
        const auto it = parent.find(key);
        if (it == parent.end()) return nullptr;
        if (!it->is_object()) fail(joinPath(path, key), "must be an object, got " + describe(*it));
        return &*it;
    }

    void number(const Json* parent, const std::string& path, const char* key, NumberRange range,
                double& out) const {
        const Json* value = find(parent, key);
        if (!value) return;
        const std::string where = joinPath(path, key);
        if (!value->is_number() || !std::isfinite(value->get<double>()) ||
            !range.contains(value->get<double>()))
            fail(where, "must be a number " + range.text() + ", got " + describe(*value));
        out = value->get<double>();
    }

    void integer(const Json* parent, const std::string& path, const char* key, int low, int high,
                 int& out) const {
        const Json* value = find(parent, key);
        if (!value) return;
        const std::string where = joinPath(path, key);
        const bool inRange =
            value->is_number_unsigned()
                ? value->get<std::uint64_t>() <= static_cast<std::uint64_t>(high) &&
                      static_cast<std::int64_t>(value->get<std::uint64_t>()) >= low
                : value->is_number_integer() && value->get<std::int64_t>() >= low &&
                      value->get<std::int64_t>() <= high;
        if (!inRange)
            fail(where, "must be an integer between " + std::to_string(low) + " and " +
                            std::to_string(high) + ", got " + describe(*value));
        out = static_cast<int>(value->get<std::int64_t>());
    }

    void boolean(const Json* parent, const std::string& path, const char* key, bool& out) const {
        const Json* value = find(parent, key);
        if (!value) return;
        if (!value->is_boolean())
            fail(joinPath(path, key), "must be true or false, got " + describe(*value));
        out = value->get<bool>();
    }

    void string(const Json* parent, const std::string& path, const char* key,
                std::string& out) const {
        const Json* value = find(parent, key);
        if (!value) return;
        if (!value->is_string())
            fail(joinPath(path, key), "must be a string, got " + describe(*value));
        out = value->get<std::string>();
    }

    std::string modeId(const Json& value, const std::string& where) const {
        if (value.is_string()) {
            const auto id = value.get<std::string>();
            for (std::string_view known : kKnownModes)
                if (id == known) return id;
        }
        fail(where, "must be a known mode id (" + knownModeList() + "), got " + describe(value));
    }

    void mode(const Json* parent, const std::string& path, const char* key,
              std::string& out) const {
        if (const Json* value = find(parent, key)) out = modeId(*value, joinPath(path, key));
    }

    void requireModeFits(const std::string& where, const std::string& id, double refreshHz) const {
        for (const ModeNeeds& needs : kModeNeeds) {
            if (needs.id != id) continue;
            if (!wholeMultiple(refreshHz, needs.rateHz))
                fail(where, "is \"" + id + "\", which needs display.refresh_hz to be a whole "
                                "multiple of " + formatNumber(needs.rateHz) + ", but it is " +
                                formatNumber(refreshHz));
            const double lagFrames = needs.lagMs * refreshHz / 1000.0;
            if (std::abs(lagFrames - std::round(lagFrames)) > 1e-9)
                fail(where, "is \"" + id + "\", whose " + formatNumber(needs.lagMs) +
                                " ms lag is not a whole number of frames at display.refresh_hz " +
                                formatNumber(refreshHz));
            return;
        }
    }

private:
    static const Json* find(const Json* parent, const char* key) {
        if (!parent) return nullptr;
        const auto it = parent->find(key);
        return it == parent->end() ? nullptr : &*it;
    }

    std::string source_;
};

// nlohmann keeps the last of two equal keys without a word; a protocol with a field written
// twice is as ambiguous as a misspelt one, so the parse callback records the first repeat.
class DuplicateKeyFinder {
public:
    bool operator()(int /*depth*/, Json::parse_event_t event, Json& parsed) {
        using Event = Json::parse_event_t;
        switch (event) {
            case Event::object_start:
            case Event::array_start:
                frames_.push_back({childPath(), event == Event::array_start, 0, {}, {}});
                break;
            case Event::object_end:
            case Event::array_end:
                frames_.pop_back();
                break;
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
        if (parent.isArray) return parent.path + "[" + std::to_string(parent.nextIndex++) + "]";
        return joinPath(parent.path, parent.lastKey);
    }

    std::vector<Frame> frames_;
    std::string firstDuplicate_;
};

// "[json.exception.name.id] message" -> "message": the id means nothing to a researcher.
std::string withoutLibraryPrefix(const std::string& what) {
    const auto end = what.find("] ");
    return what.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? what.substr(end + 2)
                                                                               : what;
}

Json parseJson(const std::string& text, const std::string& sourceName) {
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
        throw ProtocolError("protocol '" + sourceName + "': malformed JSON " + reason);
    } catch (const Json::exception& e) {
        // Valid JSON the library cannot hold, such as 1e400 (out_of_range.406).
        throw ProtocolError("protocol '" + sourceName + "': unreadable JSON, " +
                            withoutLibraryPrefix(e.what()));
    }
    if (!finder.firstDuplicate().empty())
        throw ProtocolError("protocol '" + sourceName + "': " + finder.firstDuplicate() +
                            " appears more than once");
    return document;
}

}  // namespace

ShooterProtocol parseShooterProtocol(const std::string& jsonText, const std::string& sourceName) {
    const Json document = parseJson(jsonText, sourceName);
    const Reader r(sourceName);
    if (!document.is_object())
        throw ProtocolError("protocol '" + sourceName + "': the top level must be a JSON object, got " +
                            describe(document));
    ShooterProtocol p;

    // The version comes first: a newer file may well have fields this build does not know,
    // and "too new" is the useful thing to say about it.
    const auto version = document.find("format_version");
    if (version == document.end()) r.fail("format_version", "is required but missing");
    if (!version->is_number_integer())
        r.fail("format_version", "must be an integer, got " + describe(*version));
    if (version->is_number_unsigned() ? version->get<std::uint64_t>() > kShooterFormatVersion
                                      : version->get<std::int64_t>() > kShooterFormatVersion)
        r.fail("format_version " + version->dump(),
               "is newer than this warplab supports (" + std::to_string(kShooterFormatVersion) + ")");
    if (version->get<std::int64_t>() < 1)
        r.fail("format_version", "must be at least 1, got " + version->dump());
    p.formatVersion = version->get<int>();

    r.requireKnownKeys(document, "",
                       {"format_version", "name", "description", "game", "display", "target",
                        "input", "acclimation", "training", "test"});
    for (const char* required : {"game", "name"})
        if (!document.contains(required)) r.fail(required, "is required but missing");
    p.game.clear();
    r.string(&document, "", "game", p.game);
    if (p.game != "shooter")
        r.fail("game", "must be \"shooter\" for a shooter protocol, got " + describe(document.at("game")));
    r.string(&document, "", "name", p.name);
    bool control = false;
    for (unsigned char c : p.name) control = control || c < 0x20 || c == 0x7f;
    if (p.name.empty() || p.name.size() > 200 || control)
        r.fail("name", "must be a non-empty single line of at most 200 bytes, got " +
                           describe(document.at("name")));
    r.string(&document, "", "description", p.description);

    if (const Json* display = r.object(document, "", "display")) {
        r.requireKnownKeys(*display, "display", {"refresh_hz", "vertical_fov_deg"});
        r.number(display, "display", "refresh_hz", {1, false, 1000, false}, p.refreshHz);
        r.number(display, "display", "vertical_fov_deg", {1, false, 179, false}, p.verticalFovDeg);
    }
    if (const Json* target = r.object(document, "", "target")) {
        r.requireKnownKeys(*target, "target", {"radius_m"});
        r.number(target, "target", "radius_m", {0, true, kRadiusLimit, true}, p.targetRadius);
    }
    if (const Json* input = r.object(document, "", "input")) {
        r.requireKnownKeys(*input, "input", {"mouse_radians_per_count"});
        r.number(input, "input", "mouse_radians_per_count", {0, true, kMousePerCountLimit, false},
                 p.mouseRadiansPerCount);
    }
    const NumberRange duration{0, true, kDurationLimitS, false};
    if (const Json* acclimation = r.object(document, "", "acclimation")) {
        r.requireKnownKeys(*acclimation, "acclimation", {"duration_s", "level", "mode"});
        r.number(acclimation, "acclimation", "duration_s", duration, p.acclimationS);
        r.integer(acclimation, "acclimation", "level", 0, kLevelLimit, p.acclimationLevel);
        r.mode(acclimation, "acclimation", "mode", p.acclimationMode);
    }
    StaircaseSettings& s = p.training;
    if (const Json* training = r.object(document, "", "training")) {
        r.requireKnownKeys(*training, "training",
                           {"base_speed_m_per_s", "start_level", "max_level", "shots_per_level_easy",
                            "shots_per_level_hard", "high_mode", "low_mode", "time_limit_s"});
        r.number(training, "training", "base_speed_m_per_s", {0, true, kSpeedLimit, false},
                 s.baseSpeed);
        r.integer(training, "training", "start_level", 0, kLevelLimit, s.startLevel);
        r.integer(training, "training", "max_level", 0, kLevelLimit, s.maxLevel);
        r.integer(training, "training", "shots_per_level_easy", 1, kShotsLimit, s.shotsPerLevelEasy);
        r.integer(training, "training", "shots_per_level_hard", 1, kShotsLimit, s.shotsPerLevelHard);
        r.mode(training, "training", "high_mode", s.highMode);
        r.mode(training, "training", "low_mode", s.lowMode);
        r.number(training, "training", "time_limit_s", duration, s.timeLimitS);
    }
    if (const Json* test = r.object(document, "", "test")) {
        r.requireKnownKeys(*test, "test",
                           {"conditions", "targets_per_condition", "interleave", "timeout_s",
                            "pause_s", "scoring", "supervisor_starts"});
        if (const auto conditions = test->find("conditions"); conditions != test->end()) {
            if (!conditions->is_array() || conditions->empty())
                r.fail("test.conditions", "must be a non-empty array of mode ids, got " +
                                              describe(*conditions));
            p.conditions.clear();
            for (std::size_t i = 0; i < conditions->size(); ++i) {
                const std::string where = "test.conditions[" + std::to_string(i) + "]";
                const std::string id = r.modeId((*conditions)[i], where);
                for (std::size_t j = 0; j < i; ++j)
                    if (p.conditions[j] == id)
                        r.fail(where, "repeats \"" + id + "\", already test.conditions[" +
                                          std::to_string(j) + "]");
                p.conditions.push_back(id);
            }
        }
        r.integer(test, "test", "targets_per_condition", 1, kTargetsLimit, p.targetsPerCondition);
        r.boolean(test, "test", "interleave", p.interleaveConditions);
        r.number(test, "test", "timeout_s", duration, p.timeoutS);
        r.number(test, "test", "pause_s", duration, p.pauseS);
        if (test->contains("scoring")) {
            r.string(test, "test", "scoring", p.scoring);
            if (p.scoring != "displayed" && p.scoring != "world")
                r.fail("test.scoring",
                       "must be \"displayed\" or \"world\", got " + describe(test->at("scoring")));
        }
        r.boolean(test, "test", "supervisor_starts", p.supervisorStartsTest);
    }

    // Relations between fields, checked once every field holds its final value.
    if (s.startLevel > s.maxLevel)
        r.fail("training.start_level", "must be at most training.max_level (" +
                                           std::to_string(s.maxLevel) + "), got " +
                                           std::to_string(s.startLevel));
    if (p.acclimationLevel > s.maxLevel)
        r.fail("acclimation.level", "must be at most training.max_level (" +
                                        std::to_string(s.maxLevel) + "), got " +
                                        std::to_string(p.acclimationLevel));
    if (s.shotsPerLevelHard < s.shotsPerLevelEasy)
        r.fail("training.shots_per_level_hard",
               "must be at least training.shots_per_level_easy (" +
                   std::to_string(s.shotsPerLevelEasy) + "), got " +
                   std::to_string(s.shotsPerLevelHard));
    if (s.highMode == s.lowMode)
        r.fail("training.low_mode", "must differ from training.high_mode, both are \"" +
                                        s.lowMode + "\"");
    r.requireModeFits("acclimation.mode", p.acclimationMode, p.refreshHz);
    r.requireModeFits("training.high_mode", s.highMode, p.refreshHz);
    r.requireModeFits("training.low_mode", s.lowMode, p.refreshHz);
    for (std::size_t i = 0; i < p.conditions.size(); ++i)
        r.requireModeFits("test.conditions[" + std::to_string(i) + "]", p.conditions[i],
                          p.refreshHz);
    return p;
}

ShooterProtocol loadShooterProtocol(const std::string& path) {
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (!std::filesystem::exists(status))
        throw ProtocolError("protocol '" + path + "': no such file");
    if (std::filesystem::is_directory(status))
        throw ProtocolError("protocol '" + path + "': is a directory, not a file");
    std::ifstream file(path, std::ios::binary);
    if (!file) throw ProtocolError("protocol '" + path + "': cannot be opened for reading");
    std::ostringstream text;
    text << file.rdbuf();
    if (file.bad()) throw ProtocolError("protocol '" + path + "': cannot be read");
    return parseShooterProtocol(text.str(), path);
}

std::string toJson(const ShooterProtocol& p) {
    const StaircaseSettings& s = p.training;
    Json document;
    document["format_version"] = p.formatVersion;
    document["name"] = p.name;
    document["description"] = p.description;
    document["game"] = p.game;
    document["display"]["refresh_hz"] = p.refreshHz;
    document["display"]["vertical_fov_deg"] = p.verticalFovDeg;
    document["target"]["radius_m"] = p.targetRadius;
    document["input"]["mouse_radians_per_count"] = p.mouseRadiansPerCount;
    document["acclimation"]["duration_s"] = p.acclimationS;
    document["acclimation"]["level"] = p.acclimationLevel;
    document["acclimation"]["mode"] = p.acclimationMode;
    Json& training = document["training"];
    training["base_speed_m_per_s"] = s.baseSpeed;
    training["start_level"] = s.startLevel;
    training["max_level"] = s.maxLevel;
    training["shots_per_level_easy"] = s.shotsPerLevelEasy;
    training["shots_per_level_hard"] = s.shotsPerLevelHard;
    training["high_mode"] = s.highMode;
    training["low_mode"] = s.lowMode;
    training["time_limit_s"] = s.timeLimitS;
    Json& test = document["test"];
    test["conditions"] = p.conditions;
    test["targets_per_condition"] = p.targetsPerCondition;
    test["interleave"] = p.interleaveConditions;
    test["timeout_s"] = p.timeoutS;
    test["pause_s"] = p.pauseS;
    test["scoring"] = p.scoring;
    test["supervisor_starts"] = p.supervisorStartsTest;
    // A string whose bytes are not UTF-8 is written with replacement characters rather than
    // throwing, so storing a session's copy of its protocol never fails.
    return document.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace warplab::protocol
