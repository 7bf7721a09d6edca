// libFuzzer target: arbitrary bytes as a session file (docs/fuzzing.md).
//
// Each input is written to one regular file, <private temp folder>/input.warplab-session, and
// read with session::readSession. SessionError (one sentence naming the path) is the
// documented failure; anything else is a bug: another exception, a crash, a sanitizer report,
// a leak, a hang. Beyond not crashing, the reader keeps the promises session_store.h makes:
//   - a completed session is neither damaged nor annotated; an incomplete one says why;
//   - reading leaves the folder as it was (no -wal, -shm or -journal beside the file:
//     export reads results folders it must not change).
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <stdlib.h>  // mkdtemp

#include "session/session_store.h"

namespace {

namespace fs = std::filesystem;
using warplab::session::SessionData;

[[noreturn]] void bug(const char* what, const std::string& detail) {
    std::fprintf(stderr, "fuzz_session: %s\n%s\n", what, detail.c_str());
    std::abort();
}

// One private folder per process (libFuzzer's -jobs/-workers run several), removed at exit.
// A crashing process leaves its folder behind: scripts/fuzz.sh points TMPDIR at its scratch
// folder so such folders go with it.
class Scratch {
public:
    Scratch() {
        std::string pattern = (fs::temp_directory_path() / "warplab-fuzz-session-XXXXXX").string();
        if (mkdtemp(pattern.data()) == nullptr)
            bug("cannot make a temporary folder:", pattern + ": " + std::strerror(errno));
        dir_ = pattern;
        file_ = dir_ / "input.warplab-session";
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;

    const fs::path& file() const { return file_; }

    void write(const std::uint8_t* data, std::size_t size) const {
        std::ofstream out(file_, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        out.close();
        if (!out) bug("cannot write the input to", file_.string());
    }

    // Anything in the folder but the input file: what a read left behind.
    std::string leftovers() const {
        std::string found;
        for (const auto& entry : fs::directory_iterator(dir_))
            if (entry.path() != file_) found += entry.path().string() + "\n";
        return found;
    }

private:
    fs::path dir_, file_;
};

const Scratch& scratch() {
    static const Scratch s;
    return s;
}

void checkPromises(const SessionData& data) {
    if (data.completed && data.damaged) bug("readSession: a session both completed and damaged", data.note);
    if (data.completed && !data.note.empty()) bug("readSession: a completed session with a note:", data.note);
    if (!data.completed && data.note.empty()) bug("readSession: an incomplete session without a note", "");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const Scratch& s = scratch();
    s.write(data, size);
    try {
        checkPromises(warplab::session::readSession(s.file().string()));
    } catch (const warplab::session::SessionError&) {
        // The documented failure: a file that is not a readable session.
    } catch (const std::exception& e) {
        bug("readSession threw something other than SessionError:", e.what());
    }
    const std::string left = s.leftovers();
    if (!left.empty()) bug("readSession left files beside the session file:", left);
    return 0;
}
