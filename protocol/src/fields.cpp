#include "protocol/fields.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace warplab::protocol::fields {
namespace {

[[noreturn]] void raiseProtocolError(const std::string& sentence) { throw ProtocolError(sentence); }

const Json* find(const Json* parent, const char* key) {
    if (!parent) return nullptr;
    const auto it = parent->find(key);
    return it == parent->end() ? nullptr : &*it;
}

}  // namespace

strict::Source protocolSource(const std::string& name) {
    return {"protocol", name, kMaxProtocolBytes, raiseProtocolError};
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

Reader::Reader(const std::string& source) : strict::Reader(protocolSource(source)) {}

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

void Reader::conditionId(const Json* parent, const std::string& path, const char* key, std::string& out) const {
    const Json* value = find(parent, key);
    if (!value) return;
    if (!value->is_string()) fail(joinPath(path, key), "must be a condition id (a string), got " + describe(*value));
    out = value->get<std::string>();
}

void Reader::conditionList(const Json* parent, const std::string& path, const char* key,
                           std::vector<std::string>& out) const {
    const Json* list = array(parent, path, key, "condition ids");
    if (!list) return;
    const std::string where = joinPath(path, key);
    std::vector<std::string> ids;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const Json& id = (*list)[i];
        if (!id.is_string()) fail(elementPath(where, i), "must be a condition id (a string), got " + describe(id));
        ids.push_back(id.get<std::string>());
    }
    requireDistinct(ids, [&where](std::size_t i) { return elementPath(where, i); });
    out = std::move(ids);
}

void Reader::requireCondition(const std::string& where, const std::string& id, double refreshHz) const {
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
const std::vector<const char*> kConditionKeys{"description", "render_hz",  "lag_frames", "lag_ms",
                                              "fill",        "fill_hz",    "late_warp",  "frame_time_jitter",
                                              "hitches",     "frame_times"};

// The parts in words, for a message about a preset.
std::string partsText(const condition::Condition& c) {
    std::string text = "render_hz " + condition::number(c.renderHz);
    text += c.lagFrames ? ", lag_frames " + std::to_string(*c.lagFrames) : ", lag_ms " + condition::number(c.lagMs);
    text += ", fill " + c.fill;
    if (c.fillHz) text += ", fill_hz " + condition::number(*c.fillHz);
    return text + ", late_warp " + condition::lateWarpName(c.lateWarp);
}

// The keys of "frame_time_jitter" and "hitches"; how far each may go on its own (what each
// may be against the render rate is condition::problem's).
const std::vector<const char*> kJitterKeys{"distribution", "sd_ms", "range_ms"};
const std::vector<const char*> kHitchKeys{"ms", "every_s", "rate_per_s"};
constexpr strict::NumberRange kPacingMs{0, true, 10000, false};

}  // namespace

void Reader::pacing(const Json& value, const std::string& path, int formatVersion, int since,
                    condition::Condition& c) const {
    for (const char* key : {"frame_time_jitter", "hitches", "frame_times"})
        if (value.contains(key) && formatVersion < since)
            fail(joinPath(path, key),
                 "is new in format_version " + std::to_string(since) + ", but this file is format_version " +
                     std::to_string(formatVersion));
    if (const Json* jitter = value.contains("frame_time_jitter") ? object(value, path, "frame_time_jitter") : nullptr) {
        const std::string where = joinPath(path, "frame_time_jitter");
        requireKnownKeys(*jitter, where, kJitterKeys);
        std::vector<const char*> shapes;
        for (const auto shape : condition::jitterShapes()) shapes.push_back(condition::jitterShapeName(shape));
        if (!jitter->contains("distribution"))
            fail(joinPath(where, "distribution"), "is required: \"normal\", \"lognormal\" or \"uniform\"");
        std::string shape = "normal";
        choice(jitter, where, "distribution", shapes, shape);
        c.jitter.shape = *condition::jitterShapeNamed(shape);
        const bool uniform = c.jitter.shape == condition::JitterShape::Uniform;
        const char* needed = uniform ? "range_ms" : "sd_ms";
        const char* other = uniform ? "sd_ms" : "range_ms";
        if (!jitter->contains(needed))
            fail(joinPath(where, needed), "is required for a " + shape + " jitter (milliseconds)");
        if (jitter->contains(other))
            fail(joinPath(where, other),
                 std::string("is not a parameter of a ") + shape + " jitter (give " + needed + ")");
        number(jitter, where, needed, kPacingMs, uniform ? c.jitter.rangeMs : c.jitter.sdMs);
    }
    if (const Json* hitches = value.contains("hitches") ? object(value, path, "hitches") : nullptr) {
        const std::string where = joinPath(path, "hitches");
        requireKnownKeys(*hitches, where, kHitchKeys);
        if (!hitches->contains("ms")) fail(joinPath(where, "ms"), "is required: how long each hitch stalls, in ms");
        number(hitches, where, "ms", kPacingMs, c.hitches.ms);
        if (hitches->contains("every_s") == hitches->contains("rate_per_s"))
            fail(where, "needs one of every_s (periodic) and rate_per_s (random), not both or neither");
        number(hitches, where, "every_s", {0, true, 3600, false}, c.hitches.everyS);
        number(hitches, where, "rate_per_s", {0, true, 1000, false}, c.hitches.ratePerS);
    }
    if (value.contains("frame_times")) frameTimes(value, path, c);
}

namespace {

void writePacing(Json& o, const condition::Condition& c) {
    if (c.jitter.shape != condition::JitterShape::None) {
        Json& j = o["frame_time_jitter"];
        j["distribution"] = condition::jitterShapeName(c.jitter.shape);
        if (c.jitter.shape == condition::JitterShape::Uniform)
            j["range_ms"] = c.jitter.rangeMs;
        else
            j["sd_ms"] = c.jitter.sdMs;
    }
    if (c.hitches.ms > 0.0) {
        Json& h = o["hitches"];
        h["ms"] = c.hitches.ms;
        if (c.hitches.everyS > 0.0) h["every_s"] = c.hitches.everyS;
        if (c.hitches.ratePerS > 0.0) h["rate_per_s"] = c.hitches.ratePerS;
    }
}

}  // namespace

std::vector<condition::Condition> Reader::conditions(const Json& document, int formatVersion, int since,
                                                     int pacingSince) {
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
                 "late_warp, frame_time_jitter, hitches, frame_times, description), got " +
                     describe(value));
        requireKnownKeys(value, path, kConditionKeys);
        condition::Condition c;
        c.name = name;
        // "" is the default written out (writeConditions leaves it out).
        if (value.contains("description"))
            c.description = line(value["description"], joinPath(path, "description"), /*allowEmpty=*/true);
        // A trace's render rate is its own (frame_times.mean_hz rescales it).
        if (value.contains("frame_times") && value.contains("render_hz"))
            fail(joinPath(path, "render_hz"),
                 "is given by frame_times (the trace's mean rate, or frame_times.mean_hz); leave render_hz out");
        if (!value.contains("render_hz") && !value.contains("frame_times"))
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
        pacing(value, path, formatVersion, pacingSince, c);
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
                 "is defined but no field names it (a condition list or condition field); remove it or use it");
}

void writeConditions(Json& document, const std::vector<condition::Condition>& defined) {
    if (defined.empty()) return;
    Json& all = document["conditions"];
    for (const auto& c : defined) {
        Json& o = all[c.name];
        if (!c.description.empty()) o["description"] = c.description;
        if (!c.frameTimes) o["render_hz"] = c.renderHz;
        if (c.lagFrames)
            o["lag_frames"] = *c.lagFrames;
        else
            o["lag_ms"] = c.lagMs;
        o["fill"] = c.fill;
        if (c.fillHz) o["fill_hz"] = *c.fillHz;
        o["late_warp"] = condition::lateWarpName(c.lateWarp);
        writePacing(o, c);
        writeFrameTimes(o, c);
    }
}

void Reader::requireConditions(const std::string& path, const std::vector<std::string>& ids, double refreshHz) const {
    for (std::size_t i = 0; i < ids.size(); ++i) requireCondition(elementPath(path, i), ids[i], refreshHz);
}

}  // namespace warplab::protocol::fields
