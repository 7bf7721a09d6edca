// Private to session/: the commits a writer makes, and its archive of every one it has written.
#pragma once

#include "session/session_store.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace warplab::session::detail {

// One commit as the writer makes it: its rows and what its `commits` row records.
struct CommitRows {
    std::vector<InputRecord> inputs;
    std::vector<FrameRecord> frames;
    std::vector<EventRecord> events;
    std::int64_t inputRows = 0, frameRows = 0, eventRows = 0;  // cumulative, after it
    std::optional<std::int64_t> lastFrame;
    std::int64_t checksum = 0;
    std::string committedAt;
};

// Every commit written, kept by the writer for as long as the session runs, so that it can
// write the whole session again when the file it wrote is no longer trustworthy: replaced,
// deleted, or overwritten in place (an old copy put back, truncated, another file copied over
// it). SQLite cannot do that from its own connection: the pages it did not cache are gone
// with the file. Stored serialised (integers and doubles as 8 bytes, texts as length and
// bytes, as the checksums hash them), about the session file's own size.
class Archive {
public:
    void append(const CommitRows& commit);
    // Calls f for each commit, oldest first.
    void forEach(const std::function<void(const CommitRows&)>& f) const;
    std::size_t commits() const { return commits_; }

private:
    std::string bytes_;
    std::size_t commits_ = 0;
};

}  // namespace warplab::session::detail
