// SessionWriter on the sqlite3 C API: the tables it writes are schema.h's.
#include "session/session_store.h"

#include "session/records.h"

#include "checksum.h"
#include "naming.h"
#include "schema.h"
#include "sqlite_handles.h"

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace warplab::session {
namespace {

namespace fs = std::filesystem;

// The store's shared pieces (sqlite_handles.h, schema.h, checksum.h, naming.h, v1_format.h, wal_scan.h).
using namespace detail;

std::string utcNow() {
    using namespace std::chrono;
    const auto now = system_clock::now();
    const std::time_t seconds = system_clock::to_time_t(now);
    const auto millis = duration_cast<milliseconds>(now.time_since_epoch()).count() % 1000;
    std::tm tm{};
    gmtime_r(&seconds, &tm);
    char text[96];  // room for any int the format could meet, so no truncation warning
    std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1,
                  tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(millis));
    return text;
}

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
    bool writing = false;  // inside writeHeld(): a busy lock is LockBusy, not a failure
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
            while (!writeHeld() && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        } catch (...) {}
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw SessionError("Cannot write session file " + path + " (" + what + "): " + sqlite3_errmsg(db.get()) + ".");
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
        if (sqlite3_prepare_v3(db.get(), sql.c_str(), -1, SQLITE_PREPARE_PERSISTENT, &raw, nullptr) != SQLITE_OK)
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
    void insert(const Table<R>& table, sqlite3_stmt* s, const R& r, std::int64_t id, const char* what) {
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
                bindOptional(s, 5, h.eventRows > 0 ? std::optional<std::int64_t>(h.eventRows) : std::nullopt);
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
            if (!sqlite3_get_autocommit(db.get())) sqlite3_exec(db.get(), "ROLLBACK", nullptr, nullptr, nullptr);
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
        const std::string what = fileMoved ? "the session file " + path + " was deleted or replaced by another program"
                                           : "the log " + path + "-wal was deleted or replaced by another program";
        close();
        path = savedTo;
        openForWriting();
        const std::string text = what + "; every commit up to then is saved in " + path;
        notices.push_back(text);
        heldFlags[fileMoved ? "file_replaced" : "wal_replaced"] = text;
        writeHeld();  // the flag; if the lock is taken now, it goes with the next commit
    }

    static void checkFollows(const std::optional<std::int64_t>& last, std::int64_t frame, const char* caller) {
        if (last && frame <= *last)
            throw std::invalid_argument(std::string("SessionWriter::") + caller + ": frame " + std::to_string(frame) +
                                        " does not follow frame " + std::to_string(*last) + ".");
    }

    template <typename R>
    static void checkJson(const Table<R>& table, const R& r, const char* caller) {
        for (const Field<R>& field : table.fields) {
            if (field.storage != Storage::JsonObject) continue;
            const std::string& text = r.*std::get<std::string R::*>(field.member);
            if (!isJsonObjectOrEmpty(text))
                throw std::invalid_argument(std::string("SessionWriter::") + caller + ": " + field.column +
                                            " must be a JSON object or empty, not '" + text.substr(0, 80) + "'.");
        }
    }

    void checkOpen(const char* caller) const {
        if (finished)
            throw std::logic_error(std::string("SessionWriter::") + caller + ": the session is already finished.");
    }

    // Retries writeHeld() until it gets the lock, telling `waiting` about once a second.
    void waitForWrite(const WaitCallback& waiting) {
        const auto start = Clock::now();
        auto nextCall = start + std::chrono::seconds(1);
        while (!writeHeld()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            if (waiting && Clock::now() >= nextCall) {
                waiting(std::chrono::duration<double>(Clock::now() - start).count(), WaitingFor::WriteLock);
                nextCall += std::chrono::seconds(1);
            }
        }
    }

    // Whether every frame of the -wal is now in the file: a checkpoint copies what no
    // reader's snapshot still needs from the file; a reader in a transaction since before the
    // last commits holds those back.
    bool foldedIntoFile() {
        int logFrames = -1, copied = -1;
        const int rc = sqlite3_wal_checkpoint_v2(db.get(), nullptr, SQLITE_CHECKPOINT_PASSIVE, &logFrames, &copied);
        return rc == SQLITE_OK && copied == logFrames;
    }
};

SessionWriter::SessionWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SessionWriter::SessionWriter(SessionWriter&&) noexcept = default;
SessionWriter& SessionWriter::operator=(SessionWriter&&) noexcept = default;

SessionWriter::~SessionWriter() = default;

SessionWriter::Impl& SessionWriter::impl(const char* caller) const {
    if (!impl_) throw std::logic_error(std::string("SessionWriter::") + caller + ": this writer was moved from.");
    return *impl_;
}

const std::string& SessionWriter::path() const { return impl("path").path; }

SessionWriter SessionWriter::create(const std::string& resultsDir, const SessionHeader& header) {
    if (header.formatVersion != kSessionFormatVersion)
        throw std::invalid_argument("SessionWriter::create: header.formatVersion is " +
                                    std::to_string(header.formatVersion) + " but this warplab writes format version " +
                                    std::to_string(kSessionFormatVersion) + ".");

    // Everything that can be checked is checked before the first file exists, so a bad
    // results folder leaves no litter behind.
    std::error_code ec;
    const auto status = fs::status(resultsDir, ec);
    if (resultsDir.empty() || !fs::exists(status))
        throw SessionError("Results folder '" + resultsDir + "' does not exist.");
    if (!fs::is_directory(status)) throw SessionError("Results folder '" + resultsDir + "' is not a folder.");
    if (::access(resultsDir.c_str(), W_OK | X_OK) != 0)
        throw SessionError("Results folder '" + resultsDir + "' is not writable (" + std::strerror(errno) + ").");

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
    removeAbandonedCreations(resultsDir);  // and those of killed runs that are gone
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
            impl->exec(("PRAGMA application_id=" + std::to_string(kApplicationId)).c_str(), "writing the header");
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
    return w.heldSince ? std::chrono::duration<double>(Impl::Clock::now() - *w.heldSince).count() : 0.0;
}

void SessionWriter::flush(const WaitCallback& waiting) { impl("flush").waitForWrite(waiting); }

std::vector<std::string> SessionWriter::takeNotices() { return std::exchange(impl("takeNotices").notices, {}); }

void SessionWriter::flag(const std::string& name, const std::string& text) {
    Impl& w = impl("flag");
    w.checkOpen("flag");
    w.addingFlags[name] = text;
}

void SessionWriter::finish(const WaitCallback& waiting, double foldWaitS) {
    Impl& w = impl("finish");
    w.checkOpen("finish");
    w.commitAdded();
    w.completing = true;
    w.waitForWrite(waiting);
    w.finished = true;
    // A finished session becomes one self-contained file, so it can be copied, archived or
    // read from read-only media: every commit folded into it before the run says it is done.
    const auto start = Impl::Clock::now();
    auto nextCall = start + std::chrono::seconds(1);
    while (!w.foldedIntoFile()) {
        const double waited = std::chrono::duration<double>(Impl::Clock::now() - start).count();
        if (waited >= foldWaitS)
            throw SessionError("The session finished, but its last commits are still only in '" + w.path +
                               "-wal': another program (export, replay, a DB browser, a sqlite3 script) has held a "
                               "read transaction on it for " +
                               std::to_string(static_cast<long>(waited)) +
                               " s. Keep and copy the two files together until it is folded in: the file alone is not "
                               "the whole session.");
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        if (waiting && Impl::Clock::now() >= nextCall) {
            waiting(waited, WaitingFor::Readers);
            nextCall += std::chrono::seconds(1);
        }
    }
    // The -wal, now redundant, goes where no other program has the file open (a reader that
    // does keeps WAL mode, which is just as valid: the file alone is whole).
    sqlite3_exec(w.db.get(), "PRAGMA journal_mode=DELETE", nullptr, nullptr, nullptr);
}

}  // namespace warplab::session
