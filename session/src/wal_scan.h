// Private to session/: the reader's check of a -wal for committed data SQLite would drop.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace warplab::session::detail {

// What SQLite will not read back from a session's -wal. SQLite checks each log frame against
// a running checksum and silently stops at the first one that fails (or does not belong to
// the log), dropping every later commit with it. A kill never leaves that: what it cuts off
// has no commit frame after it. So a commit frame of this log after the stop is committed
// data lost to damage. The format is SQLite's (https://sqlite.org/fileformat2.html#walformat).
struct WalLoss {
    std::int64_t byte = 0;  // where the header or frame that fails starts
    int commits = 0;  // commit frames of this log after it (0: the header itself failed)
};

// A running writer may be half-way through a frame when we look; damage stays put. So a loss
// counts only when two looks a moment apart agree.
std::optional<WalLoss> lostInWal(const std::string& walPath);

}  // namespace warplab::session::detail
