// The writer reads its file back when the session ends and compares it, row for row, with what
// it wrote. An overwrite its stamps cannot see -- same inode, size, modification time and SQLite
// header, as one that lands while a commit is fsynced is stamped afterwards -- must not pass for
// a whole session: every commit is saved beside the file, and the end says so.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <ctime>
#include <filesystem>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "session/session_store.h"
#include "temp_dir.h"

namespace warplab::session {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

constexpr int kTrials = 4;
constexpr int kFramesPerTrial = 120;

SessionHeader header() {
    SessionHeader h;
    h.protocolJson = R"({"name":"read-back"})";
    h.seed = 5;
    h.participant = "R1";
    h.player = "bot:5";
    h.startedAt = "2024-05-01T12:34:56.789Z";
    return h;
}

void writeTrials(SessionWriter& w) {
    for (int t = 0; t < kTrials; ++t) {
        for (int k = 0; k < kFramesPerTrial; ++k) {
            const std::int64_t frame = t * kFramesPerTrial + k;
            InputRecord in;
            in.frame = frame;
            in.displayTime = static_cast<double>(frame) / 120.0;
            in.mouseDx = 0.25 * k;
            w.addInput(in);
            FrameRecord f;
            f.frame = frame;
            f.condition = "conv120";
            f.kind = "rendered";
            f.detailJson = R"({"target":[1.5,2.5,-8]})";
            w.addFrame(f);
        }
        EventRecord e;
        e.frame = (t + 1) * kFramesPerTrial - 1;
        e.type = "shot";
        e.trial = t;
        e.worldOutcome = e.displayedOutcome = "hit";
        w.addEvent(e);
        ASSERT_TRUE(w.commit());
    }
}

// Zeroes the input table's root page in place, leaving the file's size, modification time and
// first page (the SQLite header) as they were: nothing a stamp looks at changes. The writer's
// own connection keeps the page cached and would write on as if nothing had happened.
void zeroTheInputTablesRootUnseen(const std::string& path) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db,
                                 "SELECT (SELECT rootpage FROM sqlite_schema WHERE name = 'input'), "
                                 "(SELECT page_size FROM pragma_page_size)",
                                 -1, &s, nullptr),
              SQLITE_OK);
    ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
    const sqlite3_int64 root = sqlite3_column_int64(s, 0), pageSize = sqlite3_column_int64(s, 1);
    sqlite3_finalize(s);
    sqlite3_close(db);
    ASSERT_GT(root, 1);

    struct stat before {};
    ASSERT_EQ(::stat(path.c_str(), &before), 0);
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    ASSERT_GE(fd, 0);
    const std::vector<char> zeros(static_cast<std::size_t>(pageSize), '\0');
    EXPECT_EQ(::pwrite(fd, zeros.data(), zeros.size(), (root - 1) * pageSize), pageSize);
    const timespec times[2] = {before.st_atim, before.st_mtim};
    EXPECT_EQ(::futimens(fd, times), 0);
    ::close(fd);
    struct stat after {};
    ASSERT_EQ(::stat(path.c_str(), &after), 0);
    ASSERT_EQ(after.st_size, before.st_size);
    ASSERT_EQ(after.st_ino, before.st_ino);
}

void expectEveryTrialBesideIt(const std::function<void(SessionWriter&)>& end, bool completed) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), header());
    const std::string name = w.path();
    writeTrials(w);
    zeroTheInputTablesRootUnseen(name);
    std::string said;
    try {
        end(w);
    } catch (const SessionError& e) {
        said = e.what();
    }
    // One sentence: what happened to the file and where the whole session is.
    EXPECT_NE(said.find("The session file " + name + " was overwritten in place by another program (seen: "),
              std::string::npos)
        << said;
    EXPECT_NE(w.path().find("-rescued"), std::string::npos) << w.path();
    EXPECT_NE(said.find("; the whole session is saved in " + w.path() + "."), std::string::npos) << said;
    const SessionData data = readSession(w.path());
    EXPECT_FALSE(data.damaged) << data.note;
    EXPECT_EQ(data.completed, completed) << data.note;
    EXPECT_EQ(data.inputs.size(), static_cast<std::size_t>(kTrials * kFramesPerTrial));
    EXPECT_EQ(data.events.size(), static_cast<std::size_t>(kTrials));
    EXPECT_EQ(data.flags.count("file_overwritten"), 1u);
}

TEST(SessionReadBack, AFinishFindsAnOverwriteTheStampsCannotSeeAndSavesEveryCommitBesideIt) {
    expectEveryTrialBesideIt([](SessionWriter& w) { w.finish(); }, true);
}

TEST(SessionReadBack, ACloseFindsAnOverwriteTheStampsCannotSeeAndSavesEveryCommitBesideIt) {
    expectEveryTrialBesideIt([](SessionWriter& w) { w.close(); }, false);
}

// A write that fails for want of room (a file-size limit stands in for a full disk): the
// writer tries to save every commit beside the file, which cannot be written either, so the
// session ends with the write's own sentence naming the file, and nothing half-written
// beside it.
TEST(SessionReadBack, AWriteWithNoRoomForARescueEndsWithTheWritesOwnSentence) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), header());
    const std::string name = w.path();
    writeTrials(w);
    rlimit before{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &before), 0);
    const auto previous = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
    rlimit small = before;
    small.rlim_cur = static_cast<rlim_t>(fs::file_size(name));
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    for (std::int64_t frame = kTrials * kFramesPerTrial; frame < 40 * kFramesPerTrial; ++frame) {
        InputRecord in;
        in.frame = frame;
        in.text = std::string(200, 'x');
        w.addInput(in);
    }
    std::string said;
    try {
        w.commit();
    } catch (const SessionError& e) {
        said = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &before);
    std::signal(SIGXFSZ, previous);
    EXPECT_EQ(said.rfind("Cannot write session file " + name + " (", 0), 0u) << said;
    EXPECT_EQ(w.path(), name);
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(dir.path())) files.push_back(entry.path().filename().string());
    for (const std::string& file : files) EXPECT_EQ(file.find("rescu"), std::string::npos) << file;
    EXPECT_EQ(readSession(name).events.size(), static_cast<std::size_t>(kTrials));
}

// What the writer did not touch passes: a session read back whole ends quietly at its name.
TEST(SessionReadBack, AnUntouchedSessionEndsAtItsName) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), header());
    const std::string name = w.path();
    writeTrials(w);
    w.flag("note", "read back");
    w.finish();
    EXPECT_EQ(w.path(), name);
    EXPECT_TRUE(readSession(name).completed);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace warplab::session
