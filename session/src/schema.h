// Private to session/: the tables, the meta entries and how numbers are written into them,
// shared by the writer and the reader. The record tables' columns come from session/records.h;
// docs/session-format.md is the contract with analysts. Keep the three in step, and bump
// kSessionFormatVersion (keeping a frozen description of the old version for the reader, as
// old_formats.h does for versions 1 to 4) when the schema changes.
#pragma once

#include "session/records.h"
#include "session/session_store.h"

#include <charconv>
#include <cstdint>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace warplab::session::detail {

// "WPLS" in the SQLite header (offset 68): tells a warplab session from any other database
// before reading a single table, and lets `file(1)` style tools recognise it.
inline constexpr std::int32_t kApplicationId = 0x57504C53;

// Where each record type is stored. Input and frame rows are keyed by their first field
// (frame); event rows by an `id` column before the fields, which the writer numbers 1, 2, 3 ...
// in the order the events were added.
template <typename Row>
struct Table {
    const char* name;
    bool numbered;  // an `id INTEGER PRIMARY KEY` comes first
    const std::vector<Field<Row>>& fields;  // records.h, or old_formats.h's frozen ones

    const char* key() const { return numbered ? "id" : fields.front().column; }
    int columnCount() const { return static_cast<int>(fields.size()) + (numbered ? 1 : 0); }
    std::string columns() const {
        std::string out = numbered ? "id" : "";
        for (const Field<Row>& f : fields) out += (out.empty() ? "" : ", ") + std::string(f.column);
        return out;
    }
    // Doubles are columns WITHOUT a declared type: a REAL-affinity column stores -0.0 as the
    // integer 0 (SQLite packs integral reals), which would break bit-exact replay. The CHECK
    // keeps every value a REAL (or NULL for NaN), so analysts still get plain doubles.
    std::string createSql() const {
        std::string sql = std::string("CREATE TABLE ") + name + " (";
        if (numbered) sql += "id INTEGER PRIMARY KEY, ";
        for (std::size_t i = 0; i < fields.size(); ++i) {
            const std::string c = fields[i].column;
            if (i > 0) sql += ", ";
            if (i == 0 && !numbered) {
                sql += c + " INTEGER PRIMARY KEY";
                continue;
            }
            switch (fields[i].storage) {
                case Storage::Integer: sql += c + " INTEGER NOT NULL"; break;
                case Storage::Real: sql += c + " CHECK (typeof(" + c + ") IN ('real', 'null'))"; break;
                case Storage::Text:
                case Storage::JsonObject: sql += c + " TEXT NOT NULL"; break;
            }
        }
        return sql + ")";
    }
};

// Functions rather than globals: usable from any static initialiser.
inline const Table<InputRecord>& inputTable() {
    static const Table<InputRecord> table{"input", false, fieldsOf<InputRecord>()};
    return table;
}
inline const Table<FrameRecord>& frameTable() {
    static const Table<FrameRecord> table{"frames", false, fieldsOf<FrameRecord>()};
    return table;
}
inline const Table<EventRecord>& eventTable() {
    static const Table<EventRecord> table{"events", true, fieldsOf<EventRecord>()};
    return table;
}

inline constexpr const char* kSchema[] = {
    "CREATE TABLE meta ("
    "  key   TEXT PRIMARY KEY,"
    "  value TEXT NOT NULL)",

    "CREATE TABLE commits ("
    "  id            INTEGER PRIMARY KEY,"
    "  input_rows    INTEGER NOT NULL,"
    "  frame_rows    INTEGER NOT NULL,"
    "  event_rows    INTEGER NOT NULL,"
    "  last_frame    INTEGER,"
    "  last_event_id INTEGER,"
    "  checksum      INTEGER NOT NULL,"
    "  committed_at  TEXT NOT NULL)",
};

inline constexpr const char* kCommitColumns = "id, input_rows, frame_rows, event_rows, last_frame, checksum";

template <typename InputRow, typename FrameRow, typename EventRow>
struct Layout {
    Table<InputRow> input;
    Table<FrameRow> frames;
    Table<EventRow> events;
};

template <typename Row>
std::string insertSql(const Table<Row>& table) {
    std::string values = "?";
    for (int i = 1; i < table.columnCount(); ++i) values += ", ?";
    return std::string("INSERT INTO ") + table.name + " (" + table.columns() + ") VALUES (" + values + ")";
}

// Meta values are TEXT; numbers go through to_chars/from_chars, which are exact (shortest
// round-trip form) and, unlike printf/strtod, ignore the process locale.
inline std::string numberText(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}
template <typename T>
std::string numberText(T v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}
template <typename T>
bool parseNumber(const std::string& text, T& out) {
    const char* end = text.data() + text.size();
    const auto r = std::from_chars(text.data(), end, out);
    return r.ec == std::errc() && r.ptr == end;
}

// Meta keys of what the writer adds as a session goes: SessionWriter::flag's and summarize's.
inline constexpr const char* kFlagPrefix = "flag:";
inline constexpr const char* kSummaryPrefix = "summary:";

// meta.resumed: the Resumption list as a JSON array of objects with the keys session_id, file,
// started_at, player, frame and resumed_at ("[]" for none). parseResumed returns false for
// text that is not such an array, leaving `out` unspecified.
std::string resumedText(const std::vector<Resumption>& resumed);
bool parseResumed(const std::string& text, std::vector<Resumption>& out);

// The header as meta entries, in checksum order (completed_at and header_checksum are not
// part of it), as a file of format `version` holds them. The single list of header keys: the
// writer stores these, the reader checks the same keys.
inline std::vector<std::pair<const char*, std::string>> headerEntries(const SessionHeader& h,
                                                                      int version = kSessionFormatVersion) {
    std::vector<std::pair<const char*, std::string>> entries = {
        {"format_version", std::to_string(version)},
        {"protocol_json", h.protocolJson},
        {"seed", numberText(h.seed)},
        {"participant", h.participant},
        {"app_version", h.appVersion},
        {"gl_renderer", h.glRenderer},
        {"gl_version", h.glVersion},
        {"refresh_hz", numberText(h.refreshHz)},
        {"display_width", numberText(h.displayWidth)},
        {"display_height", numberText(h.displayHeight)},
        {"started_at", h.startedAt},
        {"player", h.player},
    };
    if (version >= kSessionIdSince) {
        entries.push_back({"session_id", h.sessionId});
        entries.push_back({"plan_id", h.planId});
    }
    if (version >= kResumedSince) entries.push_back({"resumed", resumedText(h.resumed)});
    if (version >= kPlayerModelSince) entries.push_back({"player_model", h.playerModel});
    return entries;
}

// Header entries outside header_checksum, stored with the header when set: each was added
// without a new format version, because a reader that does not know a meta key passes over
// it, so every earlier reader still reads these files. The single list of them: the writer
// stores these, the reader reads the same keys.
inline constexpr const char* kPhotonMarkerKey = "photon_marker";
inline std::vector<std::pair<const char*, std::string>> headerExtras(const SessionHeader& h) {
    std::vector<std::pair<const char*, std::string>> entries;
    if (!h.photonMarker.empty()) entries.push_back({kPhotonMarkerKey, h.photonMarker});
    return entries;
}

}  // namespace warplab::session::detail
