#include "plan/study_plan.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>

#include <nlohmann/json.hpp>

#include "game/registry.h"
#include "physics/splitmix.h"
#include "plan/latin_square.h"
#include "protocol/study_protocol.h"
#include "strict/file.h"
#include "strict/json.h"

namespace warplab::plan {
namespace {

namespace fs = std::filesystem;
// Ordered, so study.json and a participant's protocol keep their keys in the order written.
using Json = nlohmann::ordered_json;

// Plan files are small: 10000 participants take about 3 MB.
constexpr std::size_t kMaxPlanBytes = 64u << 20;
using strict::formatNumber;
using strict::kLineLimit;  // bytes in a participant id, as in a protocol's names
// A mouse no one uses and a turn no hand makes; tiny positive values would turn into an
// infinite turn per count, so the lower bounds are real rather than "above 0".
constexpr double kMinCmPer360 = 0.1, kMaxCmPer360 = 10000;
constexpr double kMinMouseDpi = 1, kMaxMouseDpi = 100000;

std::string studyJsonPath(const std::string& planDir) { return (fs::path(planDir) / "study.json").string(); }

[[noreturn]] void raisePlanError(const std::string& sentence) { throw PlanError(sentence); }

// study.json of planDir, for the strict reader: every message starts with its path.
strict::Source planSource(const std::string& planDir) {
    return {"study plan", studyJsonPath(planDir), kMaxPlanBytes, raisePlanError};
}

std::string hex64(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

std::string fnv1a64(const std::string& bytes) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
    return hex64(h);
}

bool isLowerHex(const std::string& text, std::size_t digits) {
    return text.size() == digits &&
        std::all_of(text.begin(), text.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

bool isLine(const std::string& text) {
    return !text.empty() && text.size() <= kLineLimit &&
        std::none_of(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
}

std::string jsonString(const std::string& text) {
    return Json(text).dump(-1, ' ', false, Json::error_handler_t::replace);
}

template <class T, class Show>
std::string listText(const std::vector<T>& items, Show show) {
    std::string text = "[";
    for (std::size_t i = 0; i < items.size(); ++i) text += (i ? ", " : "") + show(items[i]);
    return text + "]";
}
std::string listText(const std::vector<std::string>& items) { return listText(items, jsonString); }
std::string listText(const std::vector<int>& items) {
    return listText(items, [](int v) { return std::to_string(v); });
}

std::string rowName(std::size_t index, const std::string& id) {
    std::string where = "participants[" + std::to_string(index) + "]";
    if (isLine(id)) where += " (" + jsonString(id) + ")";
    return where;
}

// ----------------------------------------------------------------------------- reading

ParticipantSettings readSettings(const strict::Reader& r, const Json& row, const std::string& path) {
    ParticipantSettings settings;
    const Json* value = r.object(row, path, "settings");
    if (!value) return settings;
    const std::string where = strict::joinPath(path, "settings");
    r.requireKnownKeys(*value, where, {"cm_per_360", "mouse_dpi", "invert_y"});
    if (value->contains("cm_per_360")) {
        double cm = 0;
        r.number(value, where, "cm_per_360", {kMinCmPer360, false, kMaxCmPer360, false}, cm);
        settings.cmPer360 = cm;
    }
    r.number(value, where, "mouse_dpi", {kMinMouseDpi, false, kMaxMouseDpi, false}, settings.mouseDpi);
    r.boolean(value, where, "invert_y", settings.invertY);
    return settings;
}

std::vector<std::string> readStrings(const strict::Reader& r, const Json& value, const std::string& where,
                                     const char* of) {
    std::vector<std::string> out;
    const Json& list = r.arrayAt(value, where, of, true);
    for (std::size_t i = 0; i < list.size(); ++i) out.push_back(r.stringAt(list[i], strict::elementPath(where, i)));
    return out;
}

ProtocolEntry readProtocolEntry(const strict::Reader& r, const Json& value, const std::string& path) {
    const Json& entry = r.objectAt(value, path);
    r.requireKnownKeys(entry, path, {"file", "name", "game", "hash", "conditions", "blocked"});
    ProtocolEntry out;
    out.file = r.stringAt(r.required(entry, path, "file"), path + ".file");
    out.name = r.stringAt(r.required(entry, path, "name"), path + ".name");
    out.game = r.stringAt(r.required(entry, path, "game"), path + ".game");
    out.hash = r.stringAt(r.required(entry, path, "hash"), path + ".hash");
    out.conditions = readStrings(r, r.required(entry, path, "conditions"), path + ".conditions", "condition names");
    out.blocked = r.booleanAt(r.required(entry, path, "blocked"), path + ".blocked");
    return out;
}

ParticipantPlan readParticipant(const strict::Reader& r, const Json& value, std::size_t index) {
    const Json& row = r.objectAt(value, strict::elementPath("participants", index));
    ParticipantPlan out;
    // The id first, so every later message can name the row by it.
    const auto id = row.find("id");
    if (id != row.end() && id->is_string()) out.id = id->get<std::string>();
    const std::string path = rowName(index, out.id);
    r.requireKnownKeys(row, path, {"id", "seed", "protocol_order", "condition_order", "settings"});
    out.id = r.stringAt(r.required(row, path, "id"), path + " id");
    out.seed = r.unsignedAt(r.required(row, path, "seed"), path + " seed", 1, kMaxParticipantSeed);
    const std::string orderPath = path + " protocol_order";
    const Json& order = r.arrayAt(r.required(row, path, "protocol_order"), orderPath, "protocol indices", true);
    for (std::size_t k = 0; k < order.size(); ++k)
        out.protocolOrder.push_back(static_cast<int>(
            r.integerAt(order[k], strict::elementPath(orderPath, k), 0, std::numeric_limits<int>::max())));
    const std::string conditionsPath = path + " condition_order";
    const Json& conditions =
        r.arrayAt(r.required(row, path, "condition_order"), conditionsPath, "condition orders", true);
    for (std::size_t p = 0; p < conditions.size(); ++p)
        out.conditionOrder.push_back(
            readStrings(r, conditions[p], strict::elementPath(conditionsPath, p), "condition names"));
    out.settings = readSettings(r, row, path);
    return out;
}

// study.json into the struct: its keys and their types. What the values must be together is
// validate's.
StudyPlan fromJson(const strict::Reader& r, const Json& document) {
    StudyPlan plan;
    // The version first: a newer plan may well have keys this build does not know.
    plan.formatVersion = r.formatVersion(document, kPlanFormatVersion);
    r.requireKnownKeys(document, "", {"format_version", "id", "created_at", "seed", "protocols", "participants"});
    plan.id = r.stringAt(r.required(document, "", "id"), "id");
    plan.createdAt = r.stringAt(r.required(document, "", "created_at"), "created_at");
    plan.seed = r.unsignedAt(r.required(document, "", "seed"), "seed", 0, UINT64_MAX);
    const Json& protocols = r.arrayAt(r.required(document, "", "protocols"), "protocols", "protocol entries", true);
    for (std::size_t p = 0; p < protocols.size(); ++p)
        plan.protocols.push_back(readProtocolEntry(r, protocols[p], strict::elementPath("protocols", p)));
    const Json& participants =
        r.arrayAt(r.required(document, "", "participants"), "participants", "participant rows", true);
    for (std::size_t i = 0; i < participants.size(); ++i)
        plan.participants.push_back(readParticipant(r, participants[i], i));
    return plan;
}

// ----------------------------------------------------------------------------- protocols

// A protocol file as the plan sees it: parsed by its game's loader, and its counterbalanced
// list and flag as the loader's canonical copy has them (so a list left to its default counts).
struct ParsedProtocol {
    std::string name, game;
    std::vector<std::string> conditions;
    bool blocked = false;
    std::string copy;  // what the plan folder keeps of it
};

// Whether a protocol plays a frame-time trace from a file, which it names relative to itself.
bool readsTraceFile(const Json& document) {
    const auto conditions = document.find("conditions");
    if (conditions == document.end() || !conditions->is_object()) return false;
    for (const auto& [name, c] : conditions->items()) {
        const auto trace = c.find("frame_times");
        if (trace != c.end() && trace->is_object() && !trace->contains("ms")) return true;
    }
    return false;
}

// The loader's ProtocolError, as a PlanError with the same sentence.
std::unique_ptr<game::Study> studyOf(const std::string& text, const std::string& sourceName) {
    try {
        return game::parseStudy(text, sourceName);
    } catch (const protocol::ProtocolError& e) {
        throw PlanError(e.what());
    }
}

ParsedProtocol parseProtocol(const std::string& text, const std::string& sourceName) {
    const std::unique_ptr<game::Study> study = studyOf(text, sourceName);
    ParsedProtocol out;
    out.name = study->name();
    out.game = study->game();
    const std::optional<game::CounterbalancedList> list = study->counterbalanced();
    if (!list)
        throw PlanError("protocol '" + sourceName + "': a study plan does not know which list of a " +
                        jsonString(out.game) + " protocol to counterbalance");
    out.conditions = list->conditions;
    out.blocked = list->blocked;
    // The copy lies in the plan folder, away from a trace file the protocol names beside itself:
    // such a protocol is kept as its canonical copy, the frame times inline (as a session keeps it).
    out.copy = readsTraceFile(Json::parse(text)) ? study->protocolJson() : text;
    return out;
}

// The protocol copy's path inside the plan folder; a file field that would leave the folder is
// refused, so a plan cannot point a session at any file on the machine.
fs::path protocolPath(const strict::Source& file, const std::string& planDir, const ProtocolEntry& entry,
                      const std::string& where) {
    const fs::path relative(entry.file);
    if (entry.file.empty() || relative.is_absolute() || relative.has_root_name() ||
        std::any_of(relative.begin(), relative.end(), [](const fs::path& part) { return part == ".."; }))
        file.fail(where,
                  jsonString(entry.file) + " must be a path inside the plan folder, such as protocols/NAME.json");
    return fs::path(planDir) / relative;
}

// The copy's bytes, checked against the plan's hash.
std::string protocolText(const strict::Source& file, const std::string& planDir, const ProtocolEntry& entry,
                         const std::string& where) {
    const fs::path path = protocolPath(file, planDir, entry, where);
    const strict::FileText copy = strict::readRegularFile(path.string(), protocol::kMaxProtocolBytes, "protocol");
    if (!copy.problem.empty())
        file.fail(where, jsonString(entry.file) + ": " + copy.problem + " (" + path.string() + ")");
    const std::string& text = copy.text;
    if (fnv1a64(text) != entry.hash)
        file.fail(where,
                  jsonString(entry.file) + " has changed since the plan was made (its hash is " + fnv1a64(text) +
                      ", the plan's " + entry.hash + ")");
    return text;
}

// ----------------------------------------------------------------------------- checks

void requirePermutation(const strict::Source& file, const std::string& where, const std::vector<std::string>& order,
                        const std::vector<std::string>& conditions, const std::string& of) {
    std::set<std::string> seen;
    for (std::size_t k = 0; k < order.size(); ++k) {
        if (std::find(conditions.begin(), conditions.end(), order[k]) == conditions.end())
            file.fail(where + "[" + std::to_string(k) + "]",
                      "is " + jsonString(order[k]) + ", not a condition of " + of + " (" + listText(conditions) + ")");
        if (!seen.insert(order[k]).second)
            file.fail(
                where + "[" + std::to_string(k) + "]",
                "is " + jsonString(order[k]) + " again: " + where + " must name each condition of " + of + " once");
    }
    if (order.size() != conditions.size())
        file.fail(where,
                  "is " + listText(order) + ", not an order of the " + std::to_string(conditions.size()) +
                      " conditions of " + of + " (" + listText(conditions) + ")");
}

void requireSettings(const strict::Source& file, const std::string& where, const ParticipantSettings& s) {
    auto range = [&](const char* key, double v, double low, double high) {
        if (!(v >= low && v <= high))
            file.fail(where + " settings." + key,
                      "must be a number between " + formatNumber(low) + " and " + formatNumber(high) + ", got " +
                          formatNumber(v));
    };
    if (s.cmPer360) range("cm_per_360", *s.cmPer360, kMinCmPer360, kMaxCmPer360);
    range("mouse_dpi", s.mouseDpi, kMinMouseDpi, kMaxMouseDpi);
}

// Everything a plan must be, against itself and the protocol copies in planDir.
void validate(const strict::Source& file, const std::string& planDir, const StudyPlan& plan) {
    if (!isLowerHex(plan.id, 32)) file.fail("id", "must be 32 lower-case hex digits, got " + jsonString(plan.id));
    if (!isLine(plan.createdAt)) file.fail("created_at", "must be one line of text, got " + jsonString(plan.createdAt));
    if (plan.protocols.empty()) file.fail("protocols", "is empty: a plan runs at least one protocol");
    std::set<std::string> files;
    for (std::size_t p = 0; p < plan.protocols.size(); ++p) {
        const ProtocolEntry& entry = plan.protocols[p];
        const std::string where = "protocols[" + std::to_string(p) + "]";
        if (!files.insert(fs::path(entry.file).lexically_normal().string()).second)
            file.fail(where + ".file", jsonString(entry.file) + " is listed twice");
        if (!isLowerHex(entry.hash, 16))
            file.fail(where + ".hash", "must be 16 lower-case hex digits, got " + jsonString(entry.hash));
        const std::string text = protocolText(file, planDir, entry, where + ".file");
        const ParsedProtocol parsed = parseProtocol(text, protocolPath(file, planDir, entry, where).string());
        if (entry.game != parsed.game)
            file.fail(where + ".game",
                      "is " + jsonString(entry.game) + ", but the file is for " + jsonString(parsed.game));
        if (entry.name != parsed.name)
            file.fail(where + ".name",
                      "is " + jsonString(entry.name) + ", but the file's name is " + jsonString(parsed.name));
        if (entry.conditions != parsed.conditions)
            file.fail(where + ".conditions",
                      "is " + listText(entry.conditions) + ", but the file lists " + listText(parsed.conditions));
        if (entry.blocked != parsed.blocked)
            file.fail(where + ".blocked",
                      std::string("is ") + (entry.blocked ? "true" : "false") + ", but the file " +
                          (parsed.blocked ? "plays the list in order" : "shuffles the list"));
    }

    if (plan.participants.empty()) file.fail("participants", "is empty: a plan has at least one participant");
    if (plan.participants.size() > static_cast<std::size_t>(kMaxParticipants))
        file.fail(
            "participants",
            "has " + std::to_string(plan.participants.size()) + " rows, more than " + std::to_string(kMaxParticipants));
    std::map<std::string, std::size_t> ids;
    std::map<std::uint64_t, std::size_t> seeds;
    const std::size_t protocolCount = plan.protocols.size();
    for (std::size_t i = 0; i < plan.participants.size(); ++i) {
        const ParticipantPlan& row = plan.participants[i];
        const std::string where = rowName(i, row.id);
        if (!isLine(row.id))
            file.fail(where + " id",
                      "must be 1 to " + std::to_string(kLineLimit) + " bytes on one line, got " + jsonString(row.id));
        if (const auto [it, fresh] = ids.emplace(row.id, i); !fresh)
            file.fail(where + " id",
                      jsonString(row.id) + " is also the id of participants[" + std::to_string(it->second) + "]");
        if (row.seed == 0 || row.seed > kMaxParticipantSeed)
            file.fail(where + " seed",
                      "must be an integer between 1 and " + std::to_string(kMaxParticipantSeed) + ", got " +
                          std::to_string(row.seed));
        if (const auto [it, fresh] = seeds.emplace(row.seed, i); !fresh)
            file.fail(where + " seed",
                      std::to_string(row.seed) + " is also the seed of " +
                          rowName(it->second, plan.participants[it->second].id));

        std::vector<int> sorted = row.protocolOrder;
        std::sort(sorted.begin(), sorted.end());
        bool permutation = sorted.size() == protocolCount;
        for (std::size_t k = 0; permutation && k < sorted.size(); ++k) permutation = sorted[k] == static_cast<int>(k);
        if (!permutation)
            file.fail(where + " protocol_order",
                      "is " + listText(row.protocolOrder) + ", not an order of the " + std::to_string(protocolCount) +
                          " protocols (each of 0.." + std::to_string(protocolCount - 1) + " once)");
        if (row.conditionOrder.size() != protocolCount)
            file.fail(where + " condition_order",
                      "must hold one list for each of the " + std::to_string(protocolCount) + " protocols, not " +
                          std::to_string(row.conditionOrder.size()));
        for (std::size_t p = 0; p < protocolCount; ++p)
            requirePermutation(file, where + " condition_order[" + std::to_string(p) + "]", row.conditionOrder[p],
                               plan.protocols[p].conditions, "protocols[" + std::to_string(p) + "]");
        requireSettings(file, where, row.settings);
    }
}

// ----------------------------------------------------------------------------- writing

// One line: ", " between elements, ": " after keys.
std::string inlineJson(const Json& value) {
    if (value.is_array()) {
        std::string text = "[";
        for (std::size_t i = 0; i < value.size(); ++i) text += (i ? ", " : "") + inlineJson(value[i]);
        return text + "]";
    }
    if (value.is_object()) {
        std::string text = "{";
        bool first = true;
        for (const auto& item : value.items()) {
            text += (first ? "" : ", ") + jsonString(item.key()) + ": " + inlineJson(item.value());
            first = false;
        }
        return text + "}";
    }
    if (value.is_number_float()) return formatNumber(value.get<double>());
    return value.dump(-1, ' ', false, Json::error_handler_t::replace);
}

// An object on its lines: each key on its own, two spaces deeper than `indent`, values inline.
std::string objectLines(const Json& object, const std::string& indent) {
    std::string text = "{\n";
    std::size_t k = 0;
    for (const auto& item : object.items())
        text += indent + "  " + jsonString(item.key()) + ": " + inlineJson(item.value()) +
            (++k < object.size() ? ",\n" : "\n");
    return text + indent + "}";
}

// The order of study.json's keys is the order of docs/study-plan.md's tables.
std::string planText(const StudyPlan& plan) {
    Json header;
    header["format_version"] = plan.formatVersion;
    header["id"] = plan.id;
    header["created_at"] = plan.createdAt;
    header["seed"] = plan.seed;
    std::string text = "{\n";
    for (const auto& item : header.items())
        text += "  " + jsonString(item.key()) + ": " + inlineJson(item.value()) + ",\n";
    text += "  \"protocols\": [\n";
    for (std::size_t p = 0; p < plan.protocols.size(); ++p) {
        const ProtocolEntry& e = plan.protocols[p];
        Json entry;
        entry["file"] = e.file;
        entry["name"] = e.name;
        entry["game"] = e.game;
        entry["hash"] = e.hash;
        entry["conditions"] = e.conditions;
        entry["blocked"] = e.blocked;
        text += "    " + objectLines(entry, "    ") + (p + 1 < plan.protocols.size() ? ",\n" : "\n");
    }
    text += "  ],\n  \"participants\": [\n";
    for (std::size_t i = 0; i < plan.participants.size(); ++i) {
        const ParticipantPlan& row = plan.participants[i];
        Json entry;
        entry["id"] = row.id;
        entry["seed"] = row.seed;
        entry["protocol_order"] = row.protocolOrder;
        entry["condition_order"] = row.conditionOrder;
        Json settings = Json::object();
        if (row.settings.cmPer360) settings["cm_per_360"] = *row.settings.cmPer360;
        settings["mouse_dpi"] = row.settings.mouseDpi;
        settings["invert_y"] = row.settings.invertY;
        entry["settings"] = settings;
        text += "    " + objectLines(entry, "    ") + (i + 1 < plan.participants.size() ? ",\n" : "\n");
    }
    return text + "  ]\n}\n";
}

void writeWhole(const fs::path& path, const std::string& bytes, const std::string& what) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw PlanError(what + " '" + path.string() + "' could not be written: " + std::strerror(errno));
}

std::string randomId() {
    std::random_device device;
    std::string id;
    for (int i = 0; i < 2; ++i)
        id += hex64((static_cast<std::uint64_t>(device()) << 32) ^ static_cast<std::uint64_t>(device()));
    return id;
}

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

std::string defaultId(int index, int count) {
    const int width = static_cast<int>(std::to_string(count).size());
    std::string number = std::to_string(index + 1);
    // Two digits at least: P01..P09 sort before P10 in every file browser.
    return "P" + std::string(static_cast<std::size_t>(std::max(width, 2)) - number.size(), '0') + number;
}

// Rows from.size() .. from.size() + count - 1 of the plan, as makePlan makes them: the seeds
// continue the plan's stream and the orders the squares' rows, so that a plan made for N + M
// participants and one made for N and then grown by M are the same.
void appendParticipants(StudyPlan& plan, int count, const std::vector<std::string>& ids, const std::string& prefix) {
    const std::size_t first = plan.participants.size(), total = first + static_cast<std::size_t>(count);
    if (total > static_cast<std::size_t>(kMaxParticipants))
        throw PlanError(prefix + "the number of participants must be at most " + std::to_string(kMaxParticipants) +
                        ", and " + std::to_string(first) + " + " + std::to_string(count) + " is " +
                        std::to_string(total));
    // Seeds: the top 53 bits of a splitmix64 stream from the plan's seed (kMaxParticipantSeed),
    // skipping 0 and any repeat. The rows there are draw theirs again, to reach the stream's
    // place; a seed edited into a row is skipped too.
    std::uint64_t state = plan.seed;
    std::set<std::uint64_t> seeds;
    for (const ParticipantPlan& row : plan.participants) seeds.insert(row.seed);
    std::set<std::uint64_t> drawn;
    const auto draw = [&] {
        std::uint64_t seed = 0;
        do seed = physics::splitmix64(state) >> 11;
        while (seed == 0 || !drawn.insert(seed).second);
        return seed;
    };
    for (std::size_t i = 0; i < first; ++i) draw();
    const auto protocolSquare = balancedLatinSquare(static_cast<int>(plan.protocols.size()));
    std::vector<std::vector<std::vector<int>>> conditionSquares;
    for (const ProtocolEntry& entry : plan.protocols)
        conditionSquares.push_back(balancedLatinSquare(static_cast<int>(entry.conditions.size())));
    for (std::size_t i = first; i < total; ++i) {
        ParticipantPlan row;
        row.id = ids.empty() ? defaultId(static_cast<int>(i), static_cast<int>(total)) : ids[i - first];
        do row.seed = draw();
        while (!seeds.insert(row.seed).second);
        row.protocolOrder = protocolSquare[i % protocolSquare.size()];
        // Protocol p takes row i + p of its square: with two protocols of the same length the
        // participant's two condition orders then differ, rather than repeat each other.
        for (std::size_t p = 0; p < plan.protocols.size(); ++p) {
            const auto& square = conditionSquares[p];
            std::vector<std::string> order;
            for (const int c : square[(i + p) % square.size()])
                order.push_back(plan.protocols[p].conditions[static_cast<std::size_t>(c)]);
            row.conditionOrder.push_back(std::move(order));
        }
        plan.participants.push_back(std::move(row));
    }
    // Ids are checked as readPlan checks them, before anything is written.
    for (std::size_t i = first; i < plan.participants.size(); ++i) {
        const std::string& id = plan.participants[i].id;
        if (!isLine(id))
            throw PlanError(prefix + "participant id " + std::to_string(i + 1) + " must be 1 to " +
                            std::to_string(kLineLimit) + " bytes on one line, got " + jsonString(id));
        for (std::size_t j = 0; j < i; ++j)
            if (plan.participants[j].id == id)
                throw PlanError(prefix + "participant id " + jsonString(id) +
                                (j < first ? " is already in the plan" : " is given twice") +
                                (ids.empty() ? "; name the new participants with --ids" : ""));
    }
}

}  // namespace

StudyPlan makePlan(const std::string& planDir, const std::vector<std::string>& protocolPaths, int participants,
                   const std::vector<std::string>& ids, std::uint64_t seed) {
    const std::string prefix = "study plan '" + planDir + "': ";
    if (participants < 1 || participants > kMaxParticipants)
        throw PlanError(prefix + "the number of participants must be between 1 and " +
                        std::to_string(kMaxParticipants) + ", got " + std::to_string(participants));
    if (!ids.empty() && ids.size() != static_cast<std::size_t>(participants))
        throw PlanError(prefix + std::to_string(ids.size()) + " participant ids given for " +
                        std::to_string(participants) + " participants");
    if (protocolPaths.empty()) throw PlanError(prefix + "a plan runs at least one protocol, none given");
    if (fs::exists(studyJsonPath(planDir)))
        throw PlanError(prefix + "already holds a study plan (" + studyJsonPath(planDir) +
                        "); a plan is made once, in a folder of its own");

    StudyPlan plan;
    plan.id = randomId();
    plan.createdAt = utcNow();
    plan.seed = seed;

    // Every protocol is read and parsed before anything is copied, so a refusal leaves no
    // half-made plan folder behind.
    std::vector<std::string> texts;
    for (const std::string& path : protocolPaths) {
        std::string text;
        try {
            text = protocol::readProtocolFile(path);
        } catch (const protocol::ProtocolError& e) {
            throw PlanError(e.what());
        }
        const ParsedProtocol parsed = parseProtocol(text, path);
        ProtocolEntry entry;
        entry.file = (fs::path("protocols") / fs::path(path).filename()).generic_string();
        for (std::size_t p = 0; p < plan.protocols.size(); ++p)
            if (plan.protocols[p].file == entry.file)
                throw PlanError(prefix + "protocols '" + protocolPaths[p] + "' and '" + path +
                                "' have the same file name, and the plan keeps both in " + entry.file);
        entry.name = parsed.name;
        entry.game = parsed.game;
        entry.hash = fnv1a64(parsed.copy);
        entry.conditions = parsed.conditions;
        entry.blocked = parsed.blocked;
        plan.protocols.push_back(std::move(entry));
        texts.push_back(parsed.copy);
    }

    appendParticipants(plan, participants, ids, prefix);
    std::error_code error;
    fs::create_directories(fs::path(planDir) / "protocols", error);
    if (error)
        throw PlanError(prefix + "the folder '" + (fs::path(planDir) / "protocols").string() +
                        "' could not be made: " + error.message());
    for (std::size_t p = 0; p < plan.protocols.size(); ++p)
        writeWhole(fs::path(planDir) / plan.protocols[p].file, texts[p], "the protocol copy");
    return plan;
}

void writePlan(const std::string& planDir, const StudyPlan& plan) {
    const strict::Source file = planSource(planDir);
    validate(file, planDir, plan);
    const fs::path target = file.path;
    const fs::path partial = fs::path(planDir) / ".study.json.partial";
    writeWhole(partial, planText(plan), "study plan");
    std::error_code error;
    fs::rename(partial, target, error);
    if (error) throw PlanError("study plan '" + file.path + "' could not be written: " + error.message());
}

StudyPlan readPlan(const std::string& planDir) {
    const strict::Reader reader(planSource(planDir));
    StudyPlan plan = fromJson(reader, reader.readObject());
    validate(reader.source(), planDir, plan);
    return plan;
}

StudyPlan extendPlan(const std::string& planDir, const StudyPlan& plan, int participants,
                     const std::vector<std::string>& ids) {
    const std::string prefix = "study plan '" + studyJsonPath(planDir) + "': ";
    if (participants < 1 || participants > kMaxParticipants)
        throw PlanError(prefix + "the number of participants to add must be between 1 and " +
                        std::to_string(kMaxParticipants) + ", got " + std::to_string(participants));
    if (!ids.empty() && ids.size() != static_cast<std::size_t>(participants))
        throw PlanError(prefix + std::to_string(ids.size()) + " participant ids given for " +
                        std::to_string(participants) + " participants");
    StudyPlan grown = plan;
    appendParticipants(grown, participants, ids, prefix);
    return grown;
}

const ParticipantPlan* findParticipant(const StudyPlan& plan, const std::string& id) {
    for (const ParticipantPlan& row : plan.participants)
        if (row.id == id) return &row;
    return nullptr;
}

std::string participantProtocolJson(const std::string& planDir, const StudyPlan& plan,
                                    const ParticipantPlan& participant, int protocolIndex) {
    const strict::Source file = planSource(planDir);
    if (protocolIndex < 0 || static_cast<std::size_t>(protocolIndex) >= plan.protocols.size() ||
        static_cast<std::size_t>(protocolIndex) >= participant.conditionOrder.size())
        file.fail(
            "protocols",
            "has no protocol " + std::to_string(protocolIndex) + " for participant " + jsonString(participant.id));
    const ProtocolEntry& entry = plan.protocols[static_cast<std::size_t>(protocolIndex)];
    const std::string where = "protocols[" + std::to_string(protocolIndex) + "].file";
    const std::string text = protocolText(file, planDir, entry, where);
    const std::unique_ptr<game::Study> study = studyOf(text, protocolPath(file, planDir, entry, where).string());
    if (!study->counterbalanced())
        file.fail(where, "is a " + jsonString(entry.game) + " protocol, whose list a study plan does not know");
    return study->withConditionOrder(text, participant.conditionOrder[static_cast<std::size_t>(protocolIndex)]);
}

}  // namespace warplab::plan
