#include "strict/file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace warplab::strict {
namespace {

// "" for a regular file, else what the path is instead.
std::string notRegular(const struct stat& st) {
    if (S_ISREG(st.st_mode)) return "";
    if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
    if (S_ISFIFO(st.st_mode)) return "is a FIFO (a named pipe), not a regular file";
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "is a device, not a regular file";
    if (S_ISSOCK(st.st_mode)) return "is a socket, not a regular file";
    return "is not a regular file";
}

std::string tooBig(std::size_t bytes, std::size_t maxBytes, const std::string& kind) {
    return "is " + std::to_string(bytes) + " bytes, more than a " + kind + " may be (" + std::to_string(maxBytes) + ")";
}

// Closes the descriptor on every way out.
class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

}  // namespace

void Source::fail(const std::string& where, const std::string& reason) const {
    const std::string sentence = kind + " '" + path + "': " + (where.empty() ? "" : where + " ") + reason;
    if (raise) raise(sentence);
    throw Error(sentence);
}

void Source::failAtLine(std::size_t line, const std::string& reason) const {
    const std::string sentence = kind + " '" + path + "' line " + std::to_string(line) + ": " + reason;
    if (raise) raise(sentence);
    throw Error(sentence);
}

FileText readRegularFile(const std::string& path, std::size_t maxBytes, const std::string& kind) {
    // stat before open, so that a FIFO or a device is never opened (opening a tape or a
    // terminal can do things); fstat after, for a path swapped in between.
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        return {"",
                errno == ENOENT || errno == ENOTDIR ? "no such file"
                                                    : std::string("cannot be read: ") + std::strerror(errno)};
    if (std::string problem = notRegular(st); !problem.empty()) return {"", problem};
    if (static_cast<unsigned long long>(st.st_size) > maxBytes)
        return {"", tooBig(static_cast<std::size_t>(st.st_size), maxBytes, kind)};
    // O_NONBLOCK: were it a FIFO after all, open would not wait for a writer.
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) return {"", std::string("cannot be opened for reading: ") + std::strerror(errno)};
    if (::fstat(fd.get(), &st) != 0) return {"", std::string("cannot be read: ") + std::strerror(errno)};
    if (std::string problem = notRegular(st); !problem.empty()) return {"", problem};
    // Read at most one byte past the limit: a file that grows, or one whose size stat does
    // not know (/proc), is still bounded.
    FileText out;
    char buffer[1 << 16];
    while (out.text.size() <= maxBytes) {
        const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return {"", std::string("cannot be read: ") + std::strerror(errno)};
        if (n == 0) return out;
        out.text.append(buffer, static_cast<std::size_t>(n));
    }
    return {"", "is more than the " + std::to_string(maxBytes) + " bytes a " + kind + " may be"};
}

std::string readFile(const Source& source) {
    FileText file = readRegularFile(source.path, source.maxBytes, source.kind);
    if (!file.problem.empty()) source.fail("", file.problem);
    return std::move(file.text);
}

}  // namespace warplab::strict
