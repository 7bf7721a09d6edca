// Private to session/: the names session files get in the results folder, and the files
// SQLite keeps beside them.
#pragma once

#include <cstddef>
#include <string>

namespace warplab::session::detail {

inline constexpr const char* kExtension = ".warplab-session";
inline constexpr std::size_t kMaxNameBytes = 64;

// Only [A-Za-z0-9_-] reach the file system; every run of anything else becomes one '_'.
// The id cannot then name a folder ('/' and '.' are gone), so it cannot be "." or "..", and
// a leading '-' is replaced too so the file name never reads as a command-line option.
std::string safeName(const std::string& raw, std::size_t maxBytes);
std::string timeForName(const std::string& iso);
// Throws SessionError naming the folder when it is missing, not a folder, not writable, or
// marked read-only for everyone (root included); creates nothing.
void checkResultsFolder(const std::string& resultsDir);
bool anyExists(const std::string& path);
void removeSessionFiles(const std::string& path);

// A writer builds each session file it writes in a hidden ".<stem>.<pid>.<work>" file beside
// the session and only then gives it the session's name: when it creates the session, saves it
// again after another program replaced or overwrote it, or writes a finished session whole.
inline constexpr const char* kCreating = "creating";
inline constexpr const char* kRescuing = "rescuing";
inline constexpr const char* kFinishing = "finishing";
inline constexpr const char* kHiddenWork[] = {kCreating, kRescuing, kFinishing};
std::string hiddenWorkPath(const std::string& resultsDir, const std::string& stem, const char* work);

// The hidden files (and SQLite's beside them) that a run killed before it gave one its name
// left in resultsDir: those of processes no longer running, untouched for at least a minute
// (another rig on a shared folder may be creating one under a pid this machine does not
// know). The others are left alone.
void removeAbandonedCreations(const std::string& resultsDir);

}  // namespace warplab::session::detail
