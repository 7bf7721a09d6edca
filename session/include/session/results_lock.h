// One session per results folder at a time: the lock a run holds on its folder for the whole
// session (docs/session-format.md, "The lock file"). No GL.
#pragma once

#include <optional>
#include <string>

#include "session/session_store.h"

namespace warplab::session {

// The lock file's name inside the results folder. Export and replay read only session files,
// so they pass over it; study status reads it (readLockHolder) to tell a running session.
inline constexpr const char* kLockFileName = ".warplab-lock";

// Who holds a results folder, as its lock file says.
struct LockHolder {
    long pid = 0;
    std::string host, participant, protocol;
    std::string since;  // ISO 8601 UTC
};

// Another process holds the folder's lock: what() is one sentence naming the folder and the
// holder.
class ResultsFolderBusy : public SessionError {
public:
    ResultsFolderBusy(const std::string& folder, const LockHolder& holder, bool holderKnown);
    const LockHolder& holder() const { return holder_; }

private:
    LockHolder holder_;
};

// An exclusive flock(2) on RESULTS/.warplab-lock, held from construction to destruction; the
// file says who holds it. The kernel releases the lock when the process ends in any way
// (kill -9 and power cuts included), so a file left behind by one that died blocks no one.
// The file is removed on release. Move-only; inherited across fork() (the children of one
// run share its lock) but not across exec.
// The holder a results folder's lock file names, read without taking the lock (a reader must
// never make a run starting at that instant find the folder busy); nullopt when the folder has
// no lock file or it names no holder.
std::optional<LockHolder> readLockHolder(const std::string& resultsDir);

// Whether the holder's run may still be going: on this host (or a file naming none), whether
// its pid is alive (the kernel frees the lock of a run that died, but its file stays); on
// another host, which this one cannot see into, true, as the file says.
bool holderMayRun(const LockHolder& holder);

// "pid 4242 on booth-a, since 2024-05-01T09:30:00.000Z": who holds a lock, for a sentence.
std::string holderText(const LockHolder& holder);

class ResultsFolderLock {
public:
    // Takes the lock or throws, creating nothing but the lock file: ResultsFolderBusy when
    // another process (or another lock of this one) holds it, SessionError naming the folder
    // when it is missing, not a folder or not writable. Never waits.
    ResultsFolderLock(const std::string& resultsDir, const std::string& participant, const std::string& protocol);
    ResultsFolderLock(ResultsFolderLock&& other) noexcept;
    ResultsFolderLock& operator=(ResultsFolderLock&& other) noexcept;
    ResultsFolderLock(const ResultsFolderLock&) = delete;
    ResultsFolderLock& operator=(const ResultsFolderLock&) = delete;
    ~ResultsFolderLock();

    const std::string& path() const { return path_; }

private:
    void release() noexcept;
    std::string path_;
    int fd_ = -1;
};

}  // namespace warplab::session
