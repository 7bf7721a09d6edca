// Private to protocol/: the strict field reader every game's protocol parser is built from, so
// that all protocol files follow the same rules (docs/protocol.md, "Rules"): unknown keys and
// repeated keys are errors, every number is range-checked, null is never "the default", and
// every error is one sentence naming the file and the JSON path.
#pragma once

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "protocol/study_protocol.h"

namespace warplab::protocol::detail {

// What a protocol may be: bounded, so that no file can make parsing slow or deep.
inline constexpr std::size_t kMaxProtocolBytes = 1 << 20;
inline constexpr int kMaxNestingDepth = 32;

// Ordered so that toJson keeps the documented field order and errors name the first culprit
// in file order rather than in alphabetical order.
using Json = nlohmann::ordered_json;

// Bounds that no study needs to exceed; they exist so a slip of the keyboard (an extra zero, a
// minus sign) is caught before a participant sits down, not to constrain designs.
inline constexpr std::size_t kLineLimit = 200;  // bytes in a name or a one-line text

// Limits that keep a session's data safe (docs/protocol.md has the reasoning). The session
// writer holds the rows of every frame since the last commit point (end of a trial, a match,
// a phase) in memory and writes them as one transaction, so the longest stretch a game runs
// between two of its commit points, times the refresh, is how many frames a crash can lose
// and how big one commit, and the WAL it goes through, can grow. 300 s at the 1000 Hz ceiling
// is 300000 frames: some 90 MB of rows at the click game's ~300 bytes a frame.
inline constexpr double kRefreshLimitHz = 1000;
inline constexpr double kCommitStretchLimitS = 300;

// Shortest text that reads back as the same double; integers without a decimal point.
std::string formatNumber(double value);
// "a" + "b" -> "a.b"; "" + "b" -> "b".
std::string joinPath(const std::string& parent, const std::string& key);
// The offending value as the user wrote it, short and ASCII so a message stays one line.
std::string describe(const Json& value);
// value / unit is a whole number >= 1, with the tolerance game::ModeSchedule uses.
bool wholeMultiple(double value, double unit);
// The top level every protocol starts with, in the documented order; the game's sections follow.
Json headerJson(int formatVersion, const std::string& name, const std::string& description,
                const std::string& game);
// The canonical file text: two-space indent, trailing newline. Bytes that are not UTF-8 become
// replacement characters rather than throwing, so storing a session's copy never fails.
std::string canonicalText(const Json& document);

struct NumberRange {
    double low;
    bool lowOpen;
    double high;
    bool highOpen;

    bool contains(double v) const;
    std::string text() const;  // "between 1 and 2", "greater than 0 and at most 3", ...
};

// Parser state that knows the file name, so every message starts the same way. The typed
// readers leave `out` untouched when the key is absent: unset means default.
class Reader {
public:
    // For reading the "game" field alone; mode checks need the other constructor.
    explicit Reader(std::string source);
    // Throws std::invalid_argument when `modes` is empty: without it no mode can be judged.
    Reader(std::string source, ModeCheck modes);

    [[noreturn]] void fail(const std::string& path, const std::string& reason) const;

    // The text as a JSON object: malformed JSON (with line and column), a key repeated within
    // one object, or a top level that is not an object is an error.
    Json parseObject(const std::string& text) const;
    // The required string "game".
    std::string game(const Json& document) const;
    // "game" must be `expected`. Checked first: in a file for another game nothing else means
    // what this parser thinks, so its other fields are no use in the message.
    void requireGame(const Json& document, const std::string& expected) const;
    // format_version, between 1 and `newest`. Read before the rest: a newer file may well have
    // fields this build does not know, and "too new" is the useful thing to say about it.
    int formatVersion(const Json& document, int newest) const;
    // "name", a required line, and "description", optional free text.
    void nameAndDescription(const Json& document, std::string& name,
                            std::string& description) const;

    // Unknown keys are errors: a misspelt field would otherwise silently take its default.
    void requireKnownKeys(const Json& object, const std::string& path,
                          std::initializer_list<const char*> known) const;
    // A nested object; absent means every field in it takes its default.
    const Json* object(const Json& parent, const std::string& path, const char* key) const;
    // An array, non-empty unless allowEmpty; `of` names its elements in the message.
    const Json* array(const Json* parent, const std::string& path, const char* key,
                      const char* of, bool allowEmpty = false) const;

    void number(const Json* parent, const std::string& path, const char* key, NumberRange range,
                double& out) const;
    void integer(const Json* parent, const std::string& path, const char* key, int low, int high,
                 int& out) const;
    void boolean(const Json* parent, const std::string& path, const char* key, bool& out) const;
    void string(const Json* parent, const std::string& path, const char* key,
                std::string& out) const;
    // One of `allowed`, spelt exactly.
    void choice(const Json* parent, const std::string& path, const char* key,
                const std::vector<const char*>& allowed, std::string& out) const;
    // One of EnumNames<E>, spelt exactly; a message lists them with `out`'s value (the field's
    // default, since nothing has set it yet) first.
    template <class E>
    void choice(const Json* parent, const std::string& path, const char* key, E& out) const {
        std::vector<const char*> allowed{nameOf(out)};
        for (const auto& entry : EnumNames<E>::list)
            if (entry.value != out) allowed.push_back(entry.name);
        std::string name;
        choice(parent, path, key, allowed, name);
        for (const auto& entry : EnumNames<E>::list)
            if (name == entry.name) out = entry.value;
    }
    // A non-empty single line of at most kLineLimit bytes (names, labels, statements).
    std::string line(const Json& value, const std::string& where) const;

    // Mode ids are only read as strings here; whether they exist and fit the refresh is asked
    // of the ModeCheck once the refresh is final (requireMode), so defaults are checked too.
    void modeId(const Json* parent, const std::string& path, const char* key,
                std::string& out) const;
    // A non-empty array of distinct mode ids.
    void modeList(const Json* parent, const std::string& path, const char* key,
                  std::vector<std::string>& out) const;
    void requireMode(const std::string& where, const std::string& id, double refreshHz) const;
    // Each of a list, named path[i].
    void requireModes(const std::string& path, const std::vector<std::string>& ids,
                      double refreshHz) const;

    // The first value equal to an earlier one is an error naming both places.
    void requireDistinct(const std::vector<std::string>& values,
                         const std::function<std::string(std::size_t)>& where) const;

private:
    std::string source_;
    ModeCheck modes_;
};

// display.guard_band and display.supersampling (RenderSettings), read and written alike by
// every game. Written for format `formatVersion` >= 2 always, for older ones only when not
// the defaults (which such files meant).
void readRenderSettings(const Reader& r, const Json* display, RenderSettings& out);
void writeRenderSettings(Json& display, const RenderSettings& settings, int formatVersion);

// path[i], the JSON path of an array element.
std::string elementPath(const std::string& path, std::size_t index);

}  // namespace warplab::protocol::detail
