// readSessionOutline, what a study's status reads of each session: for every session that is
// not damaged it says what readSession says (the fixtures of every format version, finished,
// running, killed with and without its -wal); it sees the damage the last commit shows; a row
// changed in place is left to the whole read, as documented; and it reads a small part of a
// long session's bytes.
#include <gtest/gtest.h>

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "session/records.h"
#include "session/session_store.h"
#include "raw_access.h"
#include "temp_dir.h"

namespace warplab::session {
namespace {

namespace fs = std::filesystem;
using testing::bytesRead;
using testing::execSql;
using testing::TempDir;

constexpr int kFramesPerTrial = 48;

SessionHeader header() {
    SessionHeader h;
    h.protocolJson = R"({"game": "shooter", "name": "outline"})";
    h.seed = 11;
    h.participant = "P01";
    h.appVersion = "test";
    h.player = "bot:1";
    h.planId = "plan-1";
    return h;
}

// One trial: a frame and an input row per display frame, a detail the size a game writes, and
// two events.
void writeTrial(SessionWriter& w, int trial) {
    const std::int64_t first = static_cast<std::int64_t>(trial) * kFramesPerTrial;
    EventRecord start;
    start.frame = first;
    start.type = "phase";
    start.trial = trial;
    w.addEvent(start);
    for (std::int64_t f = first; f < first + kFramesPerTrial; ++f) {
        InputRecord in;
        in.frame = f;
        in.displayTime = static_cast<double>(f) / 120.0;
        in.mouseDx = static_cast<double>(f % 7);
        w.addInput(in);
        FrameRecord fr;
        fr.frame = f;
        fr.condition = "warp15to120";
        fr.kind = f % 8 == 0 ? "rendered" : "warped";
        fr.detailJson = R"({"target":[)" + std::to_string(f * 0.001) + ",1.25,-3.5]}";
        w.addFrame(fr);
    }
    EventRecord shot;
    shot.frame = first + kFramesPerTrial - 1;
    shot.type = "shot";
    shot.phase = "test";
    shot.trial = trial;
    shot.worldOutcome = shot.displayedOutcome = trial % 3 ? "hit" : "miss";
    shot.detailJson = R"({"aim_time_s":0.5})";
    w.addEvent(shot);
}

std::string writeSession(const std::string& dir, int trials, bool finish) {
    SessionWriter w = SessionWriter::create(dir, header());
    for (int t = 0; t < trials; ++t) {
        writeTrial(w, t);
        if (t == 1) w.flag("missed_frames", "2 of 96");
        w.commit();
    }
    w.summarize("pacing", "[]");
    if (finish) w.finish();
    return w.path();
}

std::string copyOf(const std::string& path, const std::string& to, bool withWal) {
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(to + suffix);
    fs::copy_file(path, to);
    if (withWal && fs::exists(path + "-wal")) fs::copy_file(path + "-wal", to + "-wal");
    return to;
}

// The outline against the whole read: every field it shares with SessionData.
void expectSameAsWholeRead(const std::string& path) {
    SCOPED_TRACE(path);
    const SessionData whole = readSession(path);
    const SessionOutline outline = readSessionOutline(path);
    EXPECT_EQ(outline.header.sessionId, whole.header.sessionId);
    EXPECT_EQ(outline.header.participant, whole.header.participant);
    EXPECT_EQ(outline.header.protocolJson, whole.header.protocolJson);
    EXPECT_EQ(outline.header.planId, whole.header.planId);
    EXPECT_EQ(outline.header.formatVersion, whole.header.formatVersion);
    EXPECT_EQ(outline.completed, whole.completed);
    EXPECT_EQ(outline.damaged, whole.damaged);
    EXPECT_EQ(outline.note, whole.note);
    EXPECT_EQ(outline.flags, whole.flags);
    EXPECT_EQ(outline.summaries, whole.summaries);
    EXPECT_EQ(outline.inputRows, static_cast<std::int64_t>(whole.inputs.size()));
    EXPECT_EQ(outline.frameRows, static_cast<std::int64_t>(whole.frames.size()));
    ASSERT_EQ(outline.events.size(), whole.events.size());
    for (std::size_t i = 0; i < whole.events.size(); ++i)
        EXPECT_EQ(firstDifference(outline.events[i], whole.events[i]), "") << "event " << i;
}

TEST(SessionOutline, IsWhatTheWholeReadSaysOfEveryUndamagedSession) {
    for (const char* fixture : {"v1-shooter-quick", "v2-click-quick", "v3-shooter-quick", "v4-click-quick"})
        expectSameAsWholeRead(std::string(WARPLAB_SOURCE_DIR) + "/tests/data/" + fixture + ".warplab-session");

    TempDir dir, copies;
    expectSameAsWholeRead(writeSession(dir.str(), 5, true));
    {
        TempDir empty;  // created, nothing committed
        SessionWriter w = SessionWriter::create(empty.str(), header());
        expectSameAsWholeRead(w.path());
    }
    // Running: read beside its writer, with its -wal; then as a kill leaves it, with and without
    // the -wal.
    SessionWriter w = SessionWriter::create(dir.str(), header());
    for (int t = 0; t < 4; ++t) {
        writeTrial(w, t);
        ASSERT_TRUE(w.commit());
    }
    ASSERT_TRUE(fs::exists(w.path() + "-wal"));
    expectSameAsWholeRead(w.path());
    expectSameAsWholeRead(copyOf(w.path(), (copies.path() / "killed.warplab-session").string(), true));
    expectSameAsWholeRead(copyOf(w.path(), (copies.path() / "no-wal.warplab-session").string(), false));
    w.finish();
    expectSameAsWholeRead(w.path());
}

TEST(SessionOutline, SeesTheDamageTheLastCommitShows) {
    TempDir dir;
    constexpr int kTrials = 30;
    const std::string path = writeSession(dir.str(), kTrials, true);
    const std::string copy = (dir.path() / "copy.warplab-session").string();
    const std::string last = std::to_string(kTrials);
    struct Case {
        std::string sql, note;
    };
    for (const Case& c :
         std::vector<Case>{{"DELETE FROM events WHERE id = (SELECT max(id) FROM events)",
                            "damaged (events table: rows of commit " + last + " are missing)"},
                           {"DELETE FROM input WHERE frame > " + std::to_string((kTrials - 1) * kFramesPerTrial) +
                                "; DELETE FROM frames WHERE frame > " + std::to_string((kTrials - 1) * kFramesPerTrial),
                            "damaged (input table: rows of commit " + last + " are missing)"},
                           {"DELETE FROM commits WHERE id = " + last,
                            "damaged (commits table: rows after the last readable commit): its last commit, " +
                                std::to_string(kTrials - 1) + ", ends after frame " +
                                std::to_string((kTrials - 1) * kFramesPerTrial - 1)},
                           {"UPDATE commits SET event_rows = 'x' WHERE id = " + last,
                            "damaged (commits table: its last row has a value of the wrong type)"}}) {
        SCOPED_TRACE(c.sql);
        copyOf(path, copy, false);
        execSql(copy, c.sql);
        EXPECT_TRUE(readSession(copy).damaged);
        const SessionOutline outline = readSessionOutline(copy);
        EXPECT_TRUE(outline.damaged);
        EXPECT_FALSE(outline.completed);
        EXPECT_EQ(outline.note.rfind(c.note, 0), 0u) << outline.note;
    }

    // Cut short, as a full disk or a copy interrupted leaves it: damaged, or refused naming it.
    const auto size = static_cast<std::intmax_t>(fs::file_size(path));
    for (std::intmax_t cut = size / 2; cut < size; cut += 4096) {
        SCOPED_TRACE("cut at byte " + std::to_string(cut) + " of " + std::to_string(size));
        copyOf(path, copy, false);
        fs::resize_file(copy, static_cast<std::uintmax_t>(cut));
        try {
            EXPECT_TRUE(readSessionOutline(copy).damaged);
        } catch (const SessionError& e) {
            EXPECT_NE(std::string(e.what()).find(copy), std::string::npos) << e.what();
        }
    }
}

// Another session's -wal beside a killed one: the outline, as the whole read, reads the file
// without it and says so.
TEST(SessionOutline, RefusesAnotherSessionsWalAsTheWholeReadDoes) {
    TempDir a, b, x;
    SessionWriter first = SessionWriter::create(a.str(), header());
    for (int t = 0; t < 4; ++t) {
        writeTrial(first, t);
        ASSERT_TRUE(first.commit());
    }
    SessionWriter other = SessionWriter::create(b.str(), header());
    other.flag("missed_frames", "1");
    writeTrial(other, 0);
    ASSERT_TRUE(other.commit());
    const std::string copy = copyOf(first.path(), (x.path() / "s.warplab-session").string(), false);
    fs::copy_file(other.path() + "-wal", copy + "-wal");
    const SessionOutline outline = readSessionOutline(copy);
    EXPECT_TRUE(outline.damaged);
    EXPECT_EQ(outline.note, readSession(copy).note);
    EXPECT_NE(outline.note.find("-wal is another session's"), std::string::npos) << outline.note;
}

// What the outline leaves to the whole read (docs/session-format.md): a row changed in place
// fails its commit's checksum, which only the whole read computes. Status says done; replay,
// export and resume say damaged.
TEST(SessionOutline, LeavesARowChangedInPlaceToTheWholeRead) {
    TempDir dir;
    const std::string path = writeSession(dir.str(), 6, true);
    execSql(path, "UPDATE frames SET mode = 'conv15' WHERE frame = 100");
    EXPECT_TRUE(readSession(path).damaged);
    const SessionOutline outline = readSessionOutline(path);
    EXPECT_TRUE(outline.completed) << outline.note;
    EXPECT_FALSE(outline.damaged);
}

// The point of the outline: a long session's input and frame rows are not read. A session of
// 400 trials (19,200 frames) is read whole in megabytes; its outline in a small part of that.
TEST(SessionOutline, ReadsASmallPartOfALongSession) {
    TempDir dir;
    const std::string path = writeSession(dir.str(), 400, true);
    const auto size = fs::file_size(path);
    ASSERT_GT(size, 1500000u);
    std::uint64_t before = bytesRead();
    const SessionOutline outline = readSessionOutline(path);
    const std::uint64_t outlined = bytesRead() - before;
    EXPECT_TRUE(outline.completed) << outline.note;
    EXPECT_EQ(outline.events.size(), 800u);
    before = bytesRead();
    (void)readSession(path);
    const std::uint64_t whole = bytesRead() - before;
    EXPECT_GE(whole, size * 9 / 10);
    // The events (800 short rows) and the path down each table's b-tree: a tenth is generous.
    EXPECT_LT(outlined, size / 10) << outlined << " of " << size << " bytes read";
}

}  // namespace
}  // namespace warplab::session
