// The one definition of each session record type's columns. The session writer (CREATE TABLE,
// INSERT and its binds), the reader (SELECT and the storage-class checks), the per-commit
// checksums and replay's record comparison all walk these tables, so adding a field to a
// record is: the struct member in session_store.h, its row here, its line in
// docs/session-format.md (a test checks the page against these tables), and a format version
// bump.
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "session/session_store.h"

namespace warplab::session {

// How a column is stored in SQLite:
//   Integer     INTEGER NOT NULL (range-checked against the member's type when read);
//   Real        an untyped column whose CHECK admits only REAL or NULL: doubles bit for bit,
//               -0.0 included, NaN as NULL (docs/session-format.md says why it is untyped);
//   Text        TEXT NOT NULL, any bytes;
//   JsonObject  TEXT NOT NULL holding a JSON object or "" (none); the writer refuses anything
//               else, and firstDifference compares it key by key.
enum class Storage { Integer, Real, Text, JsonObject };

// One column of a record table: its name, how it is stored, and the member that holds it.
// The storage follows from the member's type (strings are Text unless asked to be JsonObject),
// so the two cannot disagree.
template <class R>
struct Field {
    using Member = std::variant<std::int64_t R::*, int R::*, std::uint32_t R::*, double R::*, std::string R::*>;

    // Not templates, so that a member of a base class of R converts (the store's version-1
    // rows extend today's records).
    Field(const char* name, std::int64_t R::*m) : column(name), storage(Storage::Integer), member(m) {}
    Field(const char* name, int R::*m) : column(name), storage(Storage::Integer), member(m) {}
    Field(const char* name, std::uint32_t R::*m) : column(name), storage(Storage::Integer), member(m) {}
    Field(const char* name, double R::*m) : column(name), storage(Storage::Real), member(m) {}
    Field(const char* name, std::string R::*m, bool jsonObject = false)
        : column(name), storage(jsonObject ? Storage::JsonObject : Storage::Text), member(m) {}

    const char* column;  // SQL column name, also the name firstDifference reports
    Storage storage;
    Member member;
};

// Each record type's columns in table order (the order of CREATE TABLE, of the checksum's
// serialisation and of firstDifference's search). The events table's `id` column is not a
// field: the writer numbers events itself.
template <class R>
const std::vector<Field<R>>& fieldsOf();
template <>
const std::vector<Field<InputRecord>>& fieldsOf<InputRecord>();
template <>
const std::vector<Field<FrameRecord>>& fieldsOf<FrameRecord>();
template <>
const std::vector<Field<EventRecord>>& fieldsOf<EventRecord>();

// Calls f(field, value) for every field of `record` in table order, `value` being a reference
// to the member (std::int64_t, int, std::uint32_t, double or std::string, const when the
// record is).
template <class R, class F>
void forEachField(R& record, F&& f) {
    using Plain = std::remove_const_t<R>;
    for (const Field<Plain>& field : fieldsOf<Plain>())
        std::visit([&](auto member) { f(field, record.*member); }, field.member);
}

// Whether `text` is what a JsonObject column may hold: "" or one JSON object.
bool isJsonObjectOrEmpty(const std::string& text);

// Replay's comparison of a logged record with the one the replay produced: "" when they are
// the same, else one line naming the first differing column in table order,
//   field 'NAME' logged A, replayed B
// Doubles compare bit for bit (-0.0 is not 0.0; NaN equals only the same NaN bits) and print
// with 17 significant digits; texts print in single quotes. A JsonObject column compares key
// by key (in sorted key order) and names `detail.KEY`, a key present on one side only
// included (printed as "(absent)"); its values print as JSON, numbers compare as doubles bit
// for bit (so 2 and 2.0 are the same: JSON does not tell them apart), and "" is the object
// with no keys. When either side is not a JSON object, the texts are compared and the column
// itself is named.
std::string firstDifference(const InputRecord& logged, const InputRecord& replayed);
std::string firstDifference(const FrameRecord& logged, const FrameRecord& replayed);
std::string firstDifference(const EventRecord& logged, const EventRecord& replayed);

}  // namespace warplab::session
