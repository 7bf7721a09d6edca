// Private to session/: whether a session file on disk still holds what its writer wrote.
#pragma once

#include "archive.h"
#include "schema.h"
#include "sqlite_handles.h"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace warplab::session::detail {

// The writer's stamps (device, inode, size, modification time, SQLite header) tell it when
// another program touched the file between two of its writes, but not what happened while it
// was writing: a file emptied, cut short or copied over during a commit's fsync, or during the
// checkpoint that folds the commit into the file, is stamped afresh as if the writer had left
// it so. SQLite itself checks nothing: it writes its pages into whatever the file now holds.
// So the writer reads the file back, as a reader would, and compares it with what it wrote,
// row for row (by the commits' checksum serialisation, checksum.h): cheaply after every commit
// (the header's checksum, the last commit and its rows), whole when the session ends.
//
// Each check records the first thing that differs, in words ("its last commit is number 12,
// not 44"); the later ones then do nothing.
class DiskCheck {
public:
    // `fileAlone`: the file's own bytes, without the -wal beside it (what a kill would leave
    // once every commit is folded in); otherwise as a reader sees it, through its -wal. Opens
    // read-only, in one read transaction, and writes nothing.
    DiskCheck(const std::string& path, bool fileAlone);

    // A meta entry holds `value`.
    void metaEntry(const std::string& key, const std::string& value);
    // The meta table holds exactly these entries.
    void metaExactly(const std::map<std::string, std::string>& entries);
    // Commit number `id` (1, 2, 3 ...) is as written: its `commits` row and its rows.
    void commit(std::int64_t id, const CommitRows& written);
    // The last commit is number `id` (0: none).
    void lastCommit(std::int64_t id);
    // The tables hold these many rows, no more.
    void rowCounts(std::int64_t inputs, std::int64_t frames, std::int64_t events);

    // "" while everything agrees; else what was seen, as a phrase about the file.
    const std::string& seen() const { return seen_; }

private:
    Stmt prepare(const std::string& sql);
    Stmt& statement(Stmt& s, const std::string& sql);  // prepared once, on first use
    void unreadable();
    std::optional<std::int64_t> single(const std::string& sql);
    template <typename R>
    void rows(Stmt& s, const Table<R>& table, std::int64_t commitId, const std::vector<R>& written,
              std::int64_t firstKey, std::int64_t lastKey);

    Db db_;
    Stmt commitRow_, inputRows_, frameRows_, eventRows_;
    std::string seen_;
};

}  // namespace warplab::session::detail
