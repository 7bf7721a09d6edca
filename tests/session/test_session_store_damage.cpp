// Damaged session files: truncated files and WALs, changed and flipped bytes, garbage pages,
// another session's WAL, files that are not sessions and other format versions -- whole
// commits kept, or a sentence naming the path, never a crash.
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

// ============================ damaged files ============================

// A finished session cut at many byte offsets, as a full disk or a bad copy leaves it.
TEST(SessionStoreDamage, TruncatedFileKeepsWholeCommitsOrFailsNamingThePath) {
    TempDir dir;
    constexpr int kTrials = 40;
    const std::string path = writeFinishedSession(dir.str(), kTrials);
    const auto size = static_cast<std::intmax_t>(fs::file_size(path));
    ASSERT_GT(size, 16 * 4096);
    std::vector<std::intmax_t> cuts = {0, 1, 50, 99, 100, 101, 1000, size - 1};
    for (std::intmax_t page = 4096; page < size; page += 4096)
        for (std::intmax_t offset : {page - 1, page, page + 1, page + 2000}) cuts.push_back(offset);

    const std::string copy = (dir.path() / "copy.warplab-session").string();
    int partial = 0, refused = 0;
    for (const std::intmax_t cut : cuts) {
        if (cut >= size) continue;
        SCOPED_TRACE("cut at byte " + std::to_string(cut) + " of " + std::to_string(size));
        copySession(path, copy, cut, kNoWal);
        try {
            const SessionData data = readSession(copy);
            const int trials = expectWholeTrials(data);
            EXPECT_LT(trials, kTrials);
            EXPECT_FALSE(data.completed);
            EXPECT_FALSE(data.note.empty());
            if (trials > 0) ++partial;
        } catch (const SessionError& e) {
            EXPECT_NE(std::string(e.what()).find(copy), std::string::npos) << e.what();
            ++refused;
        }
        if (::testing::Test::HasFailure()) break;
    }
    // Both outcomes must really occur: early cuts lose the header, later ones keep trials.
    EXPECT_GT(partial, 0);
    EXPECT_GT(refused, 0);
}

// The typed text is in its commit's checksum like every other column: a changed answer, a
// Backspace added or taken out, drops the commit it was typed in and everything after it.
TEST(SessionStoreDamage, AChangedTypedTextFailsItsCommit) {
    TempDir dir;
    constexpr int kTrials = 6, kChangedTrial = 3;
    const std::string path = writeFinishedSession(dir.str(), kTrials);
    // A frame of that trial with something typed (sampleRecord leaves some empty).
    std::int64_t frame = static_cast<std::int64_t>(kChangedTrial) * kFramesPerTrial;
    while (trialInput(frame).text.empty() || trialInput(frame).text.find('\0') != std::string::npos) ++frame;
    ASSERT_LT(frame, static_cast<std::int64_t>(kChangedTrial + 1) * kFramesPerTrial);
    std::string sameLength = trialInput(frame).text;
    sameLength[0] = static_cast<char>(sameLength[0] ^ 0x20);  // one letter's case
    std::string hex;
    for (const char c : sameLength) {
        char byte[3];
        std::snprintf(byte, sizeof byte, "%02X", static_cast<unsigned char>(c));
        hex += byte;
    }
    const std::string row = " WHERE frame = " + std::to_string(frame);
    const std::string copy = (dir.path() / "copy.warplab-session").string();
    for (const std::string& change :
         {"UPDATE input SET text = text || 'x'" + row, "UPDATE input SET text = text || char(8)" + row,
          "UPDATE input SET text = ''" + row, "UPDATE input SET text = CAST(X'" + hex + "' AS TEXT)" + row}) {
        SCOPED_TRACE(change);
        copySession(path, copy, kWhole, kNoWal);
        execSql(copy, change);
        const SessionData data = readSession(copy);
        EXPECT_FALSE(data.completed);
        EXPECT_TRUE(data.damaged);
        EXPECT_NE(
            data.note.find("the rows of commit " + std::to_string(kChangedTrial + 1) + " do not match its checksum"),
            std::string::npos)
            << data.note;
        EXPECT_EQ(expectWholeTrials(data), kChangedTrial);
    }
}

// The writer folds the -wal into the file after every commit, so a -wal lost after a
// commit loses nothing.
TEST(SessionStoreDamage, AMissingWalLosesNoWrittenCommit) {
    TempDir dir;
    constexpr int kTrials = 12;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    for (int t = 0; t < kTrials; ++t) {
        writeTrial(w, t);
        ASSERT_TRUE(w.commit());
    }
    const std::string path = w.path();
    ASSERT_TRUE(fs::exists(path + "-wal"));
    const std::string copy = (dir.path() / "copy.warplab-session").string();
    copySession(path, copy, kWhole, kNoWal);
    const SessionData data = readSession(copy);
    EXPECT_EQ(expectWholeTrials(data), kTrials);
    EXPECT_FALSE(data.damaged) << data.note;
    w.finish();
}

// A byte flipped in the -wal: SQLite silently stops reading the log at the frame that fails
// its checksum, so the commits after it would vanish and the session read as merely
// incomplete. The reader finds them and calls the file damaged, naming what was lost.
TEST(SessionStoreDamage, DamageInTheWalIsReportedNamingWhatWasLost) {
    TempDir dir;
    constexpr int kTrials = 10;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    const std::string path = w.path();
    const SnapshotReader reader(path);  // the commits stay in the -wal
    ASSERT_TRUE(reader.ok());
    for (int t = 0; t < kTrials; ++t) {
        writeTrial(w, t);
        ASSERT_TRUE(w.commit());
    }
    const std::string copy = (dir.path() / "copy.warplab-session").string();
    copySession(path, copy, kWhole, kWhole);
    const SessionData intact = readSession(copy);
    EXPECT_FALSE(intact.damaged) << intact.note;
    EXPECT_EQ(expectWholeTrials(intact), kTrials);

    // One byte in the page data of a frame a third of the way in.
    const auto walSize = fs::file_size(copy + "-wal");
    const std::uintmax_t frameSize = 24 + 4096;
    const std::uintmax_t at = 32 + (walSize - 32) / frameSize / 3 * frameSize + 24 + 100;
    {
        std::fstream f(copy + "-wal", std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(static_cast<std::streamoff>(at));
        const char c = static_cast<char>(f.get() ^ 0x5a);
        f.seekp(static_cast<std::streamoff>(at));
        f.put(c);
    }
    const SessionData data = readSession(copy);
    const int trials = expectWholeTrials(data);
    EXPECT_LT(trials, kTrials);
    EXPECT_TRUE(data.damaged);
    EXPECT_FALSE(data.completed);
    EXPECT_EQ(data.note.rfind("damaged (write-ahead log: the frame at byte ", 0), 0u) << data.note;
    EXPECT_NE(data.note.find(" in the write-ahead log"), std::string::npos) << data.note;
    EXPECT_NE(data.note.find("; lost "), std::string::npos) << data.note;

    // The reader still holds the last commits out of the file: finish writes the session whole.
    w.finish({}, 0.1);
    const SessionData finished = readSession(path);
    EXPECT_TRUE(finished.completed) << finished.note;
    EXPECT_EQ(expectWholeTrials(finished), kTrials);
}

// A -wal of a twin run -- same participant, seed, protocol and start time, so the same rows --
// put beside a session file that a kill left: SQLite applies any -wal it finds, and its pages
// read as this session's. Each session's commits chain to its own id, so the reader sees that
// the -wal is not the file's and reads the file without it, keeping every commit it holds.
TEST(SessionStoreDamage, AnotherSessionsWalIsNotTakenForThisOnes) {
    for (const bool twinFlagged : {false, true}) {  // with a flag, the -wal holds the twin's header page
        SCOPED_TRACE(twinFlagged ? "the -wal holds the twin's header" : "the -wal holds the twin's rows");
        TempDir a, b, x;
        SessionHeader header = sampleHeader();
        header.startedAt = "2026-03-04T05:06:07.890Z";
        SessionWriter first = SessionWriter::create(a.str(), header);
        for (int t = 0; t < 5; ++t) {
            writeTrial(first, t);
            ASSERT_TRUE(first.commit());
        }
        SessionWriter twin = SessionWriter::create(b.str(), header);
        const SnapshotReader holdsTwinsLog(twin.path());  // so its -wal keeps all its commits
        ASSERT_TRUE(holdsTwinsLog.ok());
        for (int t = 0; t < 3; ++t) {
            if (twinFlagged) twin.flag("missed_frames", "trial " + std::to_string(t));
            writeTrial(twin, t);
            ASSERT_TRUE(twin.commit());
        }
        const std::string copy = (x.path() / "s.warplab-session").string();
        fs::copy_file(first.path(), copy);
        fs::copy_file(twin.path() + "-wal", copy + "-wal");
        const SessionData data = readSession(copy);
        EXPECT_TRUE(data.damaged) << data.note;
        EXPECT_FALSE(data.completed);
        EXPECT_EQ(data.note.rfind("damaged (write-ahead log: " + copy + "-wal ", 0), 0u) << data.note;
        EXPECT_NE(data.note.find(twinFlagged ? "-wal is another session's" : "-wal does not fit this file"),
                  std::string::npos)
            << data.note;
        EXPECT_NE(data.note.find("): read the file without it (incomplete: "), std::string::npos) << data.note;
        EXPECT_EQ(expectWholeTrials(data), 5);
        EXPECT_TRUE(data.flags.empty());
    }
}

// A kill between a held-back finish's rename and its removal of the old -wal leaves the whole
// finished file beside a stale -wal: the file alone is read, and it is complete.
TEST(SessionStoreDamage, AFinishedFileBesideAStaleWalReadsComplete) {
    TempDir dir, x;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    auto reader = std::make_unique<SnapshotReader>(w.path());
    for (int t = 0; t < 3; ++t) {
        writeTrial(w, t);
        ASSERT_TRUE(w.commit());
    }
    const std::string copy = (x.path() / "s.warplab-session").string();
    fs::copy_file(w.path() + "-wal", copy + "-wal");  // the log before the finish
    w.finish({}, 0.1);
    reader.reset();
    fs::copy_file(w.path(), copy);
    const SessionData data = readSession(copy);
    EXPECT_TRUE(data.completed) << data.note;
    EXPECT_FALSE(data.damaged) << data.note;
    EXPECT_EQ(expectWholeTrials(data), 3);
}

// A reader's snapshot can hold the checkpoint back, leaving commits only in the -wal; then a
// -wal cut short or lost keeps whole commits.
TEST(SessionStoreDamage, TruncatedOrMissingWalKeepsWholeCommits) {
    TempDir dir;
    constexpr int kTrials = 12;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    const std::string path = w.path();
    const SnapshotReader reader(path);
    ASSERT_TRUE(reader.ok());
    for (int t = 0; t < kTrials; ++t) {
        writeTrial(w, t);
        ASSERT_TRUE(w.commit());  // a reader never holds the writer up
    }
    const auto walSize = static_cast<std::intmax_t>(fs::file_size(path + "-wal"));
    const std::string copy = (dir.path() / "copy.warplab-session").string();

    copySession(path, copy, kWhole, kWhole);
    EXPECT_EQ(expectWholeTrials(readSession(copy)), kTrials);

    int previous = -1;
    for (std::intmax_t cut = 0; cut < walSize; cut += 997) {
        SCOPED_TRACE("WAL cut at byte " + std::to_string(cut) + " of " + std::to_string(walSize));
        copySession(path, copy, kWhole, cut);
        const SessionData shortened = readSession(copy);
        EXPECT_FALSE(shortened.damaged) << shortened.note;  // a log cut short is what a kill leaves
        const int trials = expectWholeTrials(shortened);
        EXPECT_GE(trials, previous);  // more log, never fewer trials
        previous = trials;
        if (::testing::Test::HasFailure()) break;
    }
    EXPECT_LT(previous, kTrials);

    // The -wal deleted: the header was checkpointed into the main file, so it still reads.
    copySession(path, copy, kWhole, kNoWal);
    const SessionData data = readSession(copy);
    EXPECT_GE(expectWholeTrials(data), 0);
    EXPECT_LT(expectWholeTrials(data), kTrials);
    EXPECT_FALSE(data.completed);
    expectSame(data.header, sampleHeader());
    // The reader still holds the last commits out of the file: finish writes the session whole.
    w.finish({}, 0.1);
    const SessionData finished = readSession(path);
    EXPECT_TRUE(finished.completed) << finished.note;
    EXPECT_EQ(expectWholeTrials(finished), kTrials);
}

// Garbage over whole pages: whatever survives, reading never crashes or throws anything but
// SessionError.
TEST(SessionStoreDamage, GarbagePagesNeverCrashTheReader) {
    TempDir dir;
    const std::string path = writeFinishedSession(dir.str(), 20);
    const auto size = fs::file_size(path);
    const std::string copy = (dir.path() / "copy.warplab-session").string();
    std::mt19937 rng(7);
    for (std::uintmax_t page = 0; page * 4096 < size; ++page) {
        SCOPED_TRACE("garbage in page " + std::to_string(page + 1));
        copySession(path, copy, kWhole, kNoWal);
        {
            std::fstream f(copy, std::ios::in | std::ios::out | std::ios::binary);
            f.seekp(static_cast<std::streamoff>(page * 4096 + (page == 0 ? 100 : 0)));
            for (int i = 0; i < 4096 - (page == 0 ? 100 : 0); ++i) f.put(static_cast<char>(rng() & 0xff));
        }
        try {
            const SessionData data = readSession(copy);
            EXPECT_LE(data.inputs.size(), 20u * kFramesPerTrial);
            EXPECT_LE(data.events.size(), 20u * kEventsPerTrial);
        } catch (const SessionError& e) {
            EXPECT_NE(std::string(e.what()).find(copy), std::string::npos) << e.what();
        }
    }
}

// SQLite would read most flipped bits as valid but different data. The per-commit checksums
// must turn every one of them into "fewer whole trials" or an error -- never wrong values.
TEST(SessionStoreDamage, FlippedBytesNeverPassAsData) {
    TempDir dir;
    constexpr int kTrials = 8;
    const std::string path = writeFinishedSession(dir.str(), kTrials);
    const auto size = static_cast<std::streamoff>(fs::file_size(path));
    const std::string copy = (dir.path() / "copy.warplab-session").string();
    int shortened = 0;
    for (std::streamoff offset = 3; offset < size; offset += 53) {
        SCOPED_TRACE("byte " + std::to_string(offset) + " flipped");
        copySession(path, copy, kWhole, kNoWal);
        {
            std::fstream f(copy, std::ios::in | std::ios::out | std::ios::binary);
            f.seekg(offset);
            const int byte = f.get();
            f.seekp(offset);
            f.put(static_cast<char>(byte ^ 0x5a));
        }
        try {
            const int trials = expectWholeTrials(readSession(copy));
            if (trials < kTrials) ++shortened;
        } catch (const SessionError& e) {
            EXPECT_NE(std::string(e.what()).find(copy), std::string::npos) << e.what();
        }
        if (::testing::Test::HasFailure()) break;
    }
    EXPECT_GT(shortened, 0);
}

TEST(SessionStoreDamage, NotASessionFailsNamingThePath) {
    TempDir dir;
    const std::string text = (dir.path() / "notes.warplab-session").string();
    std::ofstream(text) << "participant P07 was tired\n" << std::string(5000, 'x');
    const std::string textError = errorOf(text);
    EXPECT_NE(textError.find(text), std::string::npos) << textError;
    EXPECT_NE(textError.find("not a SQLite database"), std::string::npos) << textError;

    const std::string empty = (dir.path() / "empty.warplab-session").string();
    std::ofstream{empty};
    EXPECT_NE(errorOf(empty).find(empty), std::string::npos);

    const std::string other = (dir.path() / "other.sqlite").string();
    execSql(other, "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT)");
    const std::string otherError = errorOf(other);
    EXPECT_NE(otherError.find("not a warplab session"), std::string::npos) << otherError;

    const std::string missing = (dir.path() / "missing.warplab-session").string();
    EXPECT_NE(errorOf(missing).find(missing), std::string::npos);
    EXPECT_FALSE(fs::exists(missing));
}

// Version 5 had no player_model: such a file reads with none, whatever meta holds besides.
TEST(SessionStore, AVersion5FileReadsWithoutAPlayerModel) {
    TempDir dir;
    SessionHeader header = sampleHeader();
    header.playerModel = "{\"reaction_s\":0.2}";
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), header);
        path = w.path();
        w.finish();
    }
    EXPECT_EQ(readSessionHeader(path).playerModel, header.playerModel);
    relabel(path, 5);
    const SessionHeader five = readSessionHeader(path);
    EXPECT_EQ(five.formatVersion, 5);
    EXPECT_EQ(five.playerModel, "");
    // And the model is in the version-6 checksum: changed, the header is damaged.
    relabel(path, 6);
    execSql(path, "UPDATE meta SET value = '{}' WHERE key = 'player_model'");
    EXPECT_NE(errorOf(path).find("checksum does not match"), std::string::npos) << errorOf(path);
}

TEST(SessionStoreDamage, OtherFormatVersionsNameTheVersions) {
    TempDir dir;
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        w.finish();
    }
    for (const int version : {7, 0, -1}) {
        execSql(path, "UPDATE meta SET value = '" + std::to_string(version) + "' WHERE key = 'format_version'");
        const std::string error = errorOf(path);
        EXPECT_NE(error.find(path), std::string::npos) << error;
        EXPECT_NE(error.find("is session format version " + std::to_string(version) + ";"), std::string::npos) << error;
        EXPECT_NE(error.find("reads session format versions 1, 2, 3, 4, 5 and 6."), std::string::npos) << error;
    }
    // The schema is checked against the file's own version: a version-3 file that says 1 lacks
    // version 1's columns.
    relabel(path, 1);
    const std::string v1Error = errorOf(path);
    EXPECT_NE(v1Error.find("does not match the session format 1 schema"), std::string::npos) << v1Error;
    EXPECT_NE(v1Error.find("target_"), std::string::npos) << v1Error;

    relabel(path, 3);
    EXPECT_EQ(errorOf(path), "");
    execSql(path, "ALTER TABLE frames DROP COLUMN kind");
    const std::string schemaError = errorOf(path);
    EXPECT_NE(schemaError.find("does not match the session format 3 schema"), std::string::npos) << schemaError;
    EXPECT_NE(schemaError.find("kind"), std::string::npos) << schemaError;
}

}  // namespace
}  // namespace warplab::session
