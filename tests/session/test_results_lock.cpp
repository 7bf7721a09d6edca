// The results folder's lock: one session per folder at a time, released by the kernel however
// its holder ends.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "session/results_lock.h"
#include "session/session_store.h"
#include "temp_dir.h"

namespace warplab::session {
namespace {

namespace fs = std::filesystem;

class TempDir : public testing::TempDir {
public:
    TempDir() : testing::TempDir("warplab-lock") {}
    fs::path lockFile() const { return path() / kLockFileName; }
};

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The sentence a second taker gets, or "" when it got the lock.
std::string refusal(const std::string& dir) {
    try {
        const ResultsFolderLock second(dir, "P02", "click-quick");
    } catch (const ResultsFolderBusy& e) {
        return e.what();
    }
    return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ResultsFolderLock, ASecondTakerIsRefusedNamingTheFolderAndTheHolder) {
    TempDir dir;
    {
        const ResultsFolderLock first(dir.str(), "P01", "shooter-quick");
        const auto holder = nlohmann::json::parse(readText(dir.lockFile()));
        EXPECT_EQ(holder["pid"], static_cast<long>(::getpid()));
        EXPECT_EQ(holder["participant"], "P01");
        EXPECT_EQ(holder["protocol"], "shooter-quick");
        EXPECT_FALSE(holder["host"].get<std::string>().empty());
        EXPECT_EQ(holder["since"].get<std::string>().back(), 'Z');

        const std::string said = refusal(dir.str());
        EXPECT_TRUE(has(said, "'" + dir.str() + "'")) << said;
        EXPECT_TRUE(has(said, "participant P01, protocol shooter-quick, pid " + std::to_string(::getpid()))) << said;
        EXPECT_TRUE(has(said, "since " + holder["since"].get<std::string>())) << said;
        // A session can still be written under the lock, and its creation cleanup leaves the
        // lock file alone.
        SessionHeader header;
        header.participant = "P01";
        SessionWriter w = SessionWriter::create(dir.str(), header);
        w.finish();
        EXPECT_TRUE(fs::exists(dir.lockFile()));
        EXPECT_FALSE(refusal(dir.str()).empty()) << "still held";
    }
    EXPECT_FALSE(fs::exists(dir.lockFile())) << "removed on release";
    EXPECT_EQ(refusal(dir.str()), "") << "free once released";
}

TEST(ResultsFolderLock, MovingKeepsOneLock) {
    TempDir dir;
    ResultsFolderLock first(dir.str(), "P01", "shooter-quick");
    ResultsFolderLock moved = std::move(first);
    EXPECT_FALSE(refusal(dir.str()).empty()) << "the moved-to lock holds it";
    { const ResultsFolderLock gone = std::move(moved); }
    EXPECT_EQ(refusal(dir.str()), "") << "released once, by the last owner";
}

// A holder killed with SIGKILL leaves its file behind, naming it; the kernel has released the
// lock, so the next taker gets it.
TEST(ResultsFolderLock, AFileLeftByAKilledHolderDoesNotBlock) {
    TempDir dir;
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        try {
            const ResultsFolderLock held(dir.str(), "KILLED", "shooter-thesis");
            (void)!::write(ready[1], "x", 1);
            for (;;) ::pause();
        } catch (...) {}
        std::_Exit(1);
    }
    ::close(ready[1]);  // so that a child that ends without the lock ends the read
    char byte = 0;
    const bool childHolds = ::read(ready[0], &byte, 1) == 1;
    ::close(ready[0]);
    if (!childHolds) ::waitpid(child, nullptr, 0);
    ASSERT_TRUE(childHolds) << "the child could not take the lock";
    const std::string said = refusal(dir.str());
    EXPECT_TRUE(has(said, "participant KILLED, protocol shooter-thesis, pid " + std::to_string(child))) << said;
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(fs::exists(dir.lockFile())) << "a killed holder cannot remove its file";
    EXPECT_TRUE(has(readText(dir.lockFile()), "KILLED"));
    {
        const ResultsFolderLock next(dir.str(), "P03", "click-quick");
        EXPECT_TRUE(has(readText(dir.lockFile()), "P03"));
        EXPECT_FALSE(has(readText(dir.lockFile()), "KILLED")) << "the stale holder's words are gone";
    }
}

TEST(ResultsFolderLock, AStaleFileOfAnyContentDoesNotBlock) {
    TempDir dir;
    std::ofstream(dir.lockFile()) << std::string(100000, '{');
    EXPECT_EQ(refusal(dir.str()), "");
}

TEST(ResultsFolderLock, AMissingFolderIsRefusedByNameCreatingNothing) {
    TempDir dir;
    const std::string missing = dir.str() + "/nowhere";
    try {
        const ResultsFolderLock lock(missing, "P01", "shooter-quick");
        ADD_FAILURE() << "a missing folder was locked";
    } catch (const ResultsFolderBusy&) {
        ADD_FAILURE() << "a missing folder is not busy";
    } catch (const SessionError& e) {
        EXPECT_TRUE(has(e.what(), "'" + missing + "' does not exist")) << e.what();
    }
    EXPECT_FALSE(fs::exists(missing));
}

}  // namespace
}  // namespace warplab::session
