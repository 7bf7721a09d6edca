#include "file_stamp.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace warplab::session::detail {

std::string FileStamp::changeFrom(const FileStamp& before) const {
    if (size != before.size)
        return "its size went from " + std::to_string(before.size) + " to " + std::to_string(size) + " bytes";
    if (head != before.head) return "its SQLite header changed";
    return "it was written to, its size unchanged";
}

std::optional<FileStamp> stampOf(const std::string& path, bool withHead) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return std::nullopt;
    FileStamp s{st.st_dev, st.st_ino, st.st_size,
                static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec, ""};
    if (withHead) {
        const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd >= 0) {
            char head[100];
            const ssize_t n = ::pread(fd, head, sizeof head, 0);
            if (n > 0) s.head.assign(head, static_cast<std::size_t>(n));
            ::close(fd);
        }
    }
    return s;
}

// Makes a rename or link in `dir` durable.
void syncFolder(const std::string& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace warplab::session::detail
