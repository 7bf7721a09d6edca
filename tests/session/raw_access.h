// What the session tests do to a file from outside warplab's store: SQL run straight on it, the
// way another program might tamper with it, and the bytes this process has read, for tests that
// bound how much of a file a read touches.
#pragma once

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdint>
#include <fstream>
#include <string>

namespace warplab::session::testing {

inline void execSql(const std::string& path, const std::string& sql) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    char* error = nullptr;
    const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
    const std::string message = error ? error : "";
    sqlite3_free(error);
    sqlite3_close(db);
    ASSERT_EQ(rc, SQLITE_OK) << message;
}

// Bytes this process has read through read(2) and pread(2) (SQLite's unix VFS reads so).
inline std::uint64_t bytesRead() {
    std::ifstream io("/proc/self/io");
    std::string key;
    std::uint64_t value = 0;
    while (io >> key >> value)
        if (key == "rchar:") return value;
    ADD_FAILURE() << "/proc/self/io has no rchar";
    return 0;
}

}  // namespace warplab::session::testing
