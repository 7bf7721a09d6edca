// Private to session/: one SQLite connection to a session file the writer writes, with its
// prepared inserts (SessionWriter, writer.cpp, keeps one for the file and may open others to
// write the session again whole).
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

#include "archive.h"
#include "schema.h"
#include "session/records.h"
#include "session/session_store.h"
#include "sqlite_handles.h"

namespace warplab::session::detail {

// Thrown inside a write while another connection holds the file's write lock: the write is
// rolled back and everything it would have written stays held for the next try.
struct LockBusy {};

inline bool isBusy(int rc) { return (rc & 0xff) == SQLITE_BUSY || (rc & 0xff) == SQLITE_LOCKED; }

// One SQLite connection to a session file the writer writes, with its statements.
struct Connection {
    std::string path;
    Db db;
    Stmt insertInput, insertFrame, insertEvent, insertCommit, insertMeta;
    bool writing = false;  // inside a write of held commits: a busy lock is LockBusy, not a failure

    // The last failure, as "<what>: <SQLite's message>", for the writer to say what it saw.
    mutable std::string failure;

    [[noreturn]] void fail(const std::string& what) const {
        const std::string message = sqlite3_errmsg(db.get());
        failure = what + ": " + message;
        throw SessionError("Cannot write session file " + path + " (" + what + "): " + message + ".");
    }
    void check(int rc, const char* what) const {
        if (writing && isBusy(rc)) throw LockBusy{};
        fail(what);
    }
    void open(int flags, const char* what) {
        sqlite3* raw = nullptr;
        const int rc = sqlite3_open_v2(path.c_str(), &raw, flags, nullptr);
        db.reset(raw);
        if (rc != SQLITE_OK) fail(what);
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
    void prepareInserts() {
        insertMeta = prepare("INSERT OR REPLACE INTO meta (key, value) VALUES (?, ?)");
        insertInput = prepare(insertSql(inputTable()));
        insertFrame = prepare(insertSql(frameTable()));
        insertEvent = prepare(insertSql(eventTable()));
        insertCommit = prepare(
            "INSERT INTO commits (input_rows, frame_rows, event_rows, last_frame, "
            "last_event_id, checksum, committed_at) VALUES (?, ?, ?, ?, ?, ?, ?)");
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

    // One commit's rows and its `commits` row, inside the caller's transaction.
    void writeCommit(const CommitRows& h) {
        for (const InputRecord& r : h.inputs) insert(inputTable(), insertInput.get(), r, 0, "adding an input record");
        for (const FrameRecord& r : h.frames) insert(frameTable(), insertFrame.get(), r, 0, "adding a frame record");
        std::int64_t id = h.eventRows - static_cast<std::int64_t>(h.events.size());
        for (const EventRecord& r : h.events)
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

    void close() {
        insertInput.reset();
        insertFrame.reset();
        insertEvent.reset();
        insertCommit.reset();
        insertMeta.reset();
        db.reset();
    }
};

}  // namespace warplab::session::detail
