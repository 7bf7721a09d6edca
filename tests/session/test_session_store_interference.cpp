// The session store against the world around it: a real SIGKILL mid-session, other programs
// locking or reading its file, and its file or WAL replaced, overwritten, emptied or deleted
// under it.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "session/records.h"
#include "session/session_store.h"
#include "raw_access.h"
#include "session_store_support.h"
#include "temp_dir.h"

namespace warplab::session {
namespace {

// A fresh folder per test (TempDir), removed afterwards; SQL straight on a file (execSql); and
// what every store test shares (session_store_support.h).
using namespace testing;

// ============================ kill -9 ============================

// A child writes a session one committed trial at a time, forever, and reports each commit
// that returned through a pipe; the parent SIGKILLs it after a random few milliseconds. The
// file must hold every reported trial (durable), at most one more (committed but killed before
// reporting), and nothing partial.
// Kills and reaps the child if an assertion leaves the test early, so it never outlives it.
struct ChildGuard {
    pid_t pid = -1;
    ~ChildGuard() {
        if (pid <= 0) return;
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
    }
};

TEST(SessionStoreKill, KeepsEveryCommittedTrialAndNothingPartial) {
    std::mt19937 rng(20240501u);
    std::uniform_int_distribution<int> delayUs(1000, 50000);
    int killedMidSession = 0;
    for (int iteration = 0; iteration < 12; ++iteration) {
        SCOPED_TRACE("iteration " + std::to_string(iteration));
        TempDir dir;
        int pipeFds[2];
        ASSERT_EQ(::pipe(pipeFds), 0);
        const pid_t pid = ::fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            // Child: no gtest here; any way out other than SIGKILL is a failure the parent sees.
            ::close(pipeFds[0]);
            try {
                SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
                if (::write(pipeFds[1], "R", 1) != 1) ::_exit(3);
                const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
                for (int trial = 0; std::chrono::steady_clock::now() < deadline; ++trial) {
                    writeTrial(w, trial);
                    w.commit();
                    if (::write(pipeFds[1], "c", 1) != 1) ::_exit(3);
                }
            } catch (...) {
                ::_exit(4);
            }
            ::_exit(5);  // never killed: the parent is gone
        }
        ChildGuard guard{pid};
        ::close(pipeFds[1]);
        char ready = 0;
        ASSERT_EQ(::read(pipeFds[0], &ready, 1), 1);
        ASSERT_EQ(ready, 'R');
        std::this_thread::sleep_for(std::chrono::microseconds(delayUs(rng)));
        ASSERT_EQ(::kill(pid, SIGKILL), 0);
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        guard.pid = -1;
        ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "child ended otherwise, status " << status;
        int reported = 0;
        char buf[4096];
        for (ssize_t n; (n = ::read(pipeFds[0], buf, sizeof buf)) > 0;) reported += static_cast<int>(n);
        ::close(pipeFds[0]);

        std::vector<fs::path> sessions;
        for (const fs::path& p : filesIn(dir.path()))
            if (p.extension() == ".warplab-session") sessions.push_back(p);
        ASSERT_EQ(sessions.size(), 1u);
        const SessionData data = readSession(sessions[0].string());
        const int trials = expectWholeTrials(data);
        EXPECT_GE(trials, reported);
        EXPECT_LE(trials, reported + 1);
        EXPECT_FALSE(data.completed);
        EXPECT_EQ(data.note.rfind("incomplete: ", 0), 0u) << data.note;
        expectSame(data.header, sampleHeader());
        if (trials > 0) ++killedMidSession;
    }
    // The delays must have let some children get going, or the test proved nothing.
    EXPECT_GE(killedMidSession, 2);
}

// ============================ other programs at the same files ============================

// The one session file in `dir`.
std::string onlySession(const fs::path& dir) {
    std::vector<fs::path> sessions;
    for (const fs::path& p : filesIn(dir))
        if (p.extension() == ".warplab-session") sessions.push_back(p);
    EXPECT_EQ(sessions.size(), 1u);
    return sessions.empty() ? std::string() : sessions[0].string();
}

// Another process takes the file's write lock, as `sqlite3` without -readonly, a DB browser or
// a script's BEGIN IMMEDIATE does, and keeps it longer than SQLite's usual busy timeouts. The
// writer never waits in commit() (a live frame must not stall), holds the commits, and writes
// every one once the lock is free.
TEST(SessionStoreLock, AnotherProgramsWriteLockDelaysCommitsAndLosesNone) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    const std::string path = w.path();
    writeTrial(w, 0);
    ASSERT_TRUE(w.commit());

    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::close(fds[0]);
        sqlite3* db = nullptr;
        if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK ||
            sqlite3_exec(db, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr) != SQLITE_OK)
            ::_exit(3);
        if (::write(fds[1], "L", 1) != 1) ::_exit(4);
        std::this_thread::sleep_for(std::chrono::seconds(6));
        sqlite3_exec(db, "COMMIT", nullptr, nullptr, nullptr);
        sqlite3_close(db);
        ::_exit(0);
    }
    ChildGuard guard{pid};
    ::close(fds[1]);
    char locked = 0;
    ASSERT_EQ(::read(fds[0], &locked, 1), 1);
    ::close(fds[0]);

    const auto before = std::chrono::steady_clock::now();
    writeTrial(w, 1);
    EXPECT_FALSE(w.commit());
    writeTrial(w, 2);
    EXPECT_FALSE(w.commit());
    EXPECT_LT(std::chrono::steady_clock::now() - before, std::chrono::seconds(1));  // never waited
    EXPECT_EQ(w.heldCommits(), 2u);
    EXPECT_EQ(expectWholeTrials(readSession(path)), 1);  // readers still see what was written

    int waits = 0;
    w.finish([&](double, SessionWriter::WaitingFor) { ++waits; });
    EXPECT_GE(waits, 3);  // it waited out the lock instead of failing
    EXPECT_EQ(w.heldCommits(), 0u);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    guard.pid = -1;
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;

    const SessionData data = readSession(path);
    EXPECT_EQ(expectWholeTrials(data), 3);
    EXPECT_TRUE(data.completed) << data.note;
}

// How docs/session-format.md says to read a live session: read-only connections, even ones
// that keep a read transaction open, never hold the writer up.
TEST(SessionStoreLock, ReadOnlyReadersNeverDisturbTheWriter) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    const std::string uri = "file:" + w.path() + "?mode=ro";
    sqlite3 *uriReader = nullptr, *flagReader = nullptr;
    ASSERT_EQ(sqlite3_open_v2(uri.c_str(), &uriReader, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr), SQLITE_OK);
    ASSERT_EQ(sqlite3_open_v2(w.path().c_str(), &flagReader, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(uriReader, "BEGIN; SELECT count(*) FROM frames;", nullptr, nullptr, nullptr), SQLITE_OK);
    for (int t = 0; t < 5; ++t) {
        writeTrial(w, t);
        EXPECT_TRUE(w.commit());
        EXPECT_EQ(sqlite3_exec(flagReader, "SELECT count(*) FROM events", nullptr, nullptr, nullptr), SQLITE_OK);
    }
    EXPECT_EQ(w.heldCommits(), 0u);
    // The reader's transaction ends while the session finishes, as an export's read does.
    std::thread release([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(1500));
        sqlite3_exec(uriReader, "COMMIT", nullptr, nullptr, nullptr);
    });
    w.finish();
    release.join();
    sqlite3_close(uriReader);
    sqlite3_close(flagReader);
    const SessionData data = readSession(w.path());
    EXPECT_EQ(expectWholeTrials(data), 5);
    EXPECT_TRUE(data.completed);
}

// A session that finishes while a reader holds a read transaction: finish waits for the reader
// (saying so) and only then returns, with every commit in the file itself, so the file copied
// alone -- as a lab archives it -- is the whole session.
TEST(SessionStoreLock, AFinishWaitsForAReaderSoTheFileAloneIsWhole) {
    TempDir dir, elsewhere;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    writeTrial(w, 0);
    ASSERT_TRUE(w.commit());
    std::unique_ptr<SnapshotReader> reader = std::make_unique<SnapshotReader>(w.path());
    ASSERT_TRUE(reader->ok());
    for (int t = 1; t < 6; ++t) {
        writeTrial(w, t);
        ASSERT_TRUE(w.commit());
    }
    std::thread release([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(2500));
        reader.reset();
    });
    int waits = 0;
    const auto before = std::chrono::steady_clock::now();
    w.finish([&](double, SessionWriter::WaitingFor what) {
        EXPECT_EQ(what, SessionWriter::WaitingFor::Readers);
        ++waits;
    });
    release.join();
    EXPECT_GE(std::chrono::steady_clock::now() - before, std::chrono::seconds(2));
    EXPECT_GE(waits, 1);
    const std::string copy = (elsewhere.path() / "copy.warplab-session").string();
    fs::copy_file(w.path(), copy);  // the file alone, no -wal
    const SessionData data = readSession(copy);
    EXPECT_EQ(expectWholeTrials(data), 6);
    EXPECT_TRUE(data.completed);
    EXPECT_FALSE(data.damaged) << data.note;
}

// A reader that never lets go: after its bound finish writes the session again whole and
// gives it the name, so the file alone -- copied, archived, its -wal deleted -- is the whole
// session. The reader keeps the snapshot it has.
TEST(SessionStoreLock, AFinishHeldBackTooLongWritesTheSessionWholeUnderItsName) {
    TempDir dir, elsewhere;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    const SnapshotReader reader(w.path());
    ASSERT_TRUE(reader.ok());
    for (int t = 0; t < 4; ++t) {
        writeTrial(w, t);
        ASSERT_TRUE(w.commit());
    }
    w.finish({}, 0.3);
    EXPECT_FALSE(fs::exists(w.path() + "-wal"));
    EXPECT_FALSE(fs::exists(w.path() + "-shm"));
    EXPECT_TRUE(reader.ok());
    const std::string copy = (elsewhere.path() / "copy.warplab-session").string();
    fs::copy_file(w.path(), copy);
    const SessionData data = readSession(copy);
    EXPECT_EQ(expectWholeTrials(data), 4);
    EXPECT_TRUE(data.completed) << data.note;
    EXPECT_FALSE(data.damaged) << data.note;
    // No hidden file is left behind.
    for (const auto& entry : fs::directory_iterator(dir.path()))
        EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
}

// The -wal deleted by another program mid-session, then the process killed: SQLite alone
// would keep writing the nameless log and lose every commit since the deletion (and the
// ones not yet checkpointed before it). The writer notices, saves and says so.
TEST(SessionStoreKill, ADeletedWalIsNoticedAndLosesNoCommit) {
    TempDir dir;
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::close(fds[0]);
        try {
            SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
            for (int t = 0; t < 3; ++t) {
                writeTrial(w, t);
                w.commit();
            }
            if (::unlink((w.path() + "-wal").c_str()) != 0) ::_exit(3);
            for (int t = 3; t < 6; ++t) {
                writeTrial(w, t);
                w.commit();
            }
            const std::string said = w.takeNotices().empty() ? "-" : "N";
            if (::write(fds[1], said.data(), 1) != 1) ::_exit(4);
        } catch (...) {
            ::_exit(5);
        }
        ::_exit(0);  // no destructors, no close: as a kill leaves it
    }
    ChildGuard guard{pid};
    ::close(fds[1]);
    char said = 0;
    EXPECT_EQ(::read(fds[0], &said, 1), 1);
    ::close(fds[0]);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    guard.pid = -1;
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
    EXPECT_EQ(said, 'N');  // the supervisor was told

    const SessionData data = readSession(onlySession(dir.path()));
    EXPECT_EQ(expectWholeTrials(data), 6);
    EXPECT_FALSE(data.damaged) << data.note;
    ASSERT_EQ(data.flags.count("wal_replaced"), 1u);
    EXPECT_NE(data.flags.at("wal_replaced").find("-wal was deleted"), std::string::npos);
}

// The session file itself moved away (a sync tool, a careless `mv`): the writer saves the whole
// session under its name again and goes on there.
TEST(SessionStore, AReplacedSessionFileIsSavedAgainAndTheSessionGoesOn) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    const std::string path = w.path();
    writeTrial(w, 0);
    ASSERT_TRUE(w.commit());
    fs::rename(path, path + ".moved");
    writeTrial(w, 1);
    ASSERT_TRUE(w.commit());
    const auto notices = w.takeNotices();
    ASSERT_EQ(notices.size(), 1u);
    EXPECT_NE(notices[0].find("was deleted or replaced"), std::string::npos) << notices[0];
    // The name was free again (its -wal and -shm, this writer's, went with the file): the
    // session is saved under it.
    EXPECT_EQ(w.path(), path);
    EXPECT_TRUE(fs::exists(path));
    writeTrial(w, 2);
    w.finish();
    const SessionData data = readSession(w.path());
    EXPECT_EQ(expectWholeTrials(data), 3);
    EXPECT_TRUE(data.completed) << data.note;
    EXPECT_EQ(data.flags.count("file_replaced"), 1u);
    EXPECT_TRUE(w.takeNotices().empty());  // each notice is given once
}

// The end of a session that another program took away from its name: finish() has saved every
// commit beside it and says so, and where, in one sentence, so the run cannot end as if all
// were well.
void expectFinishSaysWhereTheSessionIs(SessionWriter& w) {
    try {
        w.finish();
        ADD_FAILURE() << "finish() did not say that the session is no longer under its name";
    } catch (const SessionError& e) {
        EXPECT_NE(std::string(e.what()).find("; the whole session is saved in " + w.path() + "."), std::string::npos)
            << e.what();
    }
}

// Another file put in the session's place: the writer leaves it alone and saves the session
// beside it.
TEST(SessionStore, AFileInTheSessionsPlaceIsLeftAloneAndTheSessionSavedBesideIt) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    const std::string path = w.path();
    writeTrial(w, 0);
    ASSERT_TRUE(w.commit());
    fs::remove(path);
    std::ofstream(path) << "someone else's file";
    writeTrial(w, 1);
    ASSERT_TRUE(w.commit());
    ASSERT_EQ(w.takeNotices().size(), 1u);
    EXPECT_NE(w.path().find("-rescued"), std::string::npos) << w.path();
    expectFinishSaysWhereTheSessionIs(w);
    EXPECT_EQ(expectWholeTrials(readSession(w.path())), 2);
    std::ifstream in(path);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "someone else's file");
}

// The live file overwritten in place -- same inode, so no rename shows it: an old copy put
// back, another file copied over it, the file cut short. SQLite would go on writing into it
// (ending in "database disk image is malformed", or a file whose copy reads "no complete
// commit survives"). The writer notices before its next write, saves every commit written
// before beside it, flags the session and goes on there.
TEST(SessionStore, AFileOverwrittenInPlaceIsNoticedAndEveryCommitSavedBesideIt) {
    struct Case {
        const char* name;
        std::function<void(const std::string& path, const std::string& oldCopy)> overwrite;
    };
    const auto putBytes = [](const std::string& path, const std::string& bytes) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);  // same inode
        out << bytes;
    };
    const auto bytesOf = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const std::vector<Case> cases = {
        {"an old copy put back",
         [&](const std::string& path, const std::string& old) { putBytes(path, bytesOf(old)); }},
        {"another file copied over it",
         [&](const std::string& path, const std::string&) { putBytes(path, std::string(5000, 'x')); }},
        {"cut short",
         [](const std::string& path, const std::string&) { fs::resize_file(path, fs::file_size(path) / 2); }},
        {"emptied", [](const std::string& path, const std::string&) { fs::resize_file(path, 0); }},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        TempDir dir, elsewhere;
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        const std::string path = w.path();
        writeTrial(w, 0);
        ASSERT_TRUE(w.commit());
        const std::string old = (elsewhere.path() / "old.warplab-session").string();
        fs::copy_file(path, old);
        for (int t = 1; t < 4; ++t) {
            writeTrial(w, t);
            ASSERT_TRUE(w.commit());
        }
        struct stat before {};
        ASSERT_EQ(::stat(path.c_str(), &before), 0);
        c.overwrite(path, old);
        struct stat after {};
        ASSERT_EQ(::stat(path.c_str(), &after), 0);
        ASSERT_EQ(before.st_ino, after.st_ino);  // in place
        const std::string overwritten = bytesOf(path);

        writeTrial(w, 4);
        ASSERT_TRUE(w.commit());
        const auto notices = w.takeNotices();
        ASSERT_EQ(notices.size(), 1u);
        EXPECT_NE(notices[0].find("overwritten in place"), std::string::npos) << notices[0];
        EXPECT_NE(w.path().find("-rescued"), std::string::npos) << w.path();
        writeTrial(w, 5);
        expectFinishSaysWhereTheSessionIs(w);
        const SessionData data = readSession(w.path());
        EXPECT_EQ(expectWholeTrials(data), 6);
        EXPECT_TRUE(data.completed) << data.note;
        EXPECT_FALSE(data.damaged) << data.note;
        ASSERT_EQ(data.flags.count("file_overwritten"), 1u);
        EXPECT_NE(data.flags.at("file_overwritten").find(w.path()), std::string::npos);
        // What the other program put there stays as it put it, without our -wal beside it.
        EXPECT_EQ(bytesOf(path), overwritten);
        EXPECT_FALSE(fs::exists(path + "-wal"));
    }
}

// The -wal emptied in place while a reader holds the last commits in it: the writer writes the
// session whole again under its name, so a kill afterwards loses nothing.
TEST(SessionStore, AWalEmptiedInPlaceIsNoticedAndTheSessionWrittenWholeAgain) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    const std::string path = w.path();
    auto reader = std::make_unique<SnapshotReader>(path);
    ASSERT_TRUE(reader->ok());
    for (int t = 0; t < 4; ++t) {
        writeTrial(w, t);
        ASSERT_TRUE(w.commit());
    }
    fs::resize_file(path + "-wal", 0);
    writeTrial(w, 4);
    ASSERT_TRUE(w.commit());
    ASSERT_EQ(w.takeNotices().size(), 1u);
    EXPECT_EQ(w.path(), path);
    reader.reset();
    // As a kill leaves it: the file alone.
    TempDir elsewhere;
    const std::string copy = (elsewhere.path() / "copy.warplab-session").string();
    copySession(path, copy, kWhole, kNoWal);
    const SessionData data = readSession(copy);
    EXPECT_EQ(expectWholeTrials(data), 5);
    EXPECT_FALSE(data.damaged) << data.note;
    EXPECT_EQ(data.flags.count("wal_replaced"), 1u);
}

// Opening a FIFO blocks until someone writes to it: the read runs in a child, so a reader
// that hangs fails the test in seconds rather than hanging it.
TEST(SessionStore, RefusesAPipeAtOnceByName) {
    TempDir dir;
    const std::string fifo = (dir.path() / "p.warplab-session").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::close(fds[0]);
        std::string said = "read without an error";
        try {
            readSession(fifo);
        } catch (const SessionError& e) {
            said = e.what();
        }
        ::_exit(::write(fds[1], said.data(), said.size()) == static_cast<ssize_t>(said.size()) ? 0 : 3);
    }
    ChildGuard guard{pid};
    ::close(fds[1]);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::string said;
    char buf[512];
    ::fcntl(fds[0], F_SETFL, O_NONBLOCK);
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) said.append(buf, static_cast<std::size_t>(n));
    ::close(fds[0]);
    EXPECT_EQ(said, "Session file " + fifo + " is not a regular file (a pipe, socket or device), not a session file.");
}

}  // namespace
}  // namespace warplab::session
