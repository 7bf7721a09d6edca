#include "session/results_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstring>
#include <filesystem>
#include <thread>
#include <utility>

#include <nlohmann/json.hpp>

#include "naming.h"

namespace warplab::session {

namespace {

namespace fs = std::filesystem;

std::string hostName() {
    char name[HOST_NAME_MAX + 1] = {};
    if (::gethostname(name, sizeof name - 1) != 0) return "";
    return name;
}

std::string holderJson(const LockHolder& h) {
    return nlohmann::json{{"pid", h.pid},
                          {"host", h.host},
                          {"participant", h.participant},
                          {"protocol", h.protocol},
                          {"since", h.since}}
               .dump() +
        "\n";
}

// The holder the file names; false while it names none yet (its holder has only just taken
// the lock) or when it is not one of ours.
bool readHolder(int fd, LockHolder& out) {
    std::string text;
    char buffer[4096];
    for (off_t at = 0; text.size() < 65536;) {
        const ssize_t n = ::pread(fd, buffer, sizeof buffer, at);
        if (n <= 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
        at += n;
    }
    const auto j = nlohmann::json::parse(text, nullptr, false);
    if (!j.is_object()) return false;
    const auto str = [&](const char* key) {
        const auto it = j.find(key);
        return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
    };
    const auto pid = j.find("pid");
    out.pid = pid != j.end() && pid->is_number_integer() ? pid->get<long>() : 0;
    out.host = str("host");
    out.participant = str("participant");
    out.protocol = str("protocol");
    out.since = str("since");
    return true;
}

std::string busyText(const std::string& folder, const LockHolder& h, bool known) {
    std::string text = "Results folder '" + folder + "' is in use by another warplab session";
    if (known) {
        text += " (participant " + h.participant + ", protocol " + h.protocol + ", pid " + std::to_string(h.pid) +
            (h.host.empty() ? "" : " on " + h.host) + ", since " + h.since + ")";
    }
    return text;
}

}  // namespace

std::optional<LockHolder> readLockHolder(const std::string& resultsDir) {
    const std::string path = (fs::path(resultsDir) / kLockFileName).string();
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (fd < 0) return std::nullopt;
    struct stat info {};
    LockHolder holder;
    const bool known = ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && readHolder(fd, holder) && holder.pid > 0;
    ::close(fd);
    return known ? std::optional<LockHolder>(holder) : std::nullopt;
}

bool holderMayRun(const LockHolder& holder) {
    if (!holder.host.empty() && holder.host != hostName()) return true;
    // EPERM: alive, another user's.
    return holder.pid > 0 && (::kill(static_cast<pid_t>(holder.pid), 0) == 0 || errno == EPERM);
}

std::string holderText(const LockHolder& holder) {
    return "pid " + std::to_string(holder.pid) + (holder.host.empty() ? "" : " on " + holder.host) + ", since " +
        holder.since;
}

ResultsFolderBusy::ResultsFolderBusy(const std::string& folder, const LockHolder& holder, bool holderKnown)
    : SessionError(busyText(folder, holder, holderKnown)), holder_(holder) {}

ResultsFolderLock::ResultsFolderLock(const std::string& resultsDir, const std::string& participant,
                                     const std::string& protocol)
    : path_((fs::path(resultsDir) / kLockFileName).string()) {
    detail::checkResultsFolder(resultsDir);
    // A holder removes the file while it still holds the lock, so a lock taken on a file that
    // no longer has the name (or whose name now belongs to another) is on nothing: try again.
    for (int attempt = 0;; ++attempt) {
        const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
        if (fd < 0)
            throw SessionError("Results folder '" + resultsDir + "' cannot be locked: " + path_ + ": " +
                               std::strerror(errno) + ".");
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int error = errno;
            if (error != EWOULDBLOCK) {
                ::close(fd);
                throw SessionError("Results folder '" + resultsDir + "' cannot be locked: " + path_ + ": " +
                                   std::strerror(error) + ".");
            }
            // Its holder writes the file just after it takes the lock: give it a moment.
            LockHolder holder;
            bool known = readHolder(fd, holder);
            for (int wait = 0; !known && wait < 50; ++wait) {
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
                known = readHolder(fd, holder);
            }
            ::close(fd);
            throw ResultsFolderBusy(resultsDir, holder, known);
        }
        struct stat held {
        }, named{};
        if (::fstat(fd, &held) == 0 && ::stat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
            held.st_dev == named.st_dev) {
            fd_ = fd;
            break;
        }
        ::close(fd);
        if (attempt >= 100)
            throw SessionError("Results folder '" + resultsDir + "' cannot be locked: " + path_ +
                               " keeps being replaced.");
    }
    LockHolder me;
    me.pid = static_cast<long>(::getpid());
    me.host = hostName();
    me.participant = participant;
    me.protocol = protocol;
    me.since = utcNow();
    const std::string text = holderJson(me);
    // A stale holder's text goes first; a failure to write only leaves the holder unnamed.
    if (::ftruncate(fd_, 0) == 0) {
        const ssize_t written = ::pwrite(fd_, text.data(), text.size(), 0);
        (void)written;
    }
}

ResultsFolderLock::ResultsFolderLock(ResultsFolderLock&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)) {}

ResultsFolderLock& ResultsFolderLock::operator=(ResultsFolderLock&& other) noexcept {
    if (this != &other) {
        release();
        path_ = std::move(other.path_);
        fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
}

ResultsFolderLock::~ResultsFolderLock() { release(); }

void ResultsFolderLock::release() noexcept {
    if (fd_ < 0) return;
    ::unlink(path_.c_str());  // while still held, so no one else's file is removed
    ::close(fd_);
    fd_ = -1;
}

}  // namespace warplab::session
