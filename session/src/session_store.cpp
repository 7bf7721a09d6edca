// The session store on the sqlite3 C API. The record tables' columns come from
// protocol/records.h; docs/session-format.md is the contract with analysts. Keep the three in
// step, and bump kSessionFormatVersion (keeping a frozen description of the old version here
// for the reader) when the schema changes.
#include "session/session_store.h"

#include "session/records.h"

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace warplab::session {
namespace {

namespace fs = std::filesystem;

// "WPLS" in the SQLite header (offset 68): tells a warplab session from any other database
// before reading a single table, and lets `file(1)` style tools recognise it.
constexpr std::int32_t kApplicationId = 0x57504C53;
constexpr const char* kExtension = ".warplab-session";
constexpr std::size_t kMaxNameBytes = 64;

// ---- RAII for the two sqlite3 handle kinds ----

struct DbCloser {
    // close_v2 defers the close until every statement is finalised, so member order in the
    // owners cannot cause a leaked handle.
    void operator()(sqlite3* db) const { sqlite3_close_v2(db); }
};
using Db = std::unique_ptr<sqlite3, DbCloser>;

struct StmtFinaliser {
    void operator()(sqlite3_stmt* stmt) const { sqlite3_finalize(stmt); }
};
using Stmt = std::unique_ptr<sqlite3_stmt, StmtFinaliser>;

// Parameter helpers, not named `bind`: given a std::string, argument-dependent lookup would
// pick std::bind and silently bind nothing. Doubles are bound as REAL storage (IEEE-754
// binary64, read back bit for bit); SQLite turns NaN into NULL, which the reader turns back.
void bindArg(sqlite3_stmt* s, int i, double v) { sqlite3_bind_double(s, i, v); }
void bindArg(sqlite3_stmt* s, int i, std::int64_t v) { sqlite3_bind_int64(s, i, v); }
void bindArg(sqlite3_stmt* s, int i, const std::string& v) {
    // Explicit length: ids and JSON may hold NUL bytes and must survive them.
    sqlite3_bind_text(s, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
}
void bindOptional(sqlite3_stmt* s, int i, const std::optional<std::int64_t>& v) {
    if (v)
        sqlite3_bind_int64(s, i, *v);
    else
        sqlite3_bind_null(s, i);
}

std::string columnText(sqlite3_stmt* s, int i) {
    const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(s, i));
    return text ? std::string(text, static_cast<std::size_t>(sqlite3_column_bytes(s, i)))
                : std::string();
}

std::string utcNow() {
    using namespace std::chrono;
    const auto now = system_clock::now();
    const std::time_t seconds = system_clock::to_time_t(now);
    const auto millis =
        duration_cast<milliseconds>(now.time_since_epoch()).count() % 1000;
    std::tm tm{};
    gmtime_r(&seconds, &tm);
    char text[96];  // room for any int the format could meet, so no truncation warning
    std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900,
                  tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec,
                  static_cast<int>(millis));
    return text;
}

// Meta values are TEXT; numbers go through to_chars/from_chars, which are exact (shortest
// round-trip form) and, unlike printf/strtod, ignore the process locale.
std::string numberText(double v) {
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

// Only [A-Za-z0-9_-] reach the file system; every run of anything else becomes one '_'.
// The id cannot then name a folder ('/' and '.' are gone), so it cannot be "." or "..", and
// a leading '-' is replaced too so the file name never reads as a command-line option.
std::string safeName(const std::string& raw, std::size_t maxBytes) {
    std::string out;
    for (const char c : raw) {
        const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                        (c >= '0' && c <= '9') || c == '_' || c == '-';
        if (ok)
            out += c;
        else if (out.empty() || out.back() != '_')
            out += '_';
        if (out.size() >= maxBytes) break;
    }
    if (!out.empty() && out.front() == '-') out.front() = '_';
    return out;
}

std::string timeForName(const std::string& iso) {
    std::string out;
    for (const char c : iso)
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'))
            out += c;
    return out.substr(0, 32);
}

bool anyExists(const std::string& path) {
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"})
        if (fs::exists(fs::symlink_status(path + suffix, ec))) return true;
    return false;
}

void removeSessionFiles(const std::string& path) {
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(path + suffix, ec);
}

// Where each record type is stored. Input and frame rows are keyed by their first field
// (frame); event rows by an `id` column before the fields, which the writer numbers 1, 2, 3 ...
// in the order the events were added.
template <typename Row>
struct Table {
    const char* name;
    bool numbered;                          // an `id INTEGER PRIMARY KEY` comes first
    const std::vector<Field<Row>>& fields;  // records.h, or the version-1 ones below

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
const Table<InputRecord>& inputTable() {
    static const Table<InputRecord> table{"input", false, fieldsOf<InputRecord>()};
    return table;
}
const Table<FrameRecord>& frameTable() {
    static const Table<FrameRecord> table{"frames", false, fieldsOf<FrameRecord>()};
    return table;
}
const Table<EventRecord>& eventTable() {
    static const Table<EventRecord> table{"events", true, fieldsOf<EventRecord>()};
    return table;
}

constexpr const char* kSchema[] = {
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

constexpr const char* kCommitColumns =
    "id, input_rows, frame_rows, event_rows, last_frame, checksum";

// ---- version 1, read only ----
// Frozen as version 1 wrote them: the column order is also the order its checksums were
// computed in. A version-1 row type extends today's record with the columns version 2 moved
// into detail_json; toRecord() below folds them in.

struct V1FrameRow : FrameRecord {
    double targetX = 0, targetY = 0, targetZ = 0;
    std::int64_t targetVisible = 0;
};
struct V1EventRow : EventRecord {
    int difficulty = 0;
    double targetSpeed = 0, spawnTime = 0, aimTime = 0, angularErrorDeg = 0;
};

const std::vector<Field<InputRecord>>& v1InputFields() {
    using R = InputRecord;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},       {"display_time", &R::displayTime}, {"mouse_dx", &R::mouseDx},
        {"mouse_dy", &R::mouseDy}, {"buttons", &R::buttons},          {"keys", &R::keys},
    };
    return fields;
}
const std::vector<Field<V1FrameRow>>& v1FrameFields() {
    using R = V1FrameRow;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},
        {"mode", &R::mode},
        {"kind", &R::kind},
        {"frame_ms", &R::frameMs},
        {"missed_vsyncs", &R::missedVsyncs},
        {"camera_yaw", &R::cameraYaw},
        {"camera_pitch", &R::cameraPitch},
        {"target_x", &R::targetX},
        {"target_y", &R::targetY},
        {"target_z", &R::targetZ},
        {"target_visible", &R::targetVisible},
    };
    return fields;
}
const std::vector<Field<V1EventRow>>& v1EventFields() {
    using R = V1EventRow;
    static const std::vector<Field<R>> fields = {
        {"frame", &R::frame},
        {"type", &R::type},
        {"phase", &R::phase},
        {"trial", &R::trial},
        {"mode", &R::mode},
        {"difficulty", &R::difficulty},
        {"target_speed", &R::targetSpeed},
        {"spawn_time", &R::spawnTime},
        {"event_time", &R::eventTime},
        {"aim_time", &R::aimTime},
        {"world_outcome", &R::worldOutcome},
        {"displayed_outcome", &R::displayedOutcome},
        {"angular_error_deg", &R::angularErrorDeg},
        {"detail_json", &R::detailJson, /*jsonObject=*/true},
    };
    return fields;
}

// Rows the storage-class checks pass but that are still not what the writer wrote.
template <typename Row>
bool rowValid(const Row&) {
    return true;
}
bool rowValid(const V1FrameRow& r) { return r.targetVisible == 0 || r.targetVisible == 1; }
bool rowValid(const V1EventRow& r) { return isJsonObjectOrEmpty(r.detailJson); }

// Rows as records of today's format. Version 1's shooter columns go into detail_json under the
// keys the shooter writes today (docs/session-format.md, "Version 1"), so the session replays.
template <typename Record>
Record toRecord(Record r) {
    return r;
}
FrameRecord toRecord(V1FrameRow&& r) {
    FrameRecord out = std::move(static_cast<FrameRecord&>(r));
    out.detailJson = r.targetVisible
                         ? nlohmann::json{{"target", nlohmann::json::array({r.targetX, r.targetY,
                                                                            r.targetZ})}}
                               .dump()
                         : std::string();
    return out;
}
EventRecord toRecord(V1EventRow&& r) {
    nlohmann::json detail = r.detailJson.empty() ? nlohmann::json::object()
                                                 : nlohmann::json::parse(r.detailJson);
    detail["difficulty"] = r.difficulty;
    if (r.type == "shot" || r.type == "timeout" || r.type == "level")
        detail["target_speed"] = r.targetSpeed;
    if (r.type == "shot" || r.type == "timeout") {
        detail["spawn_time"] = r.spawnTime;
        detail["aim_time"] = r.aimTime;
        detail["angular_error_deg"] = r.angularErrorDeg;
    }
    EventRecord out = std::move(static_cast<EventRecord&>(r));
    out.detailJson = detail.dump();
    return out;
}

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
    return std::string("INSERT INTO ") + table.name + " (" + table.columns() + ") VALUES (" +
           values + ")";
}

// SQLite has no page checksums: a file cut inside a page reads back with zeros in place of
// the lost bytes and no error. So every commit carries a checksum of its own rows (and the
// header one of its own), and the reader keeps only commits that verify. FNV-1a 64 over a
// fixed little-endian serialisation of each row's fields in table order, spelled out in
// docs/session-format.md.
class Checksum {
public:
    void i64(std::int64_t v) {
        auto u = static_cast<std::uint64_t>(v);
        for (int i = 0; i < 8; ++i, u >>= 8) byte(static_cast<unsigned char>(u & 0xff));
    }
    void f64(double v) {
        // NaN is stored as NULL and read back as the quiet NaN, so hash that one.
        if (std::isnan(v)) v = std::numeric_limits<double>::quiet_NaN();
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        i64(static_cast<std::int64_t>(bits));
    }
    void text(const std::string& v) {
        i64(static_cast<std::int64_t>(v.size()));
        for (const char c : v) byte(static_cast<unsigned char>(c));
    }
    std::uint64_t value() const { return h_; }

private:
    void byte(unsigned char b) { h_ = (h_ ^ b) * 0x100000001b3ull; }
    std::uint64_t h_ = 0xcbf29ce484222325ull;
};

// Integers as 8-byte integers, doubles as their bits, texts (JSON ones too) as length and
// bytes; the events' id is not hashed.
template <typename Row>
void hashRow(Checksum& c, const Table<Row>& table, const Row& r) {
    for (const Field<Row>& field : table.fields)
        std::visit(
            [&](auto member) {
                const auto& v = r.*member;
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, std::string>)
                    c.text(v);
                else if constexpr (std::is_same_v<T, double>)
                    c.f64(v);
                else
                    c.i64(static_cast<std::int64_t>(v));
            },
            field.member);
}

// One running checksum per table for the rows of the commit being built.
struct CommitChecksum {
    Checksum input, frames, events;
    std::int64_t value() const {
        Checksum c;
        c.i64(static_cast<std::int64_t>(input.value()));
        c.i64(static_cast<std::int64_t>(frames.value()));
        c.i64(static_cast<std::int64_t>(events.value()));
        return static_cast<std::int64_t>(c.value());
    }
};

// The header as meta entries, in checksum order (completed_at and header_checksum are not
// part of it). The single list of header keys: the writer stores these, the reader checks
// the same keys.
std::vector<std::pair<const char*, std::string>> headerEntries(const SessionHeader& h) {
    return {
        {"format_version", std::to_string(kSessionFormatVersion)},
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
}

}  // namespace

// ============================ writer ============================

namespace {

// Thrown inside a write while another connection holds the file's write lock: the write is
// rolled back and everything it would have written stays held for the next try.
struct LockBusy {};

bool isBusy(int rc) { return (rc & 0xff) == SQLITE_BUSY || (rc & 0xff) == SQLITE_LOCKED; }

// Which file a path names now (device and inode), or nothing when the name is gone.
std::optional<std::pair<dev_t, ino_t>> fileIdentity(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return std::nullopt;
    return std::make_pair(st.st_dev, st.st_ino);
}

}  // namespace

struct SessionWriter::Impl {
    using Clock = std::chrono::steady_clock;

    std::string path;
    Db db;
    Stmt insertInput, insertFrame, insertEvent, insertCommit, insertMeta;
    bool writing = false;   // inside writeHeld(): a busy lock is LockBusy, not a failure
    bool finished = false;

    // Rows are kept in memory until they are written, so another program's write lock can
    // only delay them (see commit()).
    struct Rows {
        std::vector<InputRecord> inputs;
        std::vector<FrameRecord> frames;
        std::vector<EventRecord> events;
    };
    // Added since the last commit(): part of no commit yet, dropped as in a crash.
    Rows adding;
    CommitChecksum addingChecksum;
    std::map<std::string, std::string> addingFlags;
    std::optional<std::int64_t> lastInputFrame, lastFrameFrame;  // over every row added

    // Commits made but not yet in the file, oldest first, and what goes with them.
    struct Held {
        Rows rows;
        std::int64_t inputRows = 0, frameRows = 0, eventRows = 0;  // cumulative, after it
        std::optional<std::int64_t> lastFrame;
        std::int64_t checksum = 0;
        std::string committedAt;
    };
    std::deque<Held> held;
    std::map<std::string, std::string> heldFlags;
    bool completing = false;  // finish(): completed_at still to be written
    std::optional<Clock::time_point> heldSince;
    // Rows in every commit so far, written or held: a commit's counts are cumulative.
    std::int64_t inputRows = 0, frameRows = 0, eventRows = 0;

    // Names that must keep meaning the files this connection writes (checkWhereItWrites).
    std::optional<std::pair<dev_t, ino_t>> fileId, walId;
    std::vector<std::string> notices;

    ~Impl() {
        // Held commits were committed as far as the game knows: one last short try to write
        // them. What was added after the last commit is dropped, as a crash would drop it.
        if (!db || (held.empty() && heldFlags.empty() && !completing)) return;
        try {
            const auto deadline = Clock::now() + std::chrono::seconds(2);
            while (!writeHeld() && Clock::now() < deadline)
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
        } catch (...) {
        }
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw SessionError("Cannot write session file " + path + " (" + what +
                           "): " + sqlite3_errmsg(db.get()) + ".");
    }
    void check(int rc, const char* what) const {
        if (writing && isBusy(rc)) throw LockBusy{};
        fail(what);
    }
    void exec(const char* sql, const char* what) {
        const int rc = sqlite3_exec(db.get(), sql, nullptr, nullptr, nullptr);
        if (rc != SQLITE_OK) check(rc, what);
    }
    Stmt prepare(const std::string& sql) {
        sqlite3_stmt* raw = nullptr;
        if (sqlite3_prepare_v3(db.get(), sql.c_str(), -1, SQLITE_PREPARE_PERSISTENT, &raw,
                               nullptr) != SQLITE_OK)
            fail("preparing a statement");
        return Stmt(raw);
    }
    void run(sqlite3_stmt* s, const char* what) {
        const int rc = sqlite3_step(s);
        sqlite3_reset(s);
        if (rc != SQLITE_DONE) check(rc, what);
    }
    void putMeta(const std::string& key, const std::string& value) {
        bindArg(insertMeta.get(), 1, key);
        bindArg(insertMeta.get(), 2, value);
        run(insertMeta.get(), "writing the header");
    }

    // Opens `path` (which holds at least the header) for appending: WAL, fsync per commit,
    // statements prepared. Also used to reopen after the files were replaced under us.
    void openForWriting() {
        sqlite3* raw = nullptr;
        const int rc = sqlite3_open_v2(path.c_str(), &raw, SQLITE_OPEN_READWRITE, nullptr);
        db.reset(raw);
        if (rc != SQLITE_OK) fail("opening");
        // No busy wait inside SQLite: a foreign write lock must not stall a live frame. The
        // writer holds its commits and retries instead (commit(), flush()).
        sqlite3_busy_timeout(db.get(), 0);
        // WAL: a commit appends to the log, so a kill mid-commit leaves the previous commit
        // intact, and analysts can read a running session. FULL: each commit is fsynced, so
        // a power cut keeps it as well; one fsync per trial costs nothing next to a
        // participant's hour (see docs/session-format.md).
        sqlite3_stmt* rawMode = nullptr;
        sqlite3_prepare_v2(db.get(), "PRAGMA journal_mode=WAL", -1, &rawMode, nullptr);
        Stmt mode(rawMode);
        if (!mode || sqlite3_step(mode.get()) != SQLITE_ROW || columnText(mode.get(), 0) != "wal")
            fail("switching to WAL mode");
        mode.reset();
        exec("PRAGMA synchronous=FULL", "setting synchronous");
        insertMeta = prepare("INSERT OR REPLACE INTO meta (key, value) VALUES (?, ?)");
        insertInput = prepare(insertSql(inputTable()));
        insertFrame = prepare(insertSql(frameTable()));
        insertEvent = prepare(insertSql(eventTable()));
        insertCommit = prepare(
            "INSERT INTO commits (input_rows, frame_rows, event_rows, last_frame, "
            "last_event_id, checksum, committed_at) VALUES (?, ?, ?, ?, ?, ?, ?)");
        fileId = fileIdentity(path);
        walId.reset();  // learnt after the first write: SQLite makes the log when it needs it
    }
    void close() {
        insertInput.reset();
        insertFrame.reset();
        insertEvent.reset();
        insertCommit.reset();
        insertMeta.reset();
        db.reset();
    }

    // Makes the rows added since the last commit one commit, held until it is written.
    void commitAdded() {
        const bool rows = !adding.inputs.empty() || !adding.frames.empty() || !adding.events.empty();
        for (auto& [name, text] : addingFlags) heldFlags[name] = std::move(text);
        addingFlags.clear();
        if (!rows) return;
        Held h;
        h.inputRows = inputRows += static_cast<std::int64_t>(adding.inputs.size());
        h.frameRows = frameRows += static_cast<std::int64_t>(adding.frames.size());
        h.eventRows = eventRows += static_cast<std::int64_t>(adding.events.size());
        h.lastFrame = lastInputFrame;
        if (lastFrameFrame && (!h.lastFrame || *lastFrameFrame > *h.lastFrame)) h.lastFrame = lastFrameFrame;
        h.checksum = addingChecksum.value();
        h.committedAt = utcNow();
        h.rows = std::move(adding);
        adding = Rows{};
        addingChecksum = CommitChecksum{};
        held.push_back(std::move(h));
        if (!heldSince) heldSince = Clock::now();
    }

    // Binds one record's fields in table order (after its id, for numbered tables) and
    // inserts it.
    template <typename R>
    void insert(const Table<R>& table, sqlite3_stmt* s, const R& r, std::int64_t id,
                const char* what) {
        int i = 1;
        if (table.numbered) bindArg(s, i++, id);
        for (const Field<R>& field : table.fields)
            std::visit(
                [&](auto member) {
                    const auto& v = r.*member;
                    using T = std::decay_t<decltype(v)>;
                    if constexpr (std::is_same_v<T, std::string> || std::is_same_v<T, double>)
                        bindArg(s, i++, v);
                    else
                        bindArg(s, i++, static_cast<std::int64_t>(v));
                },
                field.member);
        run(s, what);
    }

    // Writes every held commit, in order, then the held flags and completed_at, as ONE
    // transaction (fsynced). False, with nothing written, while another connection holds the
    // write lock; any other failure throws SessionError and keeps everything held.
    bool writeHeld() {
        if (held.empty() && heldFlags.empty() && !completing) return true;
        writing = true;
        try {
            exec("BEGIN IMMEDIATE", "starting a transaction");
            for (const Held& h : held) {
                for (const InputRecord& r : h.rows.inputs)
                    insert(inputTable(), insertInput.get(), r, 0, "adding an input record");
                for (const FrameRecord& r : h.rows.frames)
                    insert(frameTable(), insertFrame.get(), r, 0, "adding a frame record");
                std::int64_t id = h.eventRows - static_cast<std::int64_t>(h.rows.events.size());
                for (const EventRecord& r : h.rows.events)
                    insert(eventTable(), insertEvent.get(), r, ++id, "adding an event record");
                sqlite3_stmt* s = insertCommit.get();
                bindArg(s, 1, h.inputRows);
                bindArg(s, 2, h.frameRows);
                bindArg(s, 3, h.eventRows);
                bindOptional(s, 4, h.lastFrame);
                bindOptional(s, 5, h.eventRows > 0 ? std::optional<std::int64_t>(h.eventRows)
                                                   : std::nullopt);
                bindArg(s, 6, h.checksum);
                bindArg(s, 7, h.committedAt);
                run(s, "recording the commit");
            }
            for (const auto& [name, text] : heldFlags) putMeta("flag:" + name, text);
            if (completing) putMeta("completed_at", utcNow());
            exec("COMMIT", "committing");
        } catch (...) {
            writing = false;
            // A failed COMMIT may or may not have rolled back by itself; make sure it did,
            // so the file holds exactly what it held before.
            if (!sqlite3_get_autocommit(db.get()))
                sqlite3_exec(db.get(), "ROLLBACK", nullptr, nullptr, nullptr);
            try {
                throw;
            } catch (const LockBusy&) {
                return false;
            }
        }
        writing = false;
        held.clear();
        heldFlags.clear();
        completing = false;
        heldSince.reset();
        // Fold the log into the main file at once (PASSIVE: never waits for a reader). The
        // -wal then holds no commit the file lacks, so a -wal deleted or damaged later loses
        // nothing written before.
        sqlite3_wal_checkpoint_v2(db.get(), nullptr, SQLITE_CHECKPOINT_PASSIVE, nullptr, nullptr);
        checkWhereItWrites();
        return true;
    }

    // Another program may delete or replace the session file or its -wal while we write
    // (a cleanup script, a sync tool). SQLite would go on writing the old, now nameless,
    // files, and everything from then on would vanish at the next kill. So after each write
    // the names are checked against the files this connection has open; on a change the
    // session is saved under its name again from the open files, and the supervisor told.
    void checkWhereItWrites() {
        const auto nowFile = fileIdentity(path);
        const auto nowWal = fileIdentity(path + "-wal");
        if (!walId) walId = nowWal;
        const bool fileMoved = nowFile != fileId;
        const bool walMoved = walId && nowWal != walId;
        if (!fileMoved && !walMoved) return;

        std::string savedTo = path;
        if (fileMoved) {
            // The file itself is gone or another one is in its place: a complete copy, from
            // what this connection sees, goes to the name if it is free, else beside it.
            // No -wal or -shm of the name may be left either: SQLite would take them for the
            // new file's.
            for (int n = 1; anyExists(savedTo); ++n)
                savedTo = path.substr(0, path.size() - std::strlen(kExtension)) + "-rescued" +
                          (n > 1 ? "-" + std::to_string(n) : "") + kExtension;
            Stmt copy = prepare("VACUUM INTO ?");
            bindArg(copy.get(), 1, savedTo);
            if (sqlite3_step(copy.get()) != SQLITE_DONE) fail("saving a copy to " + savedTo);
        } else {
            // Only the -wal: the checkpoint above copied every commit from the open log into
            // the file, unless a reader's snapshot held it back; then try again next time.
            int logFrames = 0, copied = 0;
            sqlite3_wal_checkpoint_v2(db.get(), nullptr, SQLITE_CHECKPOINT_PASSIVE, &logFrames, &copied);
            if (copied < logFrames) return;
        }
        const std::string what =
            fileMoved ? "the session file " + path + " was deleted or replaced by another program"
                      : "the log " + path + "-wal was deleted or replaced by another program";
        close();
        path = savedTo;
        openForWriting();
        const std::string text = what + "; every commit up to then is saved in " + path;
        notices.push_back(text);
        heldFlags[fileMoved ? "file_replaced" : "wal_replaced"] = text;
        writeHeld();  // the flag; if the lock is taken now, it goes with the next commit
    }

    static void checkFollows(const std::optional<std::int64_t>& last, std::int64_t frame,
                             const char* caller) {
        if (last && frame <= *last)
            throw std::invalid_argument(std::string("SessionWriter::") + caller + ": frame " +
                                        std::to_string(frame) + " does not follow frame " +
                                        std::to_string(*last) + ".");
    }

    template <typename R>
    static void checkJson(const Table<R>& table, const R& r, const char* caller) {
        for (const Field<R>& field : table.fields) {
            if (field.storage != Storage::JsonObject) continue;
            const std::string& text = r.*std::get<std::string R::*>(field.member);
            if (!isJsonObjectOrEmpty(text))
                throw std::invalid_argument(std::string("SessionWriter::") + caller + ": " +
                                            field.column +
                                            " must be a JSON object or empty, not '" +
                                            text.substr(0, 80) + "'.");
        }
    }

    void checkOpen(const char* caller) const {
        if (finished)
            throw std::logic_error(std::string("SessionWriter::") + caller +
                                   ": the session is already finished.");
    }

    // Retries writeHeld() until it gets the lock, telling `waiting` about once a second.
    void waitForWrite(const WaitCallback& waiting) {
        const auto start = Clock::now();
        auto nextCall = start + std::chrono::seconds(1);
        while (!writeHeld()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            if (waiting && Clock::now() >= nextCall) {
                waiting(std::chrono::duration<double>(Clock::now() - start).count());
                nextCall += std::chrono::seconds(1);
            }
        }
    }
};

SessionWriter::SessionWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SessionWriter::SessionWriter(SessionWriter&&) noexcept = default;
SessionWriter& SessionWriter::operator=(SessionWriter&&) noexcept = default;

SessionWriter::~SessionWriter() = default;

SessionWriter::Impl& SessionWriter::impl(const char* caller) const {
    if (!impl_)
        throw std::logic_error(std::string("SessionWriter::") + caller +
                               ": this writer was moved from.");
    return *impl_;
}

const std::string& SessionWriter::path() const { return impl("path").path; }

SessionWriter SessionWriter::create(const std::string& resultsDir, const SessionHeader& header) {
    if (header.formatVersion != kSessionFormatVersion)
        throw std::invalid_argument("SessionWriter::create: header.formatVersion is " +
                                    std::to_string(header.formatVersion) +
                                    " but this warplab writes format version " +
                                    std::to_string(kSessionFormatVersion) + ".");

    // Everything that can be checked is checked before the first file exists, so a bad
    // results folder leaves no litter behind.
    std::error_code ec;
    const auto status = fs::status(resultsDir, ec);
    if (resultsDir.empty() || !fs::exists(status))
        throw SessionError("Results folder '" + resultsDir + "' does not exist.");
    if (!fs::is_directory(status))
        throw SessionError("Results folder '" + resultsDir + "' is not a folder.");
    if (::access(resultsDir.c_str(), W_OK | X_OK) != 0)
        throw SessionError("Results folder '" + resultsDir + "' is not writable (" +
                           std::strerror(errno) + ").");

    SessionHeader h = header;
    if (h.startedAt.empty()) h.startedAt = utcNow();
    std::string stem = safeName(h.participant, kMaxNameBytes);
    if (stem.empty()) stem = "participant";
    const std::string when = timeForName(h.startedAt);
    if (!when.empty()) stem += "_" + when;

    // The header is written into a hidden file beside the session and only then linked to the
    // session's name: a kill at any instant leaves either no session or a readable one with its
    // header, never an empty file. link(2) refuses an existing name, so "pick a free name" and
    // "create it" stay one step (two rigs sharing a results folder never share a file).
    const std::string temp =
        (fs::path(resultsDir) / ("." + stem + "." + std::to_string(::getpid()) + ".creating")).string();
    removeSessionFiles(temp);  // a leftover of a killed run with our pid
    auto impl = std::make_unique<Impl>();
    try {
        {
            sqlite3* raw = nullptr;
            const int rc = sqlite3_open_v2(temp.c_str(), &raw, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
            impl->db.reset(raw);
            impl->path = temp;
            if (rc != SQLITE_OK) impl->fail("creating");
            impl->exec("PRAGMA synchronous=FULL", "setting synchronous");
            impl->exec("BEGIN IMMEDIATE", "writing the header");
            impl->exec(("PRAGMA application_id=" + std::to_string(kApplicationId)).c_str(),
                       "writing the header");
            for (const char* sql : kSchema) impl->exec(sql, "creating the tables");
            impl->exec(inputTable().createSql().c_str(), "creating the tables");
            impl->exec(frameTable().createSql().c_str(), "creating the tables");
            impl->exec(eventTable().createSql().c_str(), "creating the tables");
            impl->insertMeta = impl->prepare("INSERT OR REPLACE INTO meta (key, value) VALUES (?, ?)");
            Checksum checksum;
            for (const auto& [key, value] : headerEntries(h)) {
                impl->putMeta(key, value);
                checksum.text(key);
                checksum.text(value);
            }
            impl->putMeta("header_checksum", numberText(checksum.value()));
            impl->exec("COMMIT", "writing the header");
            impl->insertMeta.reset();
            // WAL mode is kept in the file: switching here, while nobody else can see the
            // file, means another program's lock on the named file can never stop the switch.
            impl->exec("PRAGMA journal_mode=WAL", "switching to WAL mode");
            impl->db.reset();  // closed: the header is in the file, fsynced
        }
        for (int n = 1;; ++n) {
            const std::string name = stem + (n > 1 ? "-" + std::to_string(n) : "") + kExtension;
            const std::string candidate = (fs::path(resultsDir) / name).string();
            if (anyExists(candidate)) continue;
            if (::link(temp.c_str(), candidate.c_str()) == 0) {
                impl->path = candidate;
                break;
            }
            if (errno != EEXIST || n >= 10000)
                throw SessionError("Cannot create session file " + candidate + ": " + std::strerror(errno) + ".");
        }
        removeSessionFiles(temp);  // the other name stays
        impl->openForWriting();
    } catch (...) {
        const std::string path = impl->path;
        impl.reset();
        removeSessionFiles(temp);
        if (path != temp) removeSessionFiles(path);
        throw;
    }
    return SessionWriter(std::move(impl));
}

void SessionWriter::addInput(const InputRecord& r) {
    Impl& w = impl("addInput");
    w.checkOpen("addInput");
    w.checkFollows(w.lastInputFrame, r.frame, "addInput");
    w.adding.inputs.push_back(r);
    w.lastInputFrame = r.frame;
    hashRow(w.addingChecksum.input, inputTable(), r);
}

void SessionWriter::addFrame(const FrameRecord& r) {
    Impl& w = impl("addFrame");
    w.checkOpen("addFrame");
    w.checkFollows(w.lastFrameFrame, r.frame, "addFrame");
    w.checkJson(frameTable(), r, "addFrame");
    w.adding.frames.push_back(r);
    w.lastFrameFrame = r.frame;
    hashRow(w.addingChecksum.frames, frameTable(), r);
}

void SessionWriter::addEvent(const EventRecord& r) {
    Impl& w = impl("addEvent");
    w.checkOpen("addEvent");
    w.checkJson(eventTable(), r, "addEvent");
    w.adding.events.push_back(r);
    hashRow(w.addingChecksum.events, eventTable(), r);
}

bool SessionWriter::commit() {
    Impl& w = impl("commit");
    w.checkOpen("commit");
    w.commitAdded();
    return w.writeHeld();
}

std::size_t SessionWriter::heldCommits() const { return impl("heldCommits").held.size(); }

double SessionWriter::heldForSeconds() const {
    const Impl& w = impl("heldForSeconds");
    return w.heldSince ? std::chrono::duration<double>(Impl::Clock::now() - *w.heldSince).count()
                       : 0.0;
}

void SessionWriter::flush(const WaitCallback& waiting) { impl("flush").waitForWrite(waiting); }

std::vector<std::string> SessionWriter::takeNotices() {
    return std::exchange(impl("takeNotices").notices, {});
}

void SessionWriter::flag(const std::string& name, const std::string& text) {
    Impl& w = impl("flag");
    w.checkOpen("flag");
    w.addingFlags[name] = text;
}

void SessionWriter::finish(const WaitCallback& waiting) {
    Impl& w = impl("finish");
    w.checkOpen("finish");
    w.commitAdded();
    w.completing = true;
    w.waitForWrite(waiting);
    w.finished = true;
    // A finished session becomes one self-contained file (the WAL is folded in and removed),
    // so it can be copied, archived or read from read-only media. Best effort: a reader that
    // holds the file open keeps it in WAL mode, which is just as valid.
    sqlite3_exec(w.db.get(), "PRAGMA journal_mode=DELETE", nullptr, nullptr, nullptr);
}

// ============================ reader ============================

namespace {

// What SQLite will not read back from a session's -wal. SQLite checks each log frame against
// a running checksum and silently stops at the first one that fails (or does not belong to
// the log), dropping every later commit with it. A kill never leaves that: what it cuts off
// has no commit frame after it. So a commit frame of this log after the stop is committed
// data lost to damage. The format is SQLite's (https://sqlite.org/fileformat2.html#walformat).
struct WalLoss {
    std::int64_t byte = 0;  // where the header or frame that fails starts
    int commits = 0;        // commit frames of this log after it (0: the header itself failed)
};

std::uint32_t bigEndian32(const unsigned char* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

// SQLite's WAL checksum over n bytes (a multiple of 8), continuing from s[0], s[1]; words are
// big-endian when the log's magic number says so, else little-endian.
void walChecksum(bool bigEndianWords, const unsigned char* p, std::size_t n, std::uint32_t s[2]) {
    for (std::size_t i = 0; i + 8 <= n; i += 8) {
        std::uint32_t x0 = bigEndian32(p + i), x1 = bigEndian32(p + i + 4);
        if (!bigEndianWords) {
            x0 = __builtin_bswap32(x0);
            x1 = __builtin_bswap32(x1);
        }
        s[0] += x0 + s[1];
        s[1] += x1 + s[0];
    }
}

std::optional<WalLoss> scanWal(const std::string& walPath) {
    std::ifstream in(walPath, std::ios::binary);
    const std::vector<unsigned char> log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    constexpr std::size_t kHeader = 32, kFrameHeader = 24;
    if (log.size() < kHeader) return std::nullopt;  // nothing was logged yet
    const std::uint32_t magic = bigEndian32(log.data());
    std::uint32_t pageSize = bigEndian32(log.data() + 8);
    if (pageSize == 1) pageSize = 65536;
    std::uint32_t sum[2] = {0, 0};
    walChecksum(magic & 1, log.data(), 24, sum);
    const bool headerOk = (magic == 0x377f0682 || magic == 0x377f0683) && pageSize >= 512 &&
                          pageSize <= 65536 && (pageSize & (pageSize - 1)) == 0 &&
                          sum[0] == bigEndian32(log.data() + 24) && sum[1] == bigEndian32(log.data() + 28);
    if (!headerOk)  // a header is only ever written whole, before any frame
        return log.size() > kHeader + kFrameHeader ? std::optional<WalLoss>(WalLoss{0, 0}) : std::nullopt;

    const std::uint32_t salt1 = bigEndian32(log.data() + 16), salt2 = bigEndian32(log.data() + 20);
    const std::size_t frameSize = kFrameHeader + pageSize;
    const auto ofThisLog = [&](std::size_t at) {
        return bigEndian32(log.data() + at + 8) == salt1 && bigEndian32(log.data() + at + 12) == salt2;
    };
    std::size_t at = kHeader;
    for (; at + frameSize <= log.size(); at += frameSize) {
        const unsigned char* frame = log.data() + at;
        if (!ofThisLog(at) || bigEndian32(frame) == 0) break;
        walChecksum(magic & 1, frame, 8, sum);
        walChecksum(magic & 1, frame + kFrameHeader, pageSize, sum);
        if (sum[0] != bigEndian32(frame + 16) || sum[1] != bigEndian32(frame + 20)) break;
    }
    WalLoss loss{static_cast<std::int64_t>(at), 0};
    for (std::size_t later = at + frameSize; later + frameSize <= log.size(); later += frameSize)
        loss.commits += ofThisLog(later) && bigEndian32(log.data() + later + 4) != 0;
    return loss.commits > 0 ? std::optional<WalLoss>(loss) : std::nullopt;
}

// A running writer may be half-way through a frame when we look; damage stays put. So a loss
// counts only when two looks a moment apart agree.
std::optional<WalLoss> lostInWal(const std::string& walPath) {
    auto first = scanWal(walPath);
    for (int look = 0; first && look < 3; ++look) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        auto again = scanWal(walPath);
        if (again && again->byte == first->byte && again->commits == first->commits) return again;
        first = std::move(again);
    }
    return std::nullopt;
}

class Reader {
public:
    explicit Reader(std::string path) : path_(std::move(path)) {}

    SessionData read() {
        open();
        SessionData data;
        // One read transaction: a session still being written is seen as one consistent
        // snapshot across all tables, never a commits table older than the rows.
        exec("BEGIN");
        data.header = readHeader(data.completed);
        data.flags = flags_;
        version_ = data.header.formatVersion;
        if (version_ == 1)
            readTables(data, Layout<InputRecord, V1FrameRow, V1EventRow>{
                                 {"input", false, v1InputFields()},
                                 {"frames", false, v1FrameFields()},
                                 {"events", true, v1EventFields()}});
        else
            readTables(data, Layout<InputRecord, FrameRecord, EventRecord>{
                                 inputTable(), frameTable(), eventTable()});
        // Ending a read transaction writes nothing; after damage SQLite may report the damage
        // again here, which readTables has already accounted for.
        sqlite3_exec(db_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
        return data;
    }

private:
    struct Commit {
        std::int64_t id = 0, inputRows = 0, frameRows = 0, eventRows = 0, checksum = 0;
        std::optional<std::int64_t> lastFrame;
    };
    // Where reading stopped early ("events table", "write-ahead log"), and why.
    struct Stop {
        std::string where, why;
    };

    std::string path_;
    Db db_;
    int version_ = kSessionFormatVersion;  // the file's
    std::optional<Stop> firstStop_;
    std::optional<WalLoss> walLoss_;  // committed data in the -wal that SQLite cannot read
    std::map<std::string, std::string> flags_;  // meta "flag:<name>" entries

    [[noreturn]] void fail(const std::string& sentence) const {
        throw SessionError("Session file " + path_ + " " + sentence);
    }
    std::string errmsg() const { return sqlite3_errmsg(db_.get()); }

    // file:/abs/path?immutable=1, every byte outside [A-Za-z0-9/._~-] percent-encoded.
    static std::string immutableUri(const std::string& path) {
        const std::string absolute = fs::absolute(path).lexically_normal().string();
        std::string uri = "file:";
        for (const char c : absolute) {
            const auto b = static_cast<unsigned char>(c);
            if (std::isalnum(b) || std::strchr("/._~-", c) != nullptr) {
                uri += c;
            } else {
                static const char* hex = "0123456789ABCDEF";
                uri += '%';
                uri += hex[b >> 4];
                uri += hex[b & 15];
            }
        }
        return uri + "?immutable=1";
    }

    void open() {
        std::error_code ec;
        const auto status = fs::status(path_, ec);
        if (!fs::exists(status)) fail("does not exist.");
        if (fs::is_directory(status)) fail("is a folder, not a session file.");
        // A FIFO would block the open forever, a device could be anything.
        if (!fs::is_regular_file(status)) fail("is not a regular file (a pipe, socket or device), not a session file.");
        sqlite3* raw = nullptr;
        // A WAL-mode file without its -wal beside it is whole (finished, or closed without
        // finishing): nothing is writing it. A plain read-only open would still create empty
        // -wal and -shm files next to it; "immutable" reads it as it is and leaves the folder
        // untouched (export promises that). With a -wal present a writer may be running, so
        // the read takes part in SQLite's locking as usual.
        const bool whole = !fs::exists(path_ + "-wal", ec);
        if (!whole) walLoss_ = lostInWal(path_ + "-wal");
        const std::string name = whole ? immutableUri(path_) : path_;
        const int rc = sqlite3_open_v2(name.c_str(), &raw, SQLITE_OPEN_READONLY | (whole ? SQLITE_OPEN_URI : 0), nullptr);
        db_.reset(raw);
        if (rc != SQLITE_OK) fail("cannot be opened: " + errmsg() + ".");
        sqlite3_busy_timeout(db_.get(), 5000);
        // Extra structural checks while walking pages: damaged files fail cleanly sooner.
        sqlite3_exec(db_.get(), "PRAGMA cell_size_check=ON", nullptr, nullptr, nullptr);
        // SQLite refuses a whole file that is shorter than its header says, unless the schema
        // is "writable". On this read-only connection that writes nothing; it lets a cut-off
        // file be read page by page up to the damage, where the checksums take over.
        sqlite3_exec(db_.get(), "PRAGMA writable_schema=ON", nullptr, nullptr, nullptr);

        Stmt s = prepareOrNull("PRAGMA application_id");
        const int step = s ? sqlite3_step(s.get()) : sqlite3_errcode(db_.get());
        if (step != SQLITE_ROW) {
            if ((sqlite3_errcode(db_.get()) & 0xff) == SQLITE_NOTADB)
                fail("is not a SQLite database.");
            fail("has an unreadable header: " + errmsg() + ".");
        }
        if (sqlite3_column_int(s.get(), 0) != kApplicationId)
            fail(std::filesystem::file_size(path_, ec) == 0
                     ? "is empty, not a warplab session."
                     : "is a SQLite database but not a warplab session (wrong application_id).");
    }

    void exec(const char* sql) {
        if (sqlite3_exec(db_.get(), sql, nullptr, nullptr, nullptr) != SQLITE_OK)
            fail("cannot be read: " + errmsg() + ".");
    }
    Stmt prepareOrNull(const std::string& sql) {
        sqlite3_stmt* raw = nullptr;
        sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &raw, nullptr);
        return Stmt(raw);
    }
    // A table whose SELECT does not compile is missing or lacks a column: a schema mismatch,
    // or damage to the schema page itself.
    Stmt prepareTable(const char* table, const char* columns, const char* key) {
        Stmt s = prepareOrNull(std::string("SELECT ") + columns + " FROM " + table +
                               " ORDER BY " + key);
        if (!s)
            fail("does not match the session format " + std::to_string(version_) +
                 " schema: " + errmsg() + ".");
        return s;
    }

    SessionHeader readHeader(bool& completed) {
        Stmt s = prepareOrNull("SELECT key, value FROM meta");
        if (!s) fail("has an unreadable header: " + errmsg() + ".");
        std::map<std::string, std::string> meta;
        int rc;
        while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
            if (sqlite3_column_type(s.get(), 0) != SQLITE_TEXT ||
                sqlite3_column_type(s.get(), 1) != SQLITE_TEXT)
                fail("has an unreadable header: a meta entry is not text.");
            meta[columnText(s.get(), 0)] = columnText(s.get(), 1);
        }
        if (rc != SQLITE_DONE) fail("has an unreadable header: " + errmsg() + ".");

        const auto get = [&](const char* key) -> const std::string& {
            const auto it = meta.find(key);
            if (it == meta.end())
                fail(std::string("has an unreadable header: no '") + key + "' entry in meta.");
            return it->second;
        };
        SessionHeader h;
        // The version first: a newer format may have moved everything else.
        if (!parseNumber(get("format_version"), h.formatVersion))
            fail("has an unreadable header: format_version is '" + get("format_version") + "'.");
        if (h.formatVersion < kOldestSessionFormatVersion ||
            h.formatVersion > kSessionFormatVersion) {
            std::string versions = std::to_string(kOldestSessionFormatVersion);
            for (int v = kOldestSessionFormatVersion + 1; v <= kSessionFormatVersion; ++v)
                versions += (v == kSessionFormatVersion ? " and " : ", ") + std::to_string(v);
            fail("is session format version " + std::to_string(h.formatVersion) +
                 "; this warplab reads session format versions " + versions + ".");
        }
        Checksum checksum;
        for (const auto& entry : headerEntries(SessionHeader{})) {
            checksum.text(entry.first);
            checksum.text(get(entry.first));
        }
        std::uint64_t stored = 0;
        if (!parseNumber(get("header_checksum"), stored) || stored != checksum.value())
            fail("has a damaged header: its checksum does not match its contents.");
        h.protocolJson = get("protocol_json");
        if (!parseNumber(get("seed"), h.seed))
            fail("has an unreadable header: seed is '" + get("seed") + "'.");
        h.participant = get("participant");
        h.appVersion = get("app_version");
        h.glRenderer = get("gl_renderer");
        h.glVersion = get("gl_version");
        if (!parseNumber(get("refresh_hz"), h.refreshHz))
            fail("has an unreadable header: refresh_hz is '" + get("refresh_hz") + "'.");
        if (!parseNumber(get("display_width"), h.displayWidth))
            fail("has an unreadable header: display_width is '" + get("display_width") + "'.");
        if (!parseNumber(get("display_height"), h.displayHeight))
            fail("has an unreadable header: display_height is '" + get("display_height") + "'.");
        h.startedAt = get("started_at");
        h.player = get("player");
        completed = meta.count("completed_at") > 0;
        for (const auto& [key, value] : meta)
            if (key.rfind("flag:", 0) == 0) flags_[key.substr(5)] = value;
        return h;
    }

    // Row readers return false for a value of the wrong storage class: damage that SQLite's
    // own page checks cannot see.
    static bool real(sqlite3_stmt* s, int i, double& out) {
        switch (sqlite3_column_type(s, i)) {
        case SQLITE_FLOAT: out = sqlite3_column_double(s, i); return true;
        case SQLITE_NULL: out = std::numeric_limits<double>::quiet_NaN(); return true;
        case SQLITE_INTEGER: out = static_cast<double>(sqlite3_column_int64(s, i)); return true;
        default: return false;
        }
    }
    template <typename T>
    static bool integer(sqlite3_stmt* s, int i, T& out) {
        if (sqlite3_column_type(s, i) != SQLITE_INTEGER) return false;
        const std::int64_t v = sqlite3_column_int64(s, i);
        if (v < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
            v > static_cast<std::int64_t>(std::numeric_limits<T>::max()))
            return false;
        out = static_cast<T>(v);
        return true;
    }
    static bool text(sqlite3_stmt* s, int i, std::string& out) {
        if (sqlite3_column_type(s, i) != SQLITE_TEXT) return false;
        out = columnText(s, i);
        return true;
    }
    static bool optionalInteger(sqlite3_stmt* s, int i, std::optional<std::int64_t>& out) {
        if (sqlite3_column_type(s, i) == SQLITE_NULL) {
            out.reset();
            return true;
        }
        std::int64_t v = 0;
        if (!integer(s, i, v)) return false;
        out = v;
        return true;
    }

    // Reads rows in key order -- the order they were committed in -- until the end or the
    // first unreadable row; what was read before the damage is kept.
    template <typename Row, typename Parse>
    std::vector<Row> readPrefix(const char* table, Stmt s, Parse parse) {
        std::vector<Row> rows;
        int rc;
        while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
            Row row;
            if (!parse(s.get(), row)) {
                stop(table, "row " + std::to_string(rows.size() + 1) + " has a value of the wrong type");
                return rows;
            }
            rows.push_back(std::move(row));
        }
        if (rc != SQLITE_DONE) stop(table, errmsg());
        return rows;
    }
    void stop(const char* table, const std::string& why) {
        if (!firstStop_) firstStop_ = Stop{std::string(table) + " table", why};
    }

    static bool column(sqlite3_stmt* s, int i, double& out) { return real(s, i, out); }
    static bool column(sqlite3_stmt* s, int i, std::string& out) { return text(s, i, out); }
    template <typename T>
    static bool column(sqlite3_stmt* s, int i, T& out) {
        return integer(s, i, out);
    }

    template <typename Row>
    std::vector<Row> readRows(const Table<Row>& table) {
        std::int64_t rowsRead = 0;
        return readPrefix<Row>(
            table.name, prepareTable(table.name, table.columns().c_str(), table.key()),
            [&](sqlite3_stmt* s, Row& r) {
                int i = 0;
                std::int64_t id = 0;
                // Ids are 1, 2, 3 ...: a gap means rows were lost.
                if (table.numbered && (!integer(s, i++, id) || id != ++rowsRead)) return false;
                for (const Field<Row>& field : table.fields)
                    if (!std::visit([&](auto member) { return column(s, i++, r.*member); },
                                    field.member))
                        return false;
                return rowValid(r);
            });
    }

    template <typename Row>
    static auto toRecords(std::vector<Row>&& rows) {
        std::vector<decltype(toRecord(std::move(rows.front())))> out;
        out.reserve(rows.size());
        for (Row& r : rows) out.push_back(toRecord(std::move(r)));
        return out;
    }

    // Reads the rows of a file laid out as `layout` (the file's format version), keeps the
    // commits that verify, and hands them on as today's records.
    template <typename InputRow, typename FrameRow, typename EventRow>
    void readTables(SessionData& data, const Layout<InputRow, FrameRow, EventRow>& layout) {
        auto commits = readPrefix<Commit>(
            "commits", prepareTable("commits", kCommitColumns, "id"),
            [](sqlite3_stmt* s, Commit& c) {
                return integer(s, 0, c.id) && integer(s, 1, c.inputRows) &&
                       integer(s, 2, c.frameRows) && integer(s, 3, c.eventRows) &&
                       optionalInteger(s, 4, c.lastFrame) && integer(s, 5, c.checksum);
            });
        auto inputs = readRows(layout.input);
        auto frames = readRows(layout.frames);
        auto events = readRows(layout.events);

        // The last commit whose rows are all here. Counts are cumulative and rows are read in
        // commit order, so "all here" is "the table has at least that many rows".
        const auto rowCount = [](const auto& v) { return static_cast<std::int64_t>(v.size()); };
        std::optional<Commit> kept;
        std::size_t keptIndex = 0;
        for (std::size_t i = 0; i < commits.size(); ++i) {
            const Commit& c = commits[i];
            const bool ordered = !kept || (c.inputRows >= kept->inputRows &&
                                           c.frameRows >= kept->frameRows &&
                                           c.eventRows >= kept->eventRows);
            if (!ordered) {
                stop("commits", "commit " + std::to_string(c.id) + " counts fewer rows than the one before");
                break;
            }
            if (c.inputRows > rowCount(inputs) || c.frameRows > rowCount(frames) ||
                c.eventRows > rowCount(events)) {
                stop(c.inputRows > rowCount(inputs)   ? "input"
                     : c.frameRows > rowCount(frames) ? "frames"
                                                      : "events",
                     "rows of commit " + std::to_string(c.id) + " are missing");
                break;
            }
            const Commit before = kept.value_or(Commit{});
            CommitChecksum sum;
            for (auto r = before.inputRows; r < c.inputRows; ++r)
                hashRow(sum.input, layout.input, inputs[static_cast<std::size_t>(r)]);
            for (auto r = before.frameRows; r < c.frameRows; ++r)
                hashRow(sum.frames, layout.frames, frames[static_cast<std::size_t>(r)]);
            for (auto r = before.eventRows; r < c.eventRows; ++r)
                hashRow(sum.events, layout.events, events[static_cast<std::size_t>(r)]);
            if (sum.value() != c.checksum) {
                stop("commits", "the rows of commit " + std::to_string(c.id) +
                                    " do not match its checksum");
                break;
            }
            kept = c;
            keptIndex = i + 1;
        }
        const Commit last = kept.value_or(Commit{});
        if (rowCount(inputs) > last.inputRows || rowCount(frames) > last.frameRows ||
            rowCount(events) > last.eventRows)
            stop("commits", "rows after the last readable commit");
        inputs.resize(static_cast<std::size_t>(last.inputRows));
        frames.resize(static_cast<std::size_t>(last.frameRows));
        events.resize(static_cast<std::size_t>(last.eventRows));
        data.inputs = toRecords(std::move(inputs));
        data.frames = toRecords(std::move(frames));
        data.events = toRecords(std::move(events));

        const std::string lastFrame =
            last.lastFrame ? std::to_string(*last.lastFrame) : std::string("(none)");
        if (walLoss_ && !firstStop_)
            firstStop_ = Stop{"write-ahead log", walLoss_->commits == 0
                                                     ? "its header fails its checksum"
                                                     : "the frame at byte " + std::to_string(walLoss_->byte) +
                                                           " fails its checksum"};
        if (firstStop_) {
            data.completed = false;
            data.damaged = true;
            data.note = "damaged (" + firstStop_->where + ": " + firstStop_->why + "): " +
                        (keptIndex == 0 ? std::string("no complete commit survives")
                                        : "kept the first " + std::to_string(keptIndex) +
                                              " commits, ending after frame " + lastFrame) +
                        lostText(commits, keptIndex);
        } else if (!data.completed) {
            data.note = keptIndex == 0 ? std::string("incomplete: no trial was committed")
                                       : "incomplete: ends after frame " + lastFrame +
                                             " (last commit, " + std::to_string(keptIndex) +
                                             " in all)";
        }
    }

    // What damage cost, as far as the file still tells: the commits the commits table lists
    // past the last one kept, and those the -wal holds past its damage.
    std::string lostText(const std::vector<Commit>& commits, std::size_t kept) const {
        std::vector<std::string> parts;
        if (commits.size() > kept) {
            const std::int64_t keptEvents = kept == 0 ? 0 : commits[kept - 1].eventRows;
            parts.push_back(
                (commits.size() == kept + 1 ? "commit " + std::to_string(kept + 1)
                                            : "commits " + std::to_string(kept + 1) + " to " +
                                                  std::to_string(commits.size())) +
                " (" + std::to_string(std::max<std::int64_t>(0, commits.back().eventRows - keptEvents)) +
                " events)");
        }
        if (walLoss_)
            parts.push_back(walLoss_->commits == 0
                                ? std::string("everything in the write-ahead log")
                                : std::to_string(walLoss_->commits) +
                                      (walLoss_->commits == 1 ? " commit" : " commits") +
                                      " in the write-ahead log");
        if (parts.empty()) return "";
        return "; lost " + parts[0] + (parts.size() > 1 ? " and " + parts[1] : "");
    }
};

}  // namespace

SessionData readSession(const std::string& path) { return Reader(path).read(); }

}  // namespace warplab::session
