#include "naming.h"

#include <filesystem>
#include <system_error>

namespace warplab::session::detail {

namespace fs = std::filesystem;

std::string safeName(const std::string& raw, std::size_t maxBytes) {
    std::string out;
    for (const char c : raw) {
        const bool ok =
            (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
        if (ok)
            out += c;
        else if (out.empty() || out.back() != '_')
            out += '_';
        if (out.size() >= maxBytes) break;
    }
    if (!out.empty() && out.front() == '-') out.front() = '_';
    return out;
}

std::string timeForName(const std::string& iso) {
    std::string out;
    for (const char c : iso)
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) out += c;
    return out.substr(0, 32);
}

bool anyExists(const std::string& path) {
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"})
        if (fs::exists(fs::symlink_status(path + suffix, ec))) return true;
    return false;
}

void removeSessionFiles(const std::string& path) {
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(path + suffix, ec);
}

}  // namespace warplab::session::detail
