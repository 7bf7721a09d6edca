// Private to session/: owners for the sqlite3 handles and the parameter and column helpers
// the writer and the reader share.
#pragma once

#include <sqlite3.h>

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace warplab::session::detail {

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
inline void bindArg(sqlite3_stmt* s, int i, double v) { sqlite3_bind_double(s, i, v); }
inline void bindArg(sqlite3_stmt* s, int i, std::int64_t v) { sqlite3_bind_int64(s, i, v); }
inline void bindArg(sqlite3_stmt* s, int i, const std::string& v) {
    // Explicit length: ids and JSON may hold NUL bytes and must survive them.
    sqlite3_bind_text(s, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
}
inline void bindOptional(sqlite3_stmt* s, int i, const std::optional<std::int64_t>& v) {
    if (v)
        sqlite3_bind_int64(s, i, *v);
    else
        sqlite3_bind_null(s, i);
}

inline std::string columnText(sqlite3_stmt* s, int i) {
    const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(s, i));
    return text ? std::string(text, static_cast<std::size_t>(sqlite3_column_bytes(s, i))) : std::string();
}

// file:/abs/path?immutable=1, every byte outside [A-Za-z0-9/._~-] percent-encoded: opened so,
// SQLite reads the file's own bytes as they are, takes no lock, and neither looks for nor
// creates a -wal or -shm beside it.
inline std::string immutableUri(const std::string& path) {
    const std::string absolute = std::filesystem::absolute(path).lexically_normal().string();
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

}  // namespace warplab::session::detail
