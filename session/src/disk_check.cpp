#include "disk_check.h"

#include "checksum.h"

#include <sys/stat.h>

#include <limits>

namespace warplab::session::detail {
namespace {

// One stored row hashed as hashRow hashes the record it was written from: a value of another
// storage class than its column's (damage SQLite cannot see) makes the row differ.
template <typename R>
bool hashStored(Checksum& c, const Table<R>& table, sqlite3_stmt* s) {
    int i = table.numbered ? 1 : 0;
    for (const Field<R>& field : table.fields) {
        const int type = sqlite3_column_type(s, i);
        switch (field.storage) {
            case Storage::Integer:
                if (type != SQLITE_INTEGER) return false;
                c.i64(sqlite3_column_int64(s, i));
                break;
            case Storage::Real:
                if (type != SQLITE_FLOAT && type != SQLITE_NULL) return false;
                c.f64(type == SQLITE_NULL ? std::numeric_limits<double>::quiet_NaN() : sqlite3_column_double(s, i));
                break;
            case Storage::Text:
            case Storage::JsonObject:
                if (type != SQLITE_TEXT) return false;
                c.text(columnText(s, i));
                break;
        }
        ++i;
    }
    return true;
}

}  // namespace

DiskCheck::DiskCheck(const std::string& path, bool fileAlone) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        seen_ = "it is gone";
        return;
    }
    if (st.st_size == 0) {
        seen_ = "it is empty (0 bytes)";
        return;
    }
    sqlite3* raw = nullptr;
    const std::string name = fileAlone ? immutableUri(path) : path;
    const int rc =
        sqlite3_open_v2(name.c_str(), &raw, SQLITE_OPEN_READONLY | (fileAlone ? SQLITE_OPEN_URI : 0), nullptr);
    db_.reset(raw);
    // Only this process writes the file, and not while it checks: a lock met here is another
    // program's, and says nothing about what the file holds, so wait for it a little.
    if (rc == SQLITE_OK) sqlite3_busy_timeout(db_.get(), 2000);
    if (rc != SQLITE_OK || sqlite3_exec(db_.get(), "BEGIN", nullptr, nullptr, nullptr) != SQLITE_OK) unreadable();
}

Stmt DiskCheck::prepare(const std::string& sql) {
    sqlite3_stmt* raw = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &raw, nullptr) != SQLITE_OK) unreadable();
    return Stmt(raw);
}

Stmt& DiskCheck::statement(Stmt& s, const std::string& sql) {
    if (!s) s = prepare(sql);
    return s;
}

void DiskCheck::unreadable() {
    if (!seen_.empty()) return;
    seen_ = std::string("it cannot be read (") + (db_ ? sqlite3_errmsg(db_.get()) : "out of memory") + ")";
}

std::optional<std::int64_t> DiskCheck::single(const std::string& sql) {
    Stmt s = prepare(sql);
    if (!s) return std::nullopt;
    const int rc = sqlite3_step(s.get());
    if (rc != SQLITE_ROW) {
        unreadable();
        return std::nullopt;
    }
    return sqlite3_column_type(s.get(), 0) == SQLITE_INTEGER ? sqlite3_column_int64(s.get(), 0) : 0;
}

void DiskCheck::metaEntry(const std::string& key, const std::string& value) {
    if (!seen_.empty()) return;
    Stmt s = prepare("SELECT value FROM meta WHERE key = ?");
    if (!s) return;
    bindArg(s.get(), 1, key);
    const int rc = sqlite3_step(s.get());
    if (rc == SQLITE_ROW && sqlite3_column_type(s.get(), 0) == SQLITE_TEXT && columnText(s.get(), 0) == value) return;
    if (rc != SQLITE_ROW && rc != SQLITE_DONE) return unreadable();
    seen_ = "its header is not the one written (meta '" + key + "' " +
        (rc == SQLITE_DONE ? std::string("is missing") : "differs") + ")";
}

void DiskCheck::metaExactly(const std::map<std::string, std::string>& entries) {
    if (!seen_.empty()) return;
    Stmt s = prepare("SELECT key, value FROM meta ORDER BY key");
    if (!s) return;
    std::map<std::string, std::string> stored;
    int rc;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) stored[columnText(s.get(), 0)] = columnText(s.get(), 1);
    if (rc != SQLITE_DONE) return unreadable();
    for (const auto& [key, value] : entries) {
        const auto it = stored.find(key);
        if (it == stored.end() || it->second != value) {
            seen_ = "its meta table is not the one written ('" + key + "' " +
                (it == stored.end() ? "is missing" : "differs") + ")";
            return;
        }
    }
    for (const auto& [key, value] : stored)
        if (entries.count(key) == 0) {
            seen_ = "its meta table holds '" + key + "', which was never written";
            return;
        }
}

void DiskCheck::commit(std::int64_t id, const CommitRows& c) {
    if (!seen_.empty()) return;
    Stmt& s = statement(
        commitRow_,
        "SELECT input_rows, frame_rows, event_rows, last_frame, last_event_id, checksum FROM commits WHERE id = ?");
    if (!s) return;
    sqlite3_reset(s.get());
    bindArg(s.get(), 1, id);
    const int rc = sqlite3_step(s.get());
    if (rc == SQLITE_DONE) {
        seen_ = "commit " + std::to_string(id) + " is missing from it";
        return;
    }
    if (rc != SQLITE_ROW) return unreadable();
    // NULL where the writer had none (no frame yet, no event yet).
    const auto holds = [&](int i, bool has, std::int64_t value) {
        return sqlite3_column_type(s.get(), i) == SQLITE_NULL ? !has : has && sqlite3_column_int64(s.get(), i) == value;
    };
    if (!holds(0, true, c.inputRows) || !holds(1, true, c.frameRows) || !holds(2, true, c.eventRows) ||
        !holds(3, c.lastFrame.has_value(), c.lastFrame.value_or(0)) || !holds(4, c.eventRows > 0, c.eventRows) ||
        !holds(5, true, c.checksum)) {
        seen_ = "its record of commit " + std::to_string(id) + " is not the one written";
        return;
    }
    sqlite3_reset(s.get());
    if (!c.inputs.empty()) rows(inputRows_, inputTable(), id, c.inputs, c.inputs.front().frame, c.inputs.back().frame);
    if (!c.frames.empty()) rows(frameRows_, frameTable(), id, c.frames, c.frames.front().frame, c.frames.back().frame);
    const auto events = static_cast<std::int64_t>(c.events.size());
    if (events > 0) rows(eventRows_, eventTable(), id, c.events, c.eventRows - events + 1, c.eventRows);
}

template <typename R>
void DiskCheck::rows(Stmt& s, const Table<R>& table, std::int64_t commitId, const std::vector<R>& written,
                     std::int64_t firstKey, std::int64_t lastKey) {
    if (!seen_.empty()) return;
    statement(s,
              "SELECT " + table.columns() + " FROM " + table.name + " WHERE " + table.key() +
                  " BETWEEN ? AND ? ORDER BY " + table.key());
    if (!s) return;
    sqlite3_reset(s.get());
    bindArg(s.get(), 1, firstKey);
    bindArg(s.get(), 2, lastKey);
    Checksum stored, expected;
    for (const R& r : written) hashRow(expected, table, r);
    std::int64_t n = 0;
    bool typed = true;
    int rc;
    while ((rc = sqlite3_step(s.get())) == SQLITE_ROW) {
        ++n;
        typed = typed && hashStored(stored, table, s.get());
    }
    if (rc != SQLITE_DONE) return unreadable();
    const std::string what = std::string(table.name) + " rows of commit " + std::to_string(commitId);
    if (n != static_cast<std::int64_t>(written.size()))
        seen_ = "it holds " + std::to_string(n) + " of the " + std::to_string(written.size()) + " " + what;
    else if (!typed || stored.value() != expected.value())
        seen_ = "the " + what + " differ from those written";
}

void DiskCheck::lastCommit(std::int64_t id) {
    if (!seen_.empty()) return;
    const auto last = single("SELECT max(id) FROM commits");
    if (!last || *last == id) return;
    seen_ = *last < id
        ? "its last commit is number " + std::to_string(*last) + ", not " + std::to_string(id) + " (an older copy?)"
        : "it holds commit " + std::to_string(*last) + ", which was never written";
}

void DiskCheck::rowCounts(std::int64_t inputs, std::int64_t frames, std::int64_t events) {
    const std::pair<const char*, std::int64_t> tables[] = {
        {inputTable().name, inputs}, {frameTable().name, frames}, {eventTable().name, events}};
    for (const auto& [name, expected] : tables) {
        if (!seen_.empty()) return;
        const auto n = single(std::string("SELECT count(*) FROM ") + name);
        if (n && *n != expected)
            seen_ = "its " + std::string(name) + " table holds " + std::to_string(*n) + " rows, not " +
                std::to_string(expected);
    }
}

}  // namespace warplab::session::detail
