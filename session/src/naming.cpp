#include "naming.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <system_error>

#include <unistd.h>

#include "session/session_store.h"

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

void checkResultsFolder(const std::string& resultsDir) {
    std::error_code ec;
    const auto status = fs::status(resultsDir, ec);
    if (resultsDir.empty() || !fs::exists(status))
        throw SessionError("Results folder '" + resultsDir + "' does not exist.");
    if (!fs::is_directory(status)) throw SessionError("Results folder '" + resultsDir + "' is not a folder.");
    if (::access(resultsDir.c_str(), W_OK | X_OK) != 0)
        throw SessionError("Results folder '" + resultsDir + "' is not writable (" + std::strerror(errno) + ").");
    // root passes access() on any folder; a folder with no write permission for anyone is
    // one a lab has marked read-only (an archived study), and stays so.
    if ((status.permissions() & (fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write)) ==
        fs::perms::none)
        throw SessionError("Results folder '" + resultsDir +
                           "' is read-only (no write permission for anyone); warplab writes no session into it.");
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

std::string hiddenWorkPath(const std::string& resultsDir, const std::string& stem, const char* work) {
    return (fs::path(resultsDir) / ("." + stem + "." + std::to_string(::getpid()) + "." + work)).string();
}

namespace {

// "<name>" without ".<work>" when it ends so, else "".
std::string withoutWork(const std::string& name) {
    for (const char* work : kHiddenWork) {
        const std::string suffix = std::string(".") + work;
        if (name.size() > suffix.size() + 1 && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
            return name.substr(0, name.size() - suffix.size());
    }
    return "";
}

}  // namespace

void removeAbandonedCreations(const std::string& resultsDir) {
    std::error_code ec;
    for (fs::directory_iterator it(resultsDir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const std::string rest = withoutWork(name);
        if (name[0] != '.' || rest.empty()) continue;
        const std::size_t dot = rest.rfind('.');
        if (dot == std::string::npos || dot == 0) continue;
        const std::string digits = rest.substr(dot + 1);
        if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
            continue;
        const auto pid = static_cast<pid_t>(std::stol(digits));
        if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // running, or not ours to judge
        std::error_code timeEc;
        const auto age = fs::file_time_type::clock::now() - fs::last_write_time(it->path(), timeEc);
        if (timeEc || age < std::chrono::minutes(1)) continue;
        removeSessionFiles(it->path().string());
    }
}

}  // namespace warplab::session::detail

namespace warplab::session {

std::string playerKind(const std::string& player) {
    const auto named = [&](const char* name) {
        const std::string n = name;
        return player == n || player.rfind(n + ":", 0) == 0 || player.rfind(n + " (", 0) == 0;
    };
    if (named("human")) return "human";
    if (named("bot")) return "bot";
    if (named("sim")) return "simulated";
    if (named("replay")) return "replay";
    return "";
}

std::string utcNow() {
    using namespace std::chrono;
    const auto now = system_clock::now();
    const std::time_t seconds = system_clock::to_time_t(now);
    const auto millis = duration_cast<milliseconds>(now.time_since_epoch()).count() % 1000;
    std::tm tm{};
    gmtime_r(&seconds, &tm);
    char text[96];  // room for any int the format could meet, so no truncation warning
    std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1,
                  tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(millis));
    return text;
}

}  // namespace warplab::session
