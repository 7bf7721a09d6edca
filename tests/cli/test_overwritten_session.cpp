// A running session's file overwritten in place by another program -- emptied, cut to half,
// another file copied over it, an older copy of it put back (what a sync client or a careless
// `cp` does) -- at random instants of a headless run. Whatever the instant, every commit ends
// up either in the file or in `-rescued`, and the run never exits 0 while its file is not the
// whole session (docs/session-format.md, "What survives what"). Most instants land while a
// commit is being fsynced or folded into the file, which is where the writer's stamps alone
// could not tell the other program's bytes from its own.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "cli/cli_support.h"
#include "session/session_store.h"

namespace {

namespace fs = std::filesystem;
using warplab::session::readSession;
using warplab::session::SessionData;
using warplab::testing::contains;
using Clock = std::chrono::steady_clock;

std::string bytesOf(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// Writes `bytes` over `path` as `cp` does: the same inode, truncated, then written.
void putInPlace(const std::string& path, const std::string& bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    ASSERT_GE(fd, 0) << path;
    EXPECT_EQ(::write(fd, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
    ::close(fd);
}

struct Pattern {
    const char* name;
    // Applied to the session file; `older` is a copy of it taken earlier in the run.
    std::function<void(const std::string& path, const std::string& older)> overwrite;
};

// One headless run of the quick shooter protocol, as `warplab run` is started by a supervisor.
struct Run {
    pid_t pid = -1;
    std::string dir, log;

    explicit Run(const std::string& folder) : dir(folder), log(folder + "/run.log") {
        fs::create_directories(dir + "/results");
        pid = ::fork();
        if (pid == 0) {
            const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            ::dup2(out, 1);
            ::dup2(out, 2);
            const std::string protocol = std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json";
            const std::string results = dir + "/results";
            ::execl(WARPLAB_BINARY, WARPLAB_BINARY, "run", "--protocol", protocol.c_str(), "--headless", "--player",
                    "bot:1", "--seed", "3", "--participant", "P", "--out", results.c_str(),
                    static_cast<char*>(nullptr));
            ::_exit(127);
        }
    }
    bool running() const { return ::waitpid(pid, nullptr, WNOHANG) == 0; }
    int wait() const {
        int status = 0;
        ::waitpid(pid, &status, 0);
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    std::string session() const { return warplab::testing::sessionAppearingIn(dir + "/results"); }
    std::string output() const { return bytesOf(log); }
};

// A clean run: the whole session to compare with, and how long a run writes it here (from when
// its file appears: before, the run checks the folder's room).
struct Reference {
    SessionData data;
    double seconds = 0;
};
Reference cleanRun(const std::string& dir) {
    Run run(dir);
    EXPECT_FALSE(run.session().empty()) << run.output();
    const auto start = Clock::now();
    const int status = run.wait();
    Reference ref;
    ref.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    EXPECT_EQ(status, 0) << run.output();
    ref.data = readSession(warplab::testing::sessionIn(dir + "/results"));
    EXPECT_TRUE(ref.data.completed) << ref.data.note;
    return ref;
}

// Whether the session at `path` holds every commit of the clean run: finished, nothing lost,
// every row. "" when it does, else why not.
std::string wholeAgainst(const std::string& path, const Reference& ref) {
    SessionData data;
    try {
        data = readSession(path);
    } catch (const warplab::session::SessionError& e) {
        return e.what();
    }
    if (data.damaged || !data.completed) return data.note.empty() ? "not finished" : data.note;
    if (data.inputs.size() != ref.data.inputs.size() || data.frames.size() != ref.data.frames.size() ||
        data.events.size() != ref.data.events.size())
        return std::to_string(data.events.size()) + " events, not " + std::to_string(ref.data.events.size());
    return "";
}

// Runs the protocol until `instants` runs were each overwritten once at a seeded random instant,
// and checks each outcome. Instants fall in the first 80 % of a run's time, so that they land
// while the run writes; one that finds the run already ended is not counted, and the runs after
// it draw their instants from the quickest run seen (a loaded machine times runs unevenly).
void overwriteAtRandomInstants(const Pattern& pattern, std::uint32_t seed, int instants) {
    const std::string base = warplab::testing::scratch("cli-overwritten", pattern.name);
    const Reference ref = cleanRun(base + "/clean");
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> fraction(0.02, 0.8);
    double runSeconds = ref.seconds;
    int landed = 0;
    for (int i = 0; landed < instants && i < 3 * instants; ++i) {
        const double at = fraction(random) * runSeconds;
        SCOPED_TRACE(std::string(pattern.name) + " at " + std::to_string(at) + " s");
        Run run(base + "/run" + std::to_string(i));
        const std::string session = run.session();
        const auto start = Clock::now();
        ASSERT_FALSE(session.empty()) << run.output();
        std::this_thread::sleep_for(std::chrono::duration<double>(at / 2));
        const std::string older = bytesOf(session);  // the same session, some commits ago
        std::this_thread::sleep_until(start +
                                      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(at)));
        const bool whileRunning = run.running();
        if (whileRunning) pattern.overwrite(session, older);
        const int status = run.wait();
        const std::string output = run.output();
        if (!whileRunning) {
            EXPECT_EQ(status, 0) << output;
            runSeconds = std::min(runSeconds, std::chrono::duration<double>(Clock::now() - start).count());
            continue;
        }
        ++landed;
        // No reader was there: none may be blamed.
        EXPECT_FALSE(contains(output, "reading")) << output;
        const std::string rescued =
            session.substr(0, session.size() - std::string(".warplab-session").size()) + "-rescued.warplab-session";
        if (status == 0) {
            // Only where the file at its name is the whole session.
            EXPECT_EQ(wholeAgainst(session, ref), "") << output;
            EXPECT_FALSE(fs::exists(rescued)) << output;
            continue;
        }
        // Else exit 1, ending in one sentence that says where every commit is.
        EXPECT_EQ(status, 1) << output;
        const std::string last = output.substr(output.rfind('\n', output.size() - 2) + 1);
        EXPECT_TRUE(contains(last, "warplab run: The session file " + session)) << output;
        EXPECT_TRUE(contains(last, "; the whole session is saved in " + rescued + ".\n")) << output;
        ASSERT_TRUE(fs::exists(rescued)) << output;
        EXPECT_EQ(wholeAgainst(rescued, ref), "") << output;
    }
    EXPECT_GE(landed, 1) << "no instant landed while the run was writing";
}

constexpr int kInstants = 3;

TEST(CliOverwrittenSession, EmptiedAtRandomInstantsEveryCommitIsKept) {
    overwriteAtRandomInstants(
        {"emptied", [](const std::string& path, const std::string&) { fs::resize_file(path, 0); }}, 11, kInstants);
}

TEST(CliOverwrittenSession, CutToHalfAtRandomInstantsEveryCommitIsKept) {
    overwriteAtRandomInstants(
        {"cut-to-half",
         [](const std::string& path, const std::string&) { fs::resize_file(path, fs::file_size(path) / 2); }},
        12, kInstants);
}

TEST(CliOverwrittenSession, JunkCopiedOverItAtRandomInstantsEveryCommitIsKept) {
    overwriteAtRandomInstants({"junk",
                               [](const std::string& path, const std::string&) {
                                   std::mt19937 bytes(7);
                                   std::string junk(5000, '\0');
                                   for (char& c : junk) c = static_cast<char>(bytes() & 0xff);
                                   putInPlace(path, junk);
                               }},
                              13, kInstants);
}

TEST(CliOverwrittenSession, AnOlderCopyPutBackAtRandomInstantsEveryCommitIsKept) {
    overwriteAtRandomInstants(
        {"older-copy", [](const std::string& path, const std::string& older) { putInPlace(path, older); }}, 14,
        kInstants);
}

}  // namespace
