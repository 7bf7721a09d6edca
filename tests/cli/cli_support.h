// What the CLI tests share: running a command and reading what it printed, a scratch folder
// per test, finding the session a run wrote.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace warplab::testing {

struct Result {
    int status = -1;  // exit status, or 128 + signal
    std::string output;  // stdout and stderr together
    int lines() const {
        int n = 0;
        for (char c : output) n += c == '\n';
        return n;
    }
};

inline Result runCommand(const std::string& command) {
    Result result;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (pipe == nullptr) return result;
    std::array<char, 4096> buffer{};
    while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
    const int raw = pclose(pipe);
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    return result;
}

inline Result warplab(const std::string& arguments) {
    return runCommand(std::string(WARPLAB_BINARY) + " " + arguments);
}

// An empty folder build/test-output/<group>/<name>.
inline std::string scratch(const std::string& group, const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(WARPLAB_BINARY_DIR) / "test-output" / group / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

// The session file a run wrote into `dir` ("" for none).
inline std::string sessionIn(const std::string& dir) {
    std::string found;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().extension() == ".warplab-session") found = entry.path().string();
    return found;
}

// The session file a run started in the background writes into `dir`, as soon as it is there
// ("" if none appears within 30 s).
inline std::string sessionAppearingIn(const std::string& dir) {
    std::string session;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while ((session = sessionIn(dir)).empty() && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    return session;
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A command prefix that runs a command on a fresh virtual X display (1024x768). xvfb-run -a
// takes the first display number without a lock file from its start, :99, so two tests that
// start together under ctest -j may both take it and one fails; each test process starts its
// search elsewhere. -noreset: a server that resets as its last client leaves signals xvfb-run
// again, and a signal that lands while xvfb-run removes its temporary folder fails the run
// ("problem while cleaning up temporary directory", exit 5; 3 of 96 quick runs on 2 busy cores).
inline std::string onXvfb() {
    return "xvfb-run -a -n " + std::to_string(100 + ::getpid() % 800) + " -s '-screen 0 1024x768x24 -noreset' ";
}

// A shooter protocol of a few seconds, written into `dir`, that still has every phase:
// acclimation, the supervisor's Enter, training and a test target per condition. It warns of a
// refresh other than its 120 Hz, as the quick protocols do, since Xvfb reports none. Its path.
inline std::string tinyProtocol(const std::string& dir) {
    std::ofstream(dir + "/tiny.json") << R"({"format_version":2,"name":"shooter-tiny","game":"shooter",
 "display":{"refresh_mismatch":"warn"},
 "acclimation":{"duration_s":1.0,"level":0,"mode":"conv120"},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.5},
 "test":{"targets_per_condition":1,"timeout_s":0.5,"pause_s":0.25,"supervisor_starts":true}})";
    return dir + "/tiny.json";
}

}  // namespace warplab::testing
