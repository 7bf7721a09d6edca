// The session store's exact round trip: every field of every record bit for bit (NaN, typed
// text, doubles as SQL reals), commits, flags and summaries, a running session read up to its
// last commit, and records refused out of order.
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

// Every integer field at its type's limit (max or min), every other one as sampleRecord(0).
template <class R>
R extremeRecord(bool max) {
    R r = sampleRecord<R>(0);
    forEachField(r, [&](const Field<R>&, auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_integral_v<T>) v = max ? std::numeric_limits<T>::max() : std::numeric_limits<T>::min();
    });
    return r;
}

// ============================ round trip ============================

// Each field of each record goes through every awkward value of its kind (sampleRecord cycles
// them by row), and through its type's limits.
TEST(SessionStore, RoundTripsEveryFieldBitExactly) {
    TempDir dir;
    SessionHeader header = sampleHeader("Zoë «P7»\n");
    header.protocolJson = std::string("{\"a\": \"nul\0inside\"}", 20);
    header.planId = "plan «ß»";
    header.playerModel = "{\"reaction_s\":0.2,\"note\":\"«ß»\"}";
    header.resumed = {{"0123456789abcdef0123456789abcdef", "P7_a.warplab-session", "2024-05-01T12:00:00.000Z",
                       "human (cm_per_360=0, dpi=800, invert_y=0)", 0, "2024-05-01T12:05:00.000Z"},
                      {"fedcba9876543210fedcba9876543210", "P7 \"b\".warplab-session", "2024-05-01T12:05:00.000Z",
                       "bot:3", std::numeric_limits<std::int64_t>::max(), "2024-05-02T09:00:00.000Z"}};

    constexpr int kRows = 60;  // a multiple of every cycle length above, and then some
    std::vector<InputRecord> inputs = {extremeRecord<InputRecord>(false)};
    std::vector<FrameRecord> frames = {extremeRecord<FrameRecord>(false)};
    std::vector<EventRecord> events = {extremeRecord<EventRecord>(false), extremeRecord<EventRecord>(true)};
    for (int n = 0; n < kRows; ++n) {
        inputs.push_back(sampleRecord<InputRecord>(n));
        frames.push_back(sampleRecord<FrameRecord>(n));
        events.push_back(sampleRecord<EventRecord>(n));
    }
    inputs.push_back(extremeRecord<InputRecord>(true));
    frames.push_back(extremeRecord<FrameRecord>(true));

    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), header);
        path = w.path();
        for (const auto& r : inputs) w.addInput(r);
        for (const auto& r : frames) w.addFrame(r);
        for (const auto& r : events) w.addEvent(r);
        w.finish();
    }
    const SessionData data = readSession(path);
    header.formatVersion = kSessionFormatVersion;
    expectSame(data.header, header);
    EXPECT_EQ(data.header.formatVersion, 6);
    // Drawn by create(), whatever the header passed in said.
    EXPECT_EQ(data.header.sessionId.size(), 32u);
    EXPECT_EQ(data.header.sessionId.find_first_not_of("0123456789abcdef"), std::string::npos) << data.header.sessionId;
    ASSERT_EQ(data.inputs.size(), inputs.size());
    ASSERT_EQ(data.frames.size(), frames.size());
    ASSERT_EQ(data.events.size(), events.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) expectSame(data.inputs[i], inputs[i]);
    for (std::size_t i = 0; i < frames.size(); ++i) expectSame(data.frames[i], frames[i]);
    for (std::size_t i = 0; i < events.size(); ++i) expectSame(data.events[i], events[i]);
    EXPECT_TRUE(data.completed);
    EXPECT_EQ(data.note, "");
    // finish() folds the WAL in: one self-contained file.
    EXPECT_EQ(filesIn(dir.path()).size(), 1u);
}

// NaN is stored as SQL NULL: it comes back as a NaN, not bit for bit.
TEST(SessionStore, NaNComesBackAsNaN) {
    TempDir dir;
    const auto nanEverywhere = [](auto record) {
        forEachField(record, [](const auto&, auto& v) {
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>)
                v = -std::numeric_limits<double>::signaling_NaN();
        });
        return record;
    };
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    w.addInput(nanEverywhere(sampleRecord<InputRecord>(0)));
    w.addFrame(nanEverywhere(sampleRecord<FrameRecord>(0)));
    w.addEvent(nanEverywhere(sampleRecord<EventRecord>(0)));
    w.finish();
    const SessionData data = readSession(w.path());
    ASSERT_EQ(data.inputs.size() + data.frames.size() + data.events.size(), 3u);
    EXPECT_TRUE(data.completed) << data.note;  // the checksums agree on what a NaN is
    int nans = 0;
    const auto expectNaNs = [&nans](const auto& record) {
        forEachField(record, [&nans](const auto& field, const auto& v) {
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>) {
                EXPECT_TRUE(std::isnan(v)) << field.column;
                ++nans;
            }
        });
    };
    expectNaNs(data.inputs[0]);
    expectNaNs(data.frames[0]);
    expectNaNs(data.events[0]);
    EXPECT_GT(nans, 0);
}

// The input table's text is what was typed, byte for byte: ASCII, multi-byte UTF-8, Backspace
// ('\b', as game::kTextBackspace types it), a long paste, nothing. Also what no keyboard
// types: an embedded NUL and bytes that are not UTF-8. The store keeps whatever it is given
// (texts are bound with their length), so a replay sees what was recorded, never a shortened
// or "repaired" text.
TEST(SessionStore, TypedTextRoundTripsByteForByte) {
    TempDir dir;
    const std::vector<std::string> typed = {"",
                                            "a",
                                            "Hello, world!",
                                            "Zoë ß «» 日本 🙂",
                                            "\b",
                                            "ab\b\bc\b",
                                            std::string("x\0y", 3),
                                            std::string(1, '\0'),
                                            "\xff\xfe",
                                            "\xe6\x97",  // a character cut short
                                            "'; DROP TABLE input; --",
                                            std::string(4000, 'k'),
                                            ""};
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        for (std::size_t i = 0; i < typed.size(); ++i) {
            InputRecord r = sampleRecord<InputRecord>(static_cast<std::int64_t>(i));
            r.text = typed[i];
            w.addInput(r);
            if (i % 4 == 3) w.commit();  // several commits, each checked against its checksum
        }
        w.finish();
    }
    const SessionData data = readSession(path);
    EXPECT_TRUE(data.completed) << data.note;
    ASSERT_EQ(data.inputs.size(), typed.size());
    for (std::size_t i = 0; i < typed.size(); ++i) {
        EXPECT_EQ(data.inputs[i].text.size(), typed[i].size()) << "row " << i;
        EXPECT_EQ(data.inputs[i].text, typed[i]) << "row " << i;
    }
    // And so SQL sees it: TEXT holding exactly those bytes.
    const auto stored = sqlRows(path,
                                "SELECT typeof(text) AS type, length(CAST(text AS BLOB)) AS bytes FROM input "
                                "ORDER BY frame");
    ASSERT_EQ(stored.size(), typed.size());
    for (std::size_t i = 0; i < typed.size(); ++i) {
        EXPECT_EQ(stored[i]["type"].get<std::string>(), "text") << "row " << i;
        EXPECT_EQ(stored[i]["bytes"].get<std::size_t>(), typed[i].size()) << "row " << i;
    }
}

// A run killed before its header was linked to a session name leaves a hidden .creating file;
// the next session in the folder removes those of runs that are gone, and leaves a running
// one's (and a fresh one, which another rig sharing the folder may be writing).
TEST(SessionStore, CreationsAKilledRunLeftAreRemovedByTheNext) {
    TempDir dir;
    auto touch = [&](const std::string& name, bool old) {
        const fs::path p = dir.path() / name;
        std::ofstream(p) << "x";
        if (old) fs::last_write_time(p, fs::file_time_type::clock::now() - std::chrono::minutes(5));
        return p;
    };
    const fs::path gone = touch(".P07_20240501T123456789Z.999999999.creating", true);
    const fs::path goneWal = touch(".P07_20240501T123456789Z.999999999.creating-wal", true);
    const fs::path fresh = touch(".P08_20240501T123456789Z.999999998.creating", false);
    const fs::path running = touch(".P09_20240501T123456789Z." + std::to_string(::getppid()) + ".creating", true);
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    EXPECT_FALSE(fs::exists(gone));
    EXPECT_FALSE(fs::exists(goneWal));
    EXPECT_TRUE(fs::exists(fresh));
    EXPECT_TRUE(fs::exists(running));
    w.finish();
}

TEST(SessionStore, FillsInTheStartTimeWhenEmpty) {
    TempDir dir;
    SessionHeader header = sampleHeader();
    header.startedAt.clear();
    SessionWriter w = SessionWriter::create(dir.str(), header);
    w.finish();
    const std::string started = readSession(w.path()).header.startedAt;
    ASSERT_EQ(started.size(), 24u) << started;  // 2024-05-01T12:34:56.789Z
    EXPECT_EQ(started[10], 'T');
    EXPECT_EQ(started.back(), 'Z');
    EXPECT_NE(w.path().find(started.substr(0, 4)), std::string::npos) << w.path();
}

// Analysts read the tables with plain SQL: every double column holds SQLite REALs with the
// same bits, -0.0 included (a REAL-affinity column would store it as the integer 0).
template <class R>
void expectSqlReals(sqlite3* db, const char* table, const std::vector<R>& written) {
    int checked = 0;
    for (const Field<R>& field : fieldsOf<R>()) {
        if (field.storage != Storage::Real) continue;
        SCOPED_TRACE(std::string(table) + "." + field.column);
        const std::string sql =
            std::string("SELECT typeof(") + field.column + "), " + field.column + " FROM " + table + " ORDER BY rowid";
        sqlite3_stmt* s = nullptr;
        ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr), SQLITE_OK) << sql;
        std::size_t row = 0;
        bool negativeZero = false;
        while (sqlite3_step(s) == SQLITE_ROW && row < written.size()) {
            const double expected = written[row++].*std::get<double R::*>(field.member);
            EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)), "real");
            EXPECT_TRUE(sameBits(sqlite3_column_double(s, 1), expected)) << "row " << row;
            negativeZero = negativeZero || sameBits(expected, -0.0);
        }
        sqlite3_finalize(s);
        EXPECT_EQ(row, written.size());
        EXPECT_TRUE(negativeZero);  // or this proved nothing about -0.0
        ++checked;
    }
    EXPECT_GT(checked, 0);
}

TEST(SessionStore, DoublesAreSqlRealsWithTheSameBits) {
    TempDir dir;
    std::vector<InputRecord> inputs;
    std::vector<FrameRecord> frames;
    std::vector<EventRecord> events;
    for (int n = 0; n < 30; ++n) {
        inputs.push_back(sampleRecord<InputRecord>(n));
        frames.push_back(sampleRecord<FrameRecord>(n));
        events.push_back(sampleRecord<EventRecord>(n));
    }
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        for (std::size_t i = 0; i < inputs.size(); ++i) {
            w.addInput(inputs[i]);
            w.addFrame(frames[i]);
            w.addEvent(events[i]);
        }
        w.finish();
    }
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    expectSqlReals(db, "input", inputs);
    expectSqlReals(db, "frames", frames);
    expectSqlReals(db, "events", events);
    sqlite3_close(db);
}

TEST(SessionStore, DiscardsTheUncommittedTail) {
    TempDir dir;
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        writeTrial(w, 0);
        writeTrial(w, 1);
        w.commit();
        writeTrial(w, 2);  // never committed: the writer goes away as in a crash
    }
    const SessionData data = readSession(path);
    EXPECT_EQ(expectWholeTrials(data), 2);
    EXPECT_FALSE(data.completed);
    EXPECT_EQ(data.note, "incomplete: ends after frame 95 (last commit, 1 in all)");
}

// A flag (e.g. too many missed vsyncs) is stored with the next commit, outside the header's
// checksum, and the latest of a name wins; an uncommitted one is lost like any other row.
TEST(SessionStore, FlagsTravelWithTheNextCommit) {
    TempDir dir;
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        writeTrial(w, 0);
        w.flag("missed_frames", "first");
        w.flag("missed_frames", "12 of 600 frames missed their vsync");
        w.commit();
        w.flag("other", "never committed");
    }
    const SessionData data = readSession(path);
    EXPECT_EQ(data.flags.size(), 1u);
    EXPECT_EQ(data.flags.at("missed_frames"), "12 of 600 frames missed their vsync");
    EXPECT_EQ(expectWholeTrials(data), 1);
}

// A summary (the pacing at the end of a live session) travels like a flag, under its own name:
// never taken for a flag, kept through the finish's rewrite.
TEST(SessionStore, SummariesTravelWithTheNextCommitApartFromFlags) {
    TempDir dir;
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        writeTrial(w, 0);
        w.summarize("pacing", "[]");
        w.flag("pacing", "a flag of the same name");
        w.commit();
        w.summarize("pacing", "[{\"mode\":\"conv60\"}]");
        w.summarize("unsaid", "never committed");
        w.finish();
    }
    const SessionData data = readSession(path);
    EXPECT_TRUE(data.completed);
    EXPECT_EQ(data.summaries.size(), 2u);  // finish() commits what was added
    EXPECT_EQ(data.summaries.at("pacing"), "[{\"mode\":\"conv60\"}]");
    EXPECT_EQ(data.flags.size(), 1u);
    EXPECT_EQ(data.flags.at("pacing"), "a flag of the same name");
}

TEST(SessionStore, ReadsARunningSessionUpToItsLastCommit) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    EXPECT_EQ(readSession(w.path()).note, "incomplete: no trial was committed");
    writeTrial(w, 0);
    w.commit();
    writeTrial(w, 1);  // in an open transaction while we read
    const SessionData data = readSession(w.path());
    EXPECT_EQ(expectWholeTrials(data), 1);
    EXPECT_FALSE(data.completed);
    w.commit();
    EXPECT_EQ(expectWholeTrials(readSession(w.path())), 2);
}

TEST(SessionStore, RejectsRecordsOutOfOrderAndBadDetail) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    w.addInput(trialInput(10));
    EXPECT_THROW(w.addInput(trialInput(10)), std::invalid_argument);
    EXPECT_THROW(w.addInput(trialInput(9)), std::invalid_argument);
    w.addFrame(trialFrame(3));
    EXPECT_THROW(w.addFrame(trialFrame(2)), std::invalid_argument);
    // Every detail_json column holds a JSON object or "".
    for (const std::string bad : {"[1, 2]", "{not json", "3", "\"text\"", "{} {}"}) {
        SCOPED_TRACE(bad);
        EventRecord e = trialEvent(0, 1);
        e.detailJson = bad;
        EXPECT_THROW(w.addEvent(e), std::invalid_argument);
        FrameRecord f = trialFrame(4);
        f.detailJson = bad;
        EXPECT_THROW(w.addFrame(f), std::invalid_argument);
    }
    w.commit();
    const SessionData data = readSession(w.path());
    EXPECT_EQ(data.inputs.size(), 1u);
    EXPECT_EQ(data.frames.size(), 1u);
    EXPECT_EQ(data.events.size(), 0u);
    w.finish();
    EXPECT_THROW(w.addInput(trialInput(11)), std::logic_error);
    SessionWriter moved = std::move(w);
    EXPECT_THROW(w.commit(), std::logic_error);  // NOLINT(bugprone-use-after-move)
    EXPECT_TRUE(readSession(moved.path()).completed);
}

}  // namespace
}  // namespace warplab::session
