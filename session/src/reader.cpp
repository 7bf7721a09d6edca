// readSession on the sqlite3 C API: any format version from kOldestSessionFormatVersion on,
// kept to the commits that verify (checksum.h) and handed on as today's records.
#include "session/session_store.h"

#include "session/records.h"

#include "checksum.h"
#include "schema.h"
#include "sqlite_handles.h"
#include "old_formats.h"
#include "wal_scan.h"

#include <sqlite3.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

namespace warplab::session {
namespace {

namespace fs = std::filesystem;

// The store's shared pieces (sqlite_handles.h, schema.h, checksum.h, naming.h, old_formats.h, wal_scan.h).
using namespace detail;

class Reader {
public:
    explicit Reader(std::string path) : path_(std::move(path)) {}

    SessionData read() { return readBesideWal(&Reader::readOpen, &Reader::openImage); }
    // The file alone is opened "immutable" rather than copied whole into memory: that reads
    // only the pages the outline needs (a writer checkpointing meanwhile may make it
    // unreadable alone, and then the -wal decides, as for read()).
    SessionOutline outline() { return readBesideWal(&Reader::outlineOpen, &Reader::openAlone); }

    // The header alone, as SQLite sees the file (with its -wal, if any): what the file says it
    // is, without reading or checking its records.
    SessionHeader header() {
        checkRegularFile();
        std::error_code ec;
        openFile(!fs::exists(path_ + "-wal", ec));
        exec("BEGIN");
        bool completed = false;
        SessionHeader h = readHeader(completed);
        sqlite3_exec(db_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
        return h;
    }

private:
    // Reads the file with readOpen, deciding first whether a -wal beside it belongs to it;
    // openAlone opens the file without its -wal.
    template <typename Result>
    Result readBesideWal(Result (Reader::*readOpen)(), void (Reader::*openAlone)()) {
        checkRegularFile();
        // A WAL-condition file without its -wal beside it is whole (finished, or closed without
        // finishing): nothing is writing it.
        std::error_code ec;
        if (!fs::exists(path_ + "-wal", ec)) {
            openFile(true);
            return (this->*readOpen)();
        }
        // With a -wal present a writer may be running, or the -wal may be stale or another
        // session's. The file alone tells which: a finished file alone is the whole session
        // (a -wal beside it is one the finish left behind, or one put there), and the file's
        // own session id is what the -wal's pages must keep.
        std::optional<Result> alone;
        try {
            Reader fileAlone(path_);
            (fileAlone.*openAlone)();
            alone = (fileAlone.*readOpen)();
        } catch (const SessionError&) {
            // Unreadable alone (a writer checkpointing into it as we copied it): the -wal decides.
        }
        if (alone && alone->completed && !alone->damaged) return std::move(*alone);
        walLoss_ = lostInWal(path_ + "-wal");
        Result data;
        try {
            openFile(false);
            data = (this->*readOpen)();
        } catch (const SessionError& e) {
            if (!alone) throw;
            return withoutWal(std::move(*alone), "the file cannot be read with " + path_ + "-wal: " + e.what());
        }
        if (!alone) return data;
        if (data.header.sessionId != alone->header.sessionId)
            return withoutWal(std::move(*alone),
                              path_ + "-wal is another session's (session_id " + data.header.sessionId + ", not " +
                                  alone->header.sessionId + ")");
        // Damage that only the -wal brings, costing commits the file alone holds whole: a
        // -wal of another session (its commits do not chain to this one's), or of an older
        // copy. The file alone keeps more.
        if (data.damaged && !alone->damaged && rowsOf(*alone) > rowsOf(data))
            return withoutWal(std::move(*alone),
                              path_ + "-wal does not fit this file: reading with it ends " + data.note);
        return data;
    }
    static std::size_t rowsOf(const SessionData& d) { return d.inputs.size() + d.frames.size() + d.events.size(); }
    static std::size_t rowsOf(const SessionOutline& o) {
        return static_cast<std::size_t>(o.inputRows + o.frameRows) + o.events.size();
    }
    void openAlone() { openFile(true); }

    // The file read alone, its -wal refused (`why` says why): whatever the -wal held of this
    // session is lost.
    template <typename Result>
    static Result withoutWal(Result alone, const std::string& why) {
        const std::string alonesNote = alone.note.empty() ? std::string("it holds a complete session") : alone.note;
        alone.completed = false;
        alone.damaged = true;
        alone.note = "damaged (write-ahead log: " + why + "): read the file without it (" + alonesNote +
            "); whatever of this session was only in its own -wal is lost";
        return alone;
    }

    SessionData readOpen() {
        SessionData data;
        // One read transaction: a session still being written is seen as one consistent
        // snapshot across all tables, never a commits table older than the rows.
        exec("BEGIN");
        data.header = readHeader(data.completed);
        data.flags = flags_;
        data.summaries = summaries_;
        version_ = data.header.formatVersion;
        withLayout([&](const auto& layout) { readTables(data, layout); });
        // Ending a read transaction writes nothing; after damage SQLite may report the damage
        // again here, which readTables has already accounted for.
        sqlite3_exec(db_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
        return data;
    }

    SessionOutline outlineOpen() {
        SessionOutline out;
        exec("BEGIN");  // one snapshot, as readOpen's
        out.header = readHeader(out.completed);
        out.flags = flags_;
        out.summaries = summaries_;
        version_ = out.header.formatVersion;
        withLayout([&](const auto& layout) { outlineTables(out, layout); });
        sqlite3_exec(db_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
        return out;
    }

    // Calls read(layout) with the tables laid out as the file's format version lays them.
    template <typename Read>
    void withLayout(Read&& read) {
        // Versions 1 to 4 have no input `text`: their checksums cover the columns they have.
        const Table<InputRecord> input =
            version_ >= kTypedTextSince ? inputTable() : Table<InputRecord>{"input", false, v1To4InputFields()};
        if (version_ == 1)
            read(Layout<InputRecord, V1FrameRow, V1EventRow>{
                input, {"frames", false, v1FrameFields()}, {"events", true, v1EventFields()}});
        else
            read(Layout<InputRecord, FrameRecord, EventRecord>{input, frameTable(), eventTable()});
    }

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
    std::map<std::string, std::string> summaries_;  // meta "summary:<name>" entries
    std::int64_t headerChecksum_ = 0;  // what the first commit's checksum chains to (version 3 on)

    [[noreturn]] void fail(const std::string& sentence) const {
        throw SessionError("Session file " + path_ + " " + sentence);
    }
    std::string errmsg() const { return sqlite3_errmsg(db_.get()); }

    void checkRegularFile() const {
        std::error_code ec;
        const auto status = fs::status(path_, ec);
        if (!fs::exists(status)) fail("does not exist.");
        if (fs::is_directory(status)) fail("is a folder, not a session file.");
        // A FIFO would block the open forever, a device could be anything.
        if (!fs::is_regular_file(status)) fail("is not a regular file (a pipe, socket or device), not a session file.");
    }

    // whole: no -wal beside the file. A plain read-only open of a WAL-condition file would still
    // create empty -wal and -shm files next to it; "immutable" reads it as it is and leaves
    // the folder untouched (export promises that). With a -wal present a writer may be
    // running, so the read takes part in SQLite's locking as usual.
    void openFile(bool whole) {
        sqlite3* raw = nullptr;
        const std::string name = whole ? immutableUri(path_) : path_;
        const int rc =
            sqlite3_open_v2(name.c_str(), &raw, SQLITE_OPEN_READONLY | (whole ? SQLITE_OPEN_URI : 0), nullptr);
        db_.reset(raw);
        if (rc != SQLITE_OK) fail("cannot be opened: " + errmsg() + ".");
        sqlite3_busy_timeout(db_.get(), 5000);
        checkOpened();
    }

    // The file's bytes as they are, without the -wal beside it: SQLite would apply any -wal
    // it finds next to a file, so the bytes are read into memory and opened there, marked as
    // a rollback-journal file (header bytes 18 and 19) so that no log is looked for.
    void openImage() {
        std::ifstream in(path_, std::ios::binary | std::ios::ate);
        if (!in) fail("cannot be read.");
        const auto size = static_cast<sqlite3_int64>(in.tellg());
        in.seekg(0);
        sqlite3* raw = nullptr;
        const int rc = sqlite3_open_v2(":memory:", &raw, SQLITE_OPEN_READWRITE, nullptr);
        db_.reset(raw);
        if (rc != SQLITE_OK) fail("cannot be opened: " + errmsg() + ".");
        auto* image = static_cast<unsigned char*>(sqlite3_malloc64(static_cast<sqlite3_uint64>(size) + 1));
        if (!image) fail("cannot be read: out of memory.");
        in.read(reinterpret_cast<char*>(image), size);
        const auto got = static_cast<sqlite3_int64>(in.gcount());  // shorter if cut meanwhile
        if (got >= 20 && image[18] == 2 && image[19] == 2) image[18] = image[19] = 1;
        // SQLite owns the image from here on, freed with the connection.
        if (sqlite3_deserialize(db_.get(), "main", image, got, size + 1,
                                SQLITE_DESERIALIZE_FREEONCLOSE | SQLITE_DESERIALIZE_READONLY) != SQLITE_OK)
            fail("cannot be read: " + errmsg() + ".");
        checkOpened();
    }

    void checkOpened() {
        std::error_code ec;
        // Extra structural checks while walking pages: damaged files fail cleanly sooner.
        sqlite3_exec(db_.get(), "PRAGMA cell_size_check=ON", nullptr, nullptr, nullptr);
        // SQLite refuses a whole file that is shorter than its header says, unless the schema
        // is "writable". On this read-only connection that writes nothing; it lets a cut-off
        // file be read page by page up to the damage, where the checksums take over.
        sqlite3_exec(db_.get(), "PRAGMA writable_schema=ON", nullptr, nullptr, nullptr);

        Stmt s = prepareOrNull("PRAGMA application_id");
        const int step = s ? sqlite3_step(s.get()) : sqlite3_errcode(db_.get());
        if (step != SQLITE_ROW) {
            if ((sqlite3_errcode(db_.get()) & 0xff) == SQLITE_NOTADB) fail("is not a SQLite database.");
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
    Stmt prepareSelect(const std::string& sql) {
        Stmt s = prepareOrNull(sql);
        if (!s) fail("does not match the session format " + std::to_string(version_) + " schema: " + errmsg() + ".");
        return s;
    }
    Stmt prepareTable(const char* table, const char* columns, const char* key) {
        return prepareSelect(std::string("SELECT ") + columns + " FROM " + table + " ORDER BY " + key);
    }

    SessionHeader readHeader(bool& completed) {
        Stmt s = prepareOrNull("SELECT key, value FROM meta");
        if (!s) fail("has an unreadable header: " + errmsg() + ".");
        std::map<std::string, std::string> meta;
        int rc;
        while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
            if (sqlite3_column_type(s.get(), 0) != SQLITE_TEXT || sqlite3_column_type(s.get(), 1) != SQLITE_TEXT)
                fail("has an unreadable header: a meta entry is not text.");
            meta[columnText(s.get(), 0)] = columnText(s.get(), 1);
        }
        if (rc != SQLITE_DONE) fail("has an unreadable header: " + errmsg() + ".");

        const auto get = [&](const char* key) -> const std::string& {
            const auto it = meta.find(key);
            if (it == meta.end()) fail(std::string("has an unreadable header: no '") + key + "' entry in meta.");
            return it->second;
        };
        SessionHeader h;
        // The version first: a newer format may have moved everything else.
        if (!parseNumber(get("format_version"), h.formatVersion))
            fail("has an unreadable header: format_version is '" + get("format_version") + "'.");
        if (h.formatVersion < kOldestSessionFormatVersion || h.formatVersion > kSessionFormatVersion) {
            std::string versions = std::to_string(kOldestSessionFormatVersion);
            for (int v = kOldestSessionFormatVersion + 1; v <= kSessionFormatVersion; ++v)
                versions += (v == kSessionFormatVersion ? " and " : ", ") + std::to_string(v);
            fail("is session format version " + std::to_string(h.formatVersion) +
                 "; this warplab reads session format versions " + versions + ".");
        }
        Checksum checksum;
        for (const auto& entry : headerEntries(SessionHeader{}, h.formatVersion)) {
            checksum.text(entry.first);
            checksum.text(get(entry.first));
        }
        std::uint64_t stored = 0;
        if (!parseNumber(get("header_checksum"), stored) || stored != checksum.value())
            fail("has a damaged header: its checksum does not match its contents.");
        headerChecksum_ = static_cast<std::int64_t>(stored);
        h.protocolJson = get("protocol_json");
        if (!parseNumber(get("seed"), h.seed)) fail("has an unreadable header: seed is '" + get("seed") + "'.");
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
        if (h.formatVersion >= kSessionIdSince) {
            h.sessionId = get("session_id");
            h.planId = get("plan_id");
        }
        if (h.formatVersion >= kResumedSince && !parseResumed(get("resumed"), h.resumed))
            fail("has an unreadable header: resumed is '" + get("resumed") + "'.");
        if (h.formatVersion >= kPlayerModelSince) h.playerModel = get("player_model");
        if (const auto it = meta.find(kPhotonMarkerKey); it != meta.end()) h.photonMarker = it->second;
        completed = meta.count("completed_at") > 0;
        for (const auto& [key, value] : meta)
            if (key.rfind(kFlagPrefix, 0) == 0)
                flags_[key.substr(std::strlen(kFlagPrefix))] = value;
            else if (key.rfind(kSummaryPrefix, 0) == 0)
                summaries_[key.substr(std::strlen(kSummaryPrefix))] = value;
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
    // Committed data in the -wal that SQLite cannot read is damage, unless something stopped
    // the read first.
    void stopAtWalLoss() {
        if (walLoss_ && !firstStop_)
            firstStop_ = Stop{"write-ahead log",
                              walLoss_->commits == 0
                                  ? "its header fails its checksum"
                                  : "the frame at byte " + std::to_string(walLoss_->byte) + " fails its checksum"};
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
            table.name, prepareTable(table.name, table.columns().c_str(), table.key()), [&](sqlite3_stmt* s, Row& r) {
                int i = 0;
                std::int64_t id = 0;
                // Ids are 1, 2, 3 ...: a gap means rows were lost.
                if (table.numbered && (!integer(s, i++, id) || id != ++rowsRead)) return false;
                for (const Field<Row>& field : table.fields)
                    if (!std::visit([&](auto member) { return column(s, i++, r.*member); }, field.member)) return false;
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

    static bool commitRow(sqlite3_stmt* s, Commit& c) {
        return integer(s, 0, c.id) && integer(s, 1, c.inputRows) && integer(s, 2, c.frameRows) &&
            integer(s, 3, c.eventRows) && optionalInteger(s, 4, c.lastFrame) && integer(s, 5, c.checksum);
    }

    // Reads the rows of a file laid out as `layout` (the file's format version), keeps the
    // commits that verify, and hands them on as today's records.
    template <typename InputRow, typename FrameRow, typename EventRow>
    void readTables(SessionData& data, const Layout<InputRow, FrameRow, EventRow>& layout) {
        auto commits = readPrefix<Commit>("commits", prepareTable("commits", kCommitColumns, "id"), commitRow);
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
            const bool ordered = !kept ||
                (c.inputRows >= kept->inputRows && c.frameRows >= kept->frameRows && c.eventRows >= kept->eventRows);
            if (!ordered) {
                stop("commits", "commit " + std::to_string(c.id) + " counts fewer rows than the one before");
                break;
            }
            if (c.inputRows > rowCount(inputs) || c.frameRows > rowCount(frames) || c.eventRows > rowCount(events)) {
                stop(c.inputRows > rowCount(inputs)       ? "input"
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
            const bool chained = version_ >= kSessionIdSince;
            const std::optional<std::int64_t> previous =
                chained ? std::optional<std::int64_t>(kept ? kept->checksum : headerChecksum_) : std::nullopt;
            if (sum.value(previous) != c.checksum) {
                stop("commits", "the rows of commit " + std::to_string(c.id) + " do not match its checksum");
                break;
            }
            kept = c;
            keptIndex = i + 1;
        }
        const Commit last = kept.value_or(Commit{});
        if (rowCount(inputs) > last.inputRows || rowCount(frames) > last.frameRows || rowCount(events) > last.eventRows)
            stop("commits", "rows after the last readable commit");
        inputs.resize(static_cast<std::size_t>(last.inputRows));
        frames.resize(static_cast<std::size_t>(last.frameRows));
        events.resize(static_cast<std::size_t>(last.eventRows));
        data.inputs = toRecords(std::move(inputs));
        data.frames = toRecords(std::move(frames));
        data.events = toRecords(std::move(events));

        const std::string lastFrame = last.lastFrame ? std::to_string(*last.lastFrame) : std::string("(none)");
        stopAtWalLoss();
        if (firstStop_) {
            data.completed = false;
            data.damaged = true;
            data.note = "damaged (" + firstStop_->where + ": " + firstStop_->why + "): " +
                (keptIndex == 0
                     ? std::string("no complete commit survives")
                     : "kept the first " + std::to_string(keptIndex) + " commits, ending after frame " + lastFrame) +
                lostText(commits, keptIndex);
        } else if (!data.completed) {
            data.note = keptIndex == 0 ? std::string("incomplete: no trial was committed")
                                       : "incomplete: ends after frame " + lastFrame + " (last commit, " +
                    std::to_string(keptIndex) + " in all)";
        }
    }

    // The largest key of a table keyed by frame, found through its b-tree without reading the
    // rows before it: the frame of the row committed last. nullopt for an empty table, or where
    // it cannot be read (the stop says why).
    template <typename Row>
    std::optional<std::int64_t> lastKey(const Table<Row>& table) {
        Stmt s = prepareSelect(std::string("SELECT max(") + table.key() + ") FROM " + table.name);
        std::optional<std::int64_t> key;
        if (sqlite3_step(s.get()) != SQLITE_ROW)
            stop(table.name, errmsg());
        else if (!optionalInteger(s.get(), 0, key))
            stop(table.name, "its last row has a value of the wrong type");
        return key;
    }

    // The outline of a file laid out as `layout`: its last commit, found by its key, against
    // the last keys of the input and frames tables (each a b-tree walked from the top) and
    // the events, read whole as readTables reads them. What the commits count and the tables
    // hold must meet exactly, as in a session whose commits all verify.
    template <typename InputRow, typename FrameRow, typename EventRow>
    void outlineTables(SessionOutline& out, const Layout<InputRow, FrameRow, EventRow>& layout) {
        std::optional<Commit> last;
        {
            Stmt s = prepareSelect(std::string("SELECT ") + kCommitColumns + " FROM commits ORDER BY id DESC LIMIT 1");
            Commit c;
            const int rc = sqlite3_step(s.get());
            if (rc == SQLITE_ROW && commitRow(s.get(), c))
                last = c;
            else if (rc == SQLITE_ROW)
                stop("commits", "its last row has a value of the wrong type");
            else if (rc != SQLITE_DONE)
                stop("commits", errmsg());
        }
        const std::optional<std::int64_t> lastInput = lastKey(layout.input), lastFramed = lastKey(layout.frames);
        auto events = readRows(layout.events);
        const Commit c = last.value_or(Commit{});
        const auto eventCount = static_cast<std::int64_t>(events.size());
        const std::optional<std::int64_t> lastRow = std::max(lastInput, lastFramed);  // nullopt is least
        const std::string missing = "rows of commit " + std::to_string(c.id) + " are missing";
        if (c.inputRows > 0 && !lastInput)
            stop("input", missing);
        else if (c.frameRows > 0 && !lastFramed)
            stop("frames", missing);
        else if (lastRow < c.lastFrame)
            stop(lastInput <= lastFramed ? "input" : "frames", missing);
        else if (eventCount < c.eventRows)
            stop("events", missing);
        else if (lastRow > c.lastFrame || eventCount > c.eventRows || (c.inputRows == 0 && lastInput) ||
                 (c.frameRows == 0 && lastFramed))
            stop("commits", "rows after the last readable commit");
        events.resize(static_cast<std::size_t>(std::min(eventCount, c.eventRows)));
        out.events = toRecords(std::move(events));
        out.commits = c.id;
        out.inputRows = c.inputRows;
        out.frameRows = c.frameRows;

        const std::string lastFrame = c.lastFrame ? std::to_string(*c.lastFrame) : std::string("(none)");
        stopAtWalLoss();
        if (firstStop_) {
            out.completed = false;
            out.damaged = true;
            out.note = "damaged (" + firstStop_->where + ": " + firstStop_->why + "): " +
                (last ? "its last commit, " + std::to_string(c.id) + ", ends after frame " + lastFrame
                      : std::string("no commit can be read")) +
                lostText({}, 0);
        } else if (!out.completed) {
            out.note = !last
                ? std::string("incomplete: no trial was committed")
                : "incomplete: ends after frame " + lastFrame + " (last commit, " + std::to_string(c.id) + " in all)";
        }
    }

    // What damage cost, as far as the file still tells: the commits the commits table lists
    // past the last one kept, and those the -wal holds past its damage.
    std::string lostText(const std::vector<Commit>& commits, std::size_t kept) const {
        std::vector<std::string> parts;
        if (commits.size() > kept) {
            const std::int64_t keptEvents = kept == 0 ? 0 : commits[kept - 1].eventRows;
            parts.push_back((commits.size() == kept + 1
                                 ? "commit " + std::to_string(kept + 1)
                                 : "commits " + std::to_string(kept + 1) + " to " + std::to_string(commits.size())) +
                            " (" + std::to_string(std::max<std::int64_t>(0, commits.back().eventRows - keptEvents)) +
                            " events)");
        }
        if (walLoss_)
            parts.push_back(walLoss_->commits == 0 ? std::string("everything in the write-ahead log")
                                                   : std::to_string(walLoss_->commits) +
                                    (walLoss_->commits == 1 ? " commit" : " commits") + " in the write-ahead log");
        if (parts.empty()) return "";
        return "; lost " + parts[0] + (parts.size() > 1 ? " and " + parts[1] : "");
    }
};

}  // namespace

SessionData readSession(const std::string& path) { return Reader(path).read(); }

SessionHeader readSessionHeader(const std::string& path) { return Reader(path).header(); }

SessionOutline readSessionOutline(const std::string& path) { return Reader(path).outline(); }

}  // namespace warplab::session
