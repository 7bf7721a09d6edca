// The strict JSON reader every JSON file warplab reads goes through (protocols and their
// games' sections, study plans, population files), so that all of them follow one set of
// rules (docs/protocol.md, "Rules"): bounded size and nesting, no NUL byte or anything after
// the document, a key repeated in one object or not known to the reader is an error, every
// number is finite, of the right type and range-checked, null is never "the default", and
// every error is one sentence naming the file and the JSON path (or line, when the text is not
// JSON at all).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "strict/file.h"
#include "strict/number.h"

namespace warplab::strict {

// Ordered so that a file written from it keeps the documented field order, and errors name
// the first culprit in file order rather than in alphabetical order.
using Json = nlohmann::ordered_json;

// No file warplab reads is deeper than five levels; the limit is there so that no file can
// make parsing slow or deep (the parse and the duplicate-key check keep a path per level).
inline constexpr int kMaxNestingDepth = 32;
// Bounds that no study needs to exceed; they exist so a slip of the keyboard is caught before
// a participant sits down, not to constrain designs.
inline constexpr std::size_t kLineLimit = 200;  // bytes in a name, an id or a one-line text
inline constexpr std::size_t kParagraphLimit = 1000;  // bytes in a text a person reads

// "a" + "b" -> "a.b"; "" + "b" -> "b". A path may end in a note that names its element, such as
// a participant's id (`participants[3] ("P04")`); a key follows that after a space.
std::string joinPath(const std::string& parent, const std::string& key);
// path[i], the JSON path of an array element.
std::string elementPath(const std::string& path, std::size_t index);
// The offending value as the user wrote it, short and ASCII so a message stays one line.
std::string describe(const Json& value);

// Reads one file's JSON; every message starts with the source's kind and path. The key
// readers (number, integer, ...) leave `out` untouched when the key is absent: unset means
// default. The value readers (numberAt, ...) check a value that is there, named `where`.
class Reader {
public:
    explicit Reader(Source source);

    const Source& source() const { return source_; }
    [[noreturn]] void fail(const std::string& path, const std::string& reason) const;

    // The source's file (readFile: a regular file within source.maxBytes) as a JSON object.
    Json readObject() const;
    // The text as a JSON object: more than source.maxBytes, a NUL byte, nesting deeper than
    // kMaxNestingDepth, malformed JSON (with line and column), a number beyond a double (with
    // its line), a key repeated within one object, or a top level that is not an object is an
    // error.
    Json parseObject(const std::string& text) const;

    // format_version, between 1 and `newest`. Read before the rest: a newer file may well have
    // fields this build does not know, and "too new" is the useful thing to say about it.
    int formatVersion(const Json& document, int newest) const;

    // Unknown keys are errors: a misspelt field would otherwise silently take its default.
    void requireKnownKeys(const Json& object, const std::string& path, const std::vector<const char*>& known) const;
    // A key that must be there.
    const Json& required(const Json& parent, const std::string& path, const char* key) const;
    // A nested object; absent means every field in it takes its default.
    const Json* object(const Json& parent, const std::string& path, const char* key) const;
    // An array, non-empty unless allowEmpty; `of` names its elements in the message.
    const Json* array(const Json* parent, const std::string& path, const char* key, const char* of,
                      bool allowEmpty = false) const;

    const Json& objectAt(const Json& value, const std::string& where) const;
    const Json& arrayAt(const Json& value, const std::string& where, const char* of, bool allowEmpty) const;
    double numberAt(const Json& value, const std::string& where, NumberRange range) const;
    std::int64_t integerAt(const Json& value, const std::string& where, std::int64_t low, std::int64_t high) const;
    // For the whole range of a seed, which an int64 does not hold.
    std::uint64_t unsignedAt(const Json& value, const std::string& where, std::uint64_t low, std::uint64_t high) const;
    bool booleanAt(const Json& value, const std::string& where) const;
    std::string stringAt(const Json& value, const std::string& where) const;
    // A non-empty single line of at most kLineLimit bytes (names, labels, statements); with
    // allowEmpty, "" too (a label that may be left blank).
    std::string line(const Json& value, const std::string& where, bool allowEmpty = false) const;

    void number(const Json* parent, const std::string& path, const char* key, NumberRange range, double& out) const;
    void integer(const Json* parent, const std::string& path, const char* key, int low, int high, int& out) const;
    void boolean(const Json* parent, const std::string& path, const char* key, bool& out) const;
    void string(const Json* parent, const std::string& path, const char* key, std::string& out) const;
    // One of `allowed`, spelt exactly.
    void choice(const Json* parent, const std::string& path, const char* key, const std::vector<const char*>& allowed,
                std::string& out) const;
    // Text for a person to read: at most kParagraphLimit bytes, line breaks allowed and no
    // other control characters; may be empty.
    void paragraph(const Json* parent, const std::string& path, const char* key, std::string& out) const;

    // The first value equal to an earlier one is an error naming both places.
    void requireDistinct(const std::vector<std::string>& values,
                         const std::function<std::string(std::size_t)>& where) const;

private:
    Source source_;
};

}  // namespace warplab::strict
