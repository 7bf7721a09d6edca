// Private to session/: what the writer knows of the files it writes, to tell its own writes
// from another program's.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>

namespace warplab::session::detail {

// What a name means now, as far as telling our own writes from another program's goes: which
// file (device and inode), how long, when last written, and (for the session file) its
// 100-byte SQLite header. Nothing when the name is gone.
struct FileStamp {
    dev_t device = 0;
    ino_t inode = 0;
    off_t size = 0;
    std::int64_t modifiedNs = 0;
    std::string head;

    bool sameFile(const FileStamp& o) const { return device == o.device && inode == o.inode; }
    // What differs from `before`, the same file, as seen: a phrase.
    std::string changeFrom(const FileStamp& before) const;
    bool operator==(const FileStamp& o) const {
        return sameFile(o) && size == o.size && modifiedNs == o.modifiedNs && head == o.head;
    }
};

std::optional<FileStamp> stampOf(const std::string& path, bool withHead);

// Makes a rename or link in `dir` durable.
void syncFolder(const std::string& dir);

}  // namespace warplab::session::detail
