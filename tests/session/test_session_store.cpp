// The session store and its record definitions: exact round trip, crash safety (a real SIGKILL
// mid-session), damaged files, format versions (version-1 files read and map onto today's
// records), checksums as documented, replay's record comparison (firstDifference), the field
// tables against the documented schema, and participant ids that try to be paths.
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
#include "temp_dir.h"

namespace warplab::session {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
using testing::execSql;
using testing::TempDir;

std::vector<fs::path> filesIn(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& entry : fs::directory_iterator(dir)) out.push_back(entry.path());
    return out;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

SessionHeader sampleHeader(const std::string& participant = "P07") {
    SessionHeader h;
    h.protocolJson = R"({"study": "shooter", "modes": ["conv15", "conv120", "warp15to120"]})";
    h.seed = 18446744073709551557ull;  // above INT64_MAX: must not go through a signed column
    h.participant = participant;
    h.appVersion = "0.1.0";
    h.glRenderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
    h.glVersion = "4.5 (Core Profile) Mesa 22.3.6";
    h.refreshHz = 143.98 + 1.0 / 3.0;
    h.displayWidth = 2560;
    h.displayHeight = 1440;
    h.startedAt = "2024-05-01T12:34:56.789Z";
    h.player = "bot:7";
    return h;
}

// ---- records built and compared through the field tables (session/records.h) ----
// Nothing here names a record's fields: a field added to a table is written, read, compared
// and checksummed by every test below without a change here.

// Awkward values each field cycles through. Doubles: -0.0 (which a REAL column would turn
// into the integer 0), a subnormal, the extremes, infinities; NaN has its own test, as it
// does not come back bit for bit.
const std::vector<double> kDoubles = {-0.0,
                                      1.0 / 3.0,
                                      std::numeric_limits<double>::denorm_min(),
                                      -std::numeric_limits<double>::max(),
                                      std::nextafter(1.0, 2.0),
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(),
                                      -7.3125e-300,
                                      0.1 + 0.2};
const std::vector<std::string> kTexts = {"warp15to120", "Zoë «P7»", std::string("nul\0inside", 10),
                                         "'; DROP TABLE frames; --", ""};
const std::vector<std::string> kJsonObjects = {"", R"({"ids": [2, 16], "note": "ünï", "x": -0.0})",
                                               R"({"nested":{"a":[1,2.5,"\u0000"]}})"};

// Every field of a record as a pure function of n (and of the field's place in its table, so
// that neighbouring fields differ). The frame is n.
template <class R>
R sampleRecord(std::int64_t n) {
    R r;
    std::size_t k = 0;
    forEachField(r, [&](const Field<R>& field, auto& v) {
        using T = std::decay_t<decltype(v)>;
        const auto i = static_cast<std::size_t>(n) + k++;
        if constexpr (std::is_same_v<T, double>) {
            v = i % 10 == 9 ? std::sqrt(static_cast<double>(n)) * static_cast<double>(k)
                            : kDoubles[i % 10 % kDoubles.size()];
        } else if constexpr (std::is_same_v<T, std::string>) {
            if (field.storage == Storage::JsonObject)
                v = i % 4 == 3 ? R"({"n": )" + std::to_string(n) + "}" : kJsonObjects[i % 4 % kJsonObjects.size()];
            else
                v = i % 6 == 5 ? std::string() : kTexts[i % 6 % kTexts.size()] + std::to_string(n);
        } else if constexpr (std::is_same_v<T, std::uint32_t>) {
            v = static_cast<std::uint32_t>(static_cast<std::uint64_t>(n) * 2654435761u + k);
        } else {
            v = static_cast<T>((n * 7 + static_cast<std::int64_t>(k)) % 1000 - 500);
        }
    });
    r.frame = n;
    return r;
}

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

// Field by field, doubles bit for bit, texts byte for byte (JSON text too: the store keeps
// what it was given, it does not re-serialise).
template <class R>
void expectSame(const R& actual, const R& expected) {
    for (const Field<R>& field : fieldsOf<R>())
        std::visit(
            [&](auto member) {
                const auto& a = actual.*member;
                const auto& b = expected.*member;
                if constexpr (std::is_same_v<std::decay_t<decltype(a)>, double>)
                    EXPECT_TRUE(sameBits(a, b))
                        << field.column << " of frame " << expected.frame << ": " << a << " != " << b;
                else
                    EXPECT_EQ(a, b) << field.column << " of frame " << expected.frame;
            },
            field.member);
}

// ---- what a study writes per trial: a pure function of the trial index ----

constexpr int kFramesPerTrial = 48;
constexpr int kEventsPerTrial = 2;

InputRecord trialInput(std::int64_t frame) { return sampleRecord<InputRecord>(frame); }
FrameRecord trialFrame(std::int64_t frame) { return sampleRecord<FrameRecord>(frame); }
EventRecord trialEvent(int trial, int k) {
    EventRecord e = sampleRecord<EventRecord>(trial * kEventsPerTrial + k);
    const std::int64_t first = static_cast<std::int64_t>(trial) * kFramesPerTrial;
    e.frame = k == 0 ? first : first + kFramesPerTrial - 1;
    return e;
}

void writeTrial(SessionWriter& w, int trial) {
    w.addEvent(trialEvent(trial, 0));
    for (int i = 0; i < kFramesPerTrial; ++i) {
        const std::int64_t frame = static_cast<std::int64_t>(trial) * kFramesPerTrial + i;
        w.addInput(trialInput(frame));
        w.addFrame(trialFrame(frame));
    }
    w.addEvent(trialEvent(trial, 1));
}

void expectSame(const SessionHeader& a, const SessionHeader& b) {
    EXPECT_EQ(a.protocolJson, b.protocolJson);
    EXPECT_EQ(a.seed, b.seed);
    EXPECT_EQ(a.participant, b.participant);
    EXPECT_EQ(a.appVersion, b.appVersion);
    EXPECT_EQ(a.glRenderer, b.glRenderer);
    EXPECT_EQ(a.glVersion, b.glVersion);
    EXPECT_TRUE(sameBits(a.refreshHz, b.refreshHz));
    EXPECT_EQ(a.displayWidth, b.displayWidth);
    EXPECT_EQ(a.displayHeight, b.displayHeight);
    EXPECT_EQ(a.startedAt, b.startedAt);
    EXPECT_EQ(a.player, b.player);
    EXPECT_EQ(a.planId, b.planId);
    EXPECT_EQ(a.playerModel, b.playerModel);
    ASSERT_EQ(a.resumed.size(), b.resumed.size());
    for (std::size_t i = 0; i < a.resumed.size(); ++i) {
        EXPECT_EQ(a.resumed[i].sessionId, b.resumed[i].sessionId);
        EXPECT_EQ(a.resumed[i].file, b.resumed[i].file);
        EXPECT_EQ(a.resumed[i].startedAt, b.resumed[i].startedAt);
        EXPECT_EQ(a.resumed[i].player, b.resumed[i].player);
        EXPECT_EQ(a.resumed[i].frame, b.resumed[i].frame);
        EXPECT_EQ(a.resumed[i].resumedAt, b.resumed[i].resumedAt);
    }
    EXPECT_EQ(a.formatVersion, b.formatVersion);
}

// Holds when `data` is exactly trials 0 .. n-1 as writeTrial writes them; returns n.
// Anything else -- a partial trial, a changed value -- fails the calling test.
int expectWholeTrials(const SessionData& data) {
    const int trials = static_cast<int>(data.events.size()) / kEventsPerTrial;
    const auto whole = [&](std::size_t perTrial) { return static_cast<std::size_t>(trials) * perTrial; };
    const bool sized = data.events.size() == whole(kEventsPerTrial) && data.inputs.size() == whole(kFramesPerTrial) &&
        data.frames.size() == whole(kFramesPerTrial);
    EXPECT_TRUE(sized) << "not whole trials: " << data.inputs.size() << " inputs, " << data.frames.size() << " frames, "
                       << data.events.size() << " events";
    if (!sized) return -1;
    for (std::size_t i = 0; i < data.inputs.size(); ++i) {
        expectSame(data.inputs[i], trialInput(static_cast<std::int64_t>(i)));
        expectSame(data.frames[i], trialFrame(static_cast<std::int64_t>(i)));
    }
    for (std::size_t i = 0; i < data.events.size(); ++i)
        expectSame(data.events[i],
                   trialEvent(static_cast<int>(i) / kEventsPerTrial, static_cast<int>(i) % kEventsPerTrial));
    return trials;
}

// ---- raw SQLite access, to tamper with files the way the outside world might ----

// Copies a session to dst as if the disk had lost the rest: the main file cut to mainBytes
// (kWhole: all of it) and the WAL cut to walBytes (kWhole: all of it; kNoWal: not copied, as
// if deleted). Stale -shm files of earlier copies are removed first.
constexpr std::intmax_t kWhole = -1;
constexpr std::intmax_t kNoWal = -2;
void copySession(const std::string& src, const std::string& dst, std::intmax_t mainBytes, std::intmax_t walBytes) {
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(dst + suffix);
    fs::copy_file(src, dst);
    if (mainBytes != kWhole) fs::resize_file(dst, static_cast<std::uintmax_t>(mainBytes));
    if (walBytes != kNoWal && fs::exists(src + "-wal")) {
        fs::copy_file(src + "-wal", dst + "-wal");
        if (walBytes != kWhole) fs::resize_file(dst + "-wal", static_cast<std::uintmax_t>(walBytes));
    }
}

// A finished session of `trials` trials, each committed on its own; returns its path.
std::string writeFinishedSession(const std::string& dir, int trials) {
    SessionWriter w = SessionWriter::create(dir, sampleHeader());
    const std::string path = w.path();
    for (int t = 0; t < trials; ++t) {
        writeTrial(w, t);
        w.commit();
    }
    w.finish();
    return path;
}

std::string errorOf(const std::string& path) {
    try {
        readSession(path);
    } catch (const SessionError& e) {
        return e.what();
    }
    return "";
}

// A statement's rows as column name -> value (NULL as an empty json), in order.
std::vector<nlohmann::json> sqlRows(const std::string& path, const std::string& sql) {
    std::vector<nlohmann::json> rows;
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr), SQLITE_OK) << sql;
    while (s && sqlite3_step(s) == SQLITE_ROW) {
        nlohmann::json row = nlohmann::json::object();
        for (int i = 0; i < sqlite3_column_count(s); ++i) {
            auto& v = row[sqlite3_column_name(s, i)];
            switch (sqlite3_column_type(s, i)) {
                case SQLITE_INTEGER: v = sqlite3_column_int64(s, i); break;
                case SQLITE_FLOAT: v = sqlite3_column_double(s, i); break;
                case SQLITE_TEXT:
                    v = std::string(reinterpret_cast<const char*>(sqlite3_column_text(s, i)),
                                    static_cast<std::size_t>(sqlite3_column_bytes(s, i)));
                    break;
                default: break;
            }
        }
        rows.push_back(std::move(row));
    }
    sqlite3_finalize(s);
    sqlite3_close(db);
    return rows;
}

// FNV-1a 64 over the byte stream docs/session-format.md describes ("Checksums"), written from
// the page rather than from the store's code.
struct Fnv {
    std::uint64_t hash = 0xcbf29ce484222325ull;
    void bytes(const void* data, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i)
            hash = (hash ^ static_cast<const unsigned char*>(data)[i]) * 0x100000001b3ull;
    }
    void integer(std::int64_t v) {
        unsigned char le[8];
        for (int i = 0; i < 8; ++i) le[i] = static_cast<unsigned char>(static_cast<std::uint64_t>(v) >> (8 * i));
        bytes(le, 8);
    }
    void value(double v) {
        std::int64_t bits;
        if (std::isnan(v)) v = std::numeric_limits<double>::quiet_NaN();
        std::memcpy(&bits, &v, 8);
        integer(bits);
    }
    void value(const std::string& v) {
        integer(static_cast<std::int64_t>(v.size()));
        bytes(v.data(), v.size());
    }
    template <class T>
    void value(T v) {
        integer(static_cast<std::int64_t>(v));
    }
};

// Changes a file's format_version and recomputes its header checksum, so that the reader gets
// past the header and checks the tables against that version's schema.
void relabel(const std::string& path, int version) {
    execSql(path, "UPDATE meta SET value = '" + std::to_string(version) + "' WHERE key = 'format_version'");
    Fnv h;
    std::vector<std::string> keys = {"format_version", "protocol_json",  "seed",       "participant",
                                     "app_version",    "gl_renderer",    "gl_version", "refresh_hz",
                                     "display_width",  "display_height", "started_at", "player"};
    if (version >= 3) {
        keys.push_back("session_id");
        keys.push_back("plan_id");
    }
    if (version >= 4) keys.push_back("resumed");
    if (version >= 6) keys.push_back("player_model");
    for (const std::string& key : keys) {
        const auto rows = sqlRows(path, "SELECT value FROM meta WHERE key = '" + key + "'");
        ASSERT_EQ(rows.size(), 1u) << key;
        h.value(key);
        h.value(rows[0]["value"].get<std::string>());
    }
    execSql(path, "UPDATE meta SET value = '" + std::to_string(h.hash) + "' WHERE key = 'header_checksum'");
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
// A read-only connection that keeps a read transaction open, as an analyst's DB browser may:
// it holds the writer's checkpoint back, so commits made meanwhile stay in the -wal.
class SnapshotReader {
public:
    explicit SnapshotReader(const std::string& path) {
        ok_ = sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK &&
            sqlite3_exec(db_, "BEGIN; SELECT count(*) FROM events;", nullptr, nullptr, nullptr) == SQLITE_OK;
    }
    ~SnapshotReader() {
        sqlite3_exec(db_, "COMMIT", nullptr, nullptr, nullptr);
        sqlite3_close(db_);
    }
    SnapshotReader(const SnapshotReader&) = delete;
    SnapshotReader& operator=(const SnapshotReader&) = delete;
    bool ok() const { return ok_; }

private:
    sqlite3* db_ = nullptr;
    bool ok_ = false;
};

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

// ============================ checksums ============================

// The serialisation docs/session-format.md spells out, computed here from the rows read back
// and the field tables: a commit's checksum is FNV-1a 64 of the three tables' hashes, each over
// its rows' fields in table order, after the checksum of the commit before it (the header's
// for the first). Written independently of the store's own Checksum.
TEST(SessionStoreChecksum, FollowsTheDocumentedSerialisation) {
    TempDir dir;
    const std::string path = writeFinishedSession(dir.str(), 3);
    const SessionData data = readSession(path);
    ASSERT_TRUE(data.completed) << data.note;

    const auto rowsHash = [](const auto& rows, std::size_t from, std::size_t to) {
        Fnv h;
        for (std::size_t i = from; i < to; ++i) forEachField(rows[i], [&h](const auto&, const auto& v) { h.value(v); });
        return h.hash;
    };
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db,
                                 "SELECT input_rows, frame_rows, event_rows, checksum FROM commits "
                                 "ORDER BY id",
                                 -1, &s, nullptr),
              SQLITE_OK);
    std::size_t inputs = 0, frames = 0, events = 0;
    int commits = 0;
    const auto headerChecksum = sqlRows(path, "SELECT value FROM meta WHERE key = 'header_checksum'");
    ASSERT_EQ(headerChecksum.size(), 1u);
    auto previous = static_cast<std::int64_t>(std::stoull(headerChecksum[0]["value"].get<std::string>()));
    while (sqlite3_step(s) == SQLITE_ROW) {
        const auto in = static_cast<std::size_t>(sqlite3_column_int64(s, 0));
        const auto fr = static_cast<std::size_t>(sqlite3_column_int64(s, 1));
        const auto ev = static_cast<std::size_t>(sqlite3_column_int64(s, 2));
        Fnv commit;
        commit.integer(previous);
        commit.integer(static_cast<std::int64_t>(rowsHash(data.inputs, inputs, in)));
        commit.integer(static_cast<std::int64_t>(rowsHash(data.frames, frames, fr)));
        commit.integer(static_cast<std::int64_t>(rowsHash(data.events, events, ev)));
        EXPECT_EQ(static_cast<std::int64_t>(commit.hash), sqlite3_column_int64(s, 3)) << "commit " << commits + 1;
        previous = sqlite3_column_int64(s, 3);
        inputs = in;
        frames = fr;
        events = ev;
        ++commits;
    }
    sqlite3_finalize(s);
    sqlite3_close(db);
    EXPECT_EQ(commits, 3);
}

// ============================ version 1 ============================
// tests/data/v1-shooter-quick.warplab-session was written by the version-1 store (see
// tests/data/README.md). Its rows are checked against the file's own columns, read here with
// plain SQL.

std::string v1Fixture() { return std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v1-shooter-quick.warplab-session"; }

// The columns version 1 shares with today's records read back unchanged.
template <class R>
void expectSharedColumns(const std::vector<nlohmann::json>& raw, const std::vector<R>& records) {
    ASSERT_EQ(raw.size(), records.size());
    for (std::size_t i = 0; i < raw.size(); ++i)
        forEachField(records[i], [&](const Field<R>& field, const auto& v) {
            if (field.storage == Storage::JsonObject) return;  // folded; tested on its own
            using T = std::decay_t<decltype(v)>;
            if (!raw[i].contains(field.column)) {  // newer than version 1 (render_ms): its default
                EXPECT_EQ(v, T{}) << field.column << " row " << i;
                return;
            }
            const nlohmann::json& cell = raw[i].at(field.column);
            if constexpr (std::is_same_v<T, double>)
                EXPECT_TRUE(sameBits(cell.get<double>(), v)) << field.column << " row " << i;
            else
                EXPECT_EQ(cell.get<T>(), v) << field.column << " row " << i;
        });
}

TEST(SessionStoreV1, ReadsTheVersion1Fixture) {
    const SessionData data = readSession(v1Fixture());
    EXPECT_EQ(data.header.formatVersion, 1);
    EXPECT_EQ(data.header.participant, "v1-fixture");
    EXPECT_EQ(data.header.seed, 5u);
    EXPECT_EQ(data.header.player, "bot:3");
    EXPECT_EQ(data.header.displayWidth, 640);
    EXPECT_EQ(data.header.displayHeight, 360);
    // Complete with no note: every commit verified against the checksum version 1 computed.
    EXPECT_TRUE(data.completed);
    EXPECT_EQ(data.note, "");
    EXPECT_EQ(data.inputs.size(), 4686u);
    EXPECT_EQ(data.frames.size(), 4686u);
    EXPECT_EQ(data.events.size(), 48u);
    expectSharedColumns(sqlRows(v1Fixture(), "SELECT * FROM input ORDER BY frame"), data.inputs);
    expectSharedColumns(sqlRows(v1Fixture(), "SELECT * FROM frames ORDER BY frame"), data.frames);
    expectSharedColumns(sqlRows(v1Fixture(), "SELECT * FROM events ORDER BY id"), data.events);
}

// ============================ version 2 ============================
// tests/data/v2-click-quick.warplab-session was written by the version-2 store (see
// tests/data/README.md): no session id, commit checksums not chained.

TEST(SessionStoreV2, ReadsTheVersion2FixtureAgainstItsUnchainedChecksums) {
    const std::string fixture = std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v2-click-quick.warplab-session";
    const SessionData data = readSession(fixture);
    EXPECT_EQ(data.header.formatVersion, 2);
    EXPECT_EQ(data.header.sessionId, "");
    EXPECT_EQ(data.header.participant, "v2-fixture");
    EXPECT_EQ(data.header.seed, 5u);
    EXPECT_TRUE(data.completed);
    EXPECT_EQ(data.note, "");
    EXPECT_EQ(data.inputs.size(), 4699u);
    EXPECT_EQ(data.frames.size(), 4699u);
    EXPECT_EQ(data.events.size(), 164u);
    expectSharedColumns(sqlRows(fixture, "SELECT * FROM input ORDER BY frame"), data.inputs);
}

// ============================ version 3 ============================
// tests/data/v3-shooter-quick.warplab-session was written by the version-3 store (see
// tests/data/README.md): a session id and chained checksums, no record of resumption.

TEST(SessionStoreV3, ReadsTheVersion3FixtureAgainstItsChainedChecksums) {
    const std::string fixture = std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v3-shooter-quick.warplab-session";
    const SessionData data = readSession(fixture);
    EXPECT_EQ(data.header.formatVersion, 3);
    EXPECT_EQ(data.header.sessionId, "3104661b4699d13a2eeadd6106950de6");
    EXPECT_EQ(data.header.planId, "");
    EXPECT_TRUE(data.header.resumed.empty());
    EXPECT_EQ(data.header.participant, "v3-fixture");
    EXPECT_EQ(data.header.seed, 5u);
    EXPECT_TRUE(data.completed);
    EXPECT_FALSE(data.damaged);
    EXPECT_EQ(data.note, "");
    EXPECT_EQ(data.inputs.size(), 4686u);
    EXPECT_EQ(data.frames.size(), 4686u);
    EXPECT_EQ(data.events.size(), 48u);
    expectSharedColumns(sqlRows(fixture, "SELECT * FROM events ORDER BY id"), data.events);
}

// ============================ version 4 ============================
// tests/data/v4-click-quick.warplab-session was written by the version-4 store (see
// tests/data/README.md): its input table has no `text`, and its checksums were computed
// without one.

std::string v4Fixture() { return std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v4-click-quick.warplab-session"; }

TEST(SessionStoreV4, ReadsTheVersion4FixtureWithNothingTyped) {
    const SessionData data = readSession(v4Fixture());
    EXPECT_EQ(data.header.formatVersion, 4);
    EXPECT_EQ(data.header.sessionId, "b2178aa22c32feaa69fff36269ab424e");
    EXPECT_TRUE(data.header.resumed.empty());
    EXPECT_EQ(data.header.participant, "v4-fixture");
    EXPECT_EQ(data.header.seed, 5u);
    // Complete with no note: every commit verified against the checksum version 4 computed.
    EXPECT_TRUE(data.completed);
    EXPECT_FALSE(data.damaged);
    EXPECT_EQ(data.note, "");
    EXPECT_EQ(data.inputs.size(), 306u);
    EXPECT_EQ(data.frames.size(), 306u);
    EXPECT_EQ(data.events.size(), 14u);
    const auto raw = sqlRows(v4Fixture(), "SELECT * FROM input ORDER BY frame");
    ASSERT_FALSE(raw.empty());
    EXPECT_FALSE(raw[0].contains("text")) << raw[0].dump();
    expectSharedColumns(raw, data.inputs);  // and text, which it lacks, is ""
    for (const InputRecord& in : data.inputs) EXPECT_EQ(in.text, "") << "frame " << in.frame;
    expectSharedColumns(sqlRows(v4Fixture(), "SELECT * FROM frames ORDER BY frame"), data.frames);
    expectSharedColumns(sqlRows(v4Fixture(), "SELECT * FROM events ORDER BY id"), data.events);
}

// Read by its own version's columns: its checksums still cover the six input columns it has,
// a `text` column added to it is not read, and a file that says it is version 5 must have one.
TEST(SessionStoreV4, ReadsItsOwnInputColumnsAndChecksThem) {
    TempDir dir;
    const std::string copy = (dir.path() / "v4.warplab-session").string();
    for (const std::string change : {"UPDATE input SET mouse_dx = mouse_dx + 1 WHERE frame = 200",
                                     "UPDATE input SET keys = keys + 2 WHERE frame = 200"}) {
        SCOPED_TRACE(change);
        copySession(v4Fixture(), copy, kWhole, kNoWal);
        execSql(copy, change);
        const SessionData data = readSession(copy);
        EXPECT_FALSE(data.completed);
        EXPECT_NE(data.note.find("the rows of commit 6 do not match its checksum"), std::string::npos) << data.note;
        EXPECT_EQ(data.inputs.size(), 169u);  // commit 5's
    }

    copySession(v4Fixture(), copy, kWhole, kNoWal);
    execSql(copy, "ALTER TABLE input ADD COLUMN text TEXT NOT NULL DEFAULT 'typed'");
    const SessionData extra = readSession(copy);
    EXPECT_TRUE(extra.completed) << extra.note;
    ASSERT_EQ(extra.inputs.size(), 306u);
    EXPECT_EQ(extra.inputs[0].text, "");

    copySession(v4Fixture(), copy, kWhole, kNoWal);
    relabel(copy, 5);
    const std::string error = errorOf(copy);
    EXPECT_NE(error.find("does not match the session format 5 schema"), std::string::npos) << error;
    EXPECT_NE(error.find("text"), std::string::npos) << error;
}

TEST(SessionStoreV1, FoldsShooterColumnsIntoEventDetail) {
    const SessionData data = readSession(v1Fixture());
    const auto raw = sqlRows(v1Fixture(), "SELECT * FROM events ORDER BY id");
    ASSERT_EQ(raw.size(), data.events.size());
    const std::vector<std::string> timing = {"target_speed", "spawn_time", "aim_time", "angular_error_deg"};
    std::map<std::string, int> types;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        const EventRecord& e = data.events[i];
        SCOPED_TRACE("event " + std::to_string(i + 1) + " (" + e.type + "): " + e.detailJson);
        ++types[e.type];
        const auto detail = nlohmann::json::parse(e.detailJson);
        // Sorted keys, nlohmann's own text: what the shooter writes today.
        EXPECT_EQ(e.detailJson, detail.dump());

        // What version 1 had in detail_json is kept as it was, and the folded keys come in.
        nlohmann::json expected = raw[i]["detail_json"].get<std::string>().empty()
            ? nlohmann::json::object()
            : nlohmann::json::parse(raw[i]["detail_json"].get<std::string>());
        expected["difficulty"] = raw[i]["difficulty"];
        std::vector<std::string> folded;
        if (e.type == "shot" || e.type == "timeout")
            folded = timing;
        else if (e.type == "level")
            folded = {"target_speed"};
        for (const std::string& key : folded) expected[key] = raw[i][key];
        ASSERT_EQ(detail.size(), expected.size());
        for (auto it = expected.begin(); it != expected.end(); ++it) {
            ASSERT_TRUE(detail.contains(it.key())) << it.key();
            const auto& got = detail[it.key()];
            if (it.value().is_number_float())
                EXPECT_TRUE(got.is_number_float() && sameBits(got.get<double>(), it.value().get<double>()))
                    << it.key() << ": " << got << " vs " << it.value();
            else
                EXPECT_EQ(got, it.value()) << it.key();
        }
        EXPECT_TRUE(detail["difficulty"].is_number_integer());
    }
    // The fixture has each kind the fold treats differently.
    EXPECT_GT(types["shot"], 10);
    EXPECT_GT(types["level"], 0);
    EXPECT_GT(types["phase"], 0);
    EXPECT_GT(types["training_limit"], 0);

    // A spot check with the shooter's meaning, not the fold's code: a shot's five keys hold
    // plausible values.
    const auto shot =
        std::find_if(data.events.begin(), data.events.end(), [](const EventRecord& e) { return e.type == "shot"; });
    ASSERT_NE(shot, data.events.end());
    const auto detail = nlohmann::json::parse(shot->detailJson);
    for (const char* key :
         {"difficulty", "target_speed", "spawn_time", "aim_time", "angular_error_deg", "scored", "start_x", "plane_z"})
        EXPECT_TRUE(detail.contains(key)) << key << " missing from " << shot->detailJson;
    EXPECT_GE(detail["difficulty"].get<int>(), 0);
    EXPECT_GT(detail["target_speed"].get<double>(), 0.0);
    EXPECT_GT(detail["aim_time"].get<double>(), 0.0);
    EXPECT_LT(detail["aim_time"].get<double>(), 10.0);
    EXPECT_NEAR(detail["aim_time"].get<double>(), shot->eventTime - detail["spawn_time"].get<double>(), 1e-9);
    EXPECT_GE(detail["angular_error_deg"].get<double>(), 0.0);
    EXPECT_LT(detail["angular_error_deg"].get<double>(), 180.0);
}

TEST(SessionStoreV1, FrameTargetsBecomeDetail) {
    const SessionData data = readSession(v1Fixture());
    const auto raw = sqlRows(v1Fixture(),
                             "SELECT target_x, target_y, target_z, target_visible FROM frames "
                             "ORDER BY frame");
    ASSERT_EQ(raw.size(), data.frames.size());
    int visible = 0, hidden = 0;
    for (std::size_t i = 0; i < raw.size(); ++i) {
        const std::string& detail = data.frames[i].detailJson;
        if (raw[i]["target_visible"] == 0) {
            EXPECT_EQ(detail, "") << "frame " << i;
            ++hidden;
            continue;
        }
        ++visible;
        const auto target = nlohmann::json::parse(detail);
        ASSERT_EQ(target.size(), 1u) << detail;
        ASSERT_EQ(target["target"].size(), 3u) << detail;
        int axis = 0;
        for (const char* column : {"target_x", "target_y", "target_z"})
            EXPECT_TRUE(sameBits(target["target"][axis++].get<double>(), raw[i][column].get<double>()))
                << "frame " << i << " " << column << ": " << detail;
        EXPECT_EQ(detail, target.dump());
        if (::testing::Test::HasFailure()) break;
    }
    EXPECT_GT(visible, 1000);
    EXPECT_GT(hidden, 0);
}

// Version 1's checksums cover its own columns, target and shooter ones included: a changed
// value there drops the commit it belongs to and everything after.
TEST(SessionStoreV1, ChangedVersion1ColumnsFailTheirCommit) {
    TempDir dir;
    const std::string copy = (dir.path() / "v1.warplab-session").string();
    const SessionData whole = readSession(v1Fixture());
    for (const std::string change : {"UPDATE frames SET target_x = target_x + 1e-9 WHERE frame = 3000",
                                     "UPDATE frames SET target_visible = 1 - target_visible WHERE frame = 3000",
                                     "UPDATE events SET aim_time = aim_time * 2 WHERE id = 40",
                                     "UPDATE events SET difficulty = difficulty + 1 WHERE id = 40"}) {
        SCOPED_TRACE(change);
        copySession(v1Fixture(), copy, kWhole, kNoWal);
        execSql(copy, change);
        const SessionData data = readSession(copy);
        EXPECT_FALSE(data.completed);
        EXPECT_NE(data.note.find("do not match its checksum"), std::string::npos) << data.note;
        EXPECT_LT(data.events.size(), 40u);
        EXPECT_LT(data.frames.size(), whole.frames.size());
        EXPECT_GT(data.frames.size(), 0u);
    }
    // target_visible is 0 or 1, whatever a changed file holds (its CHECK switched off here).
    copySession(v1Fixture(), copy, kWhole, kNoWal);
    execSql(copy,
            "PRAGMA ignore_check_constraints = ON; "
            "UPDATE frames SET target_visible = 2 WHERE frame = 3000");
    const SessionData data = readSession(copy);
    EXPECT_EQ(data.note.rfind("damaged (frames table: row 3001 has a value of the wrong type)", 0), 0u) << data.note;
    EXPECT_LT(data.frames.size(), 3001u);
}

// ============================ firstDifference ============================

TEST(Records, FirstDifferenceIsEmptyForIdenticalRecords) {
    for (std::int64_t n = 0; n < 20; ++n) {
        EXPECT_EQ(firstDifference(sampleRecord<InputRecord>(n), sampleRecord<InputRecord>(n)), "");
        EXPECT_EQ(firstDifference(sampleRecord<FrameRecord>(n), sampleRecord<FrameRecord>(n)), "");
        EXPECT_EQ(firstDifference(sampleRecord<EventRecord>(n), sampleRecord<EventRecord>(n)), "");
    }
}

// Changing any one field, and only it, is reported under that field's name.
template <class R>
void expectEachFieldNamed() {
    const R logged = sampleRecord<R>(3);
    for (const Field<R>& field : fieldsOf<R>()) {
        SCOPED_TRACE(field.column);
        R replayed = logged;
        std::visit(
            [&](auto member) {
                auto& v = replayed.*member;
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, std::string>)
                    v = field.storage == Storage::JsonObject ? R"({"changed": 1})" : v + "!";
                else if constexpr (std::is_same_v<T, double>)
                    v = std::nextafter(v, 1e300);
                else
                    v = static_cast<T>(v + 1);
            },
            field.member);
        const std::string diff = firstDifference(logged, replayed);
        const std::string name = field.storage == Storage::JsonObject ? "detail." : field.column;
        EXPECT_EQ(diff.rfind("field '" + name, 0), 0u) << diff;
        EXPECT_NE(diff.find(" logged "), std::string::npos) << diff;
        EXPECT_NE(diff.find(", replayed "), std::string::npos) << diff;
    }
}

TEST(Records, FirstDifferenceNamesTheChangedColumn) {
    expectEachFieldNamed<InputRecord>();
    expectEachFieldNamed<FrameRecord>();
    expectEachFieldNamed<EventRecord>();

    EventRecord logged;
    logged.frame = 120;
    logged.type = "shot";
    logged.trial = 4;
    logged.eventTime = 0.1;
    logged.detailJson = R"({"aim_time":0.5})";
    EventRecord replayed = logged;
    replayed.trial = 5;
    replayed.eventTime = 0.2;
    replayed.type = "timeout";
    // The first differing column in table order, whatever else differs after it.
    EXPECT_EQ(firstDifference(logged, replayed), "field 'type' logged 'shot', replayed 'timeout'");
    replayed.type = "shot";
    EXPECT_EQ(firstDifference(logged, replayed), "field 'trial' logged 4, replayed 5");
    replayed.trial = 4;
    EXPECT_EQ(firstDifference(logged, replayed),
              "field 'event_time' logged 0.10000000000000001, replayed 0.20000000000000001");
}

TEST(Records, FirstDifferenceComparesDetailKeyByKey) {
    EventRecord logged;
    logged.type = "shot";
    logged.detailJson = R"({"aim_time":0.5,"angular_error_deg":1.25,"difficulty":3,"scored":"hit","target":[1.0,2.0]})";
    EventRecord replayed = logged;
    replayed.detailJson =
        R"({"aim_time":0.75,"angular_error_deg":1.25,"difficulty":3,"scored":"hit","target":[1.0,2.0]})";
    EXPECT_EQ(firstDifference(logged, replayed), "field 'detail.aim_time' logged 0.5, replayed 0.75");

    // The same object written otherwise (key order, spacing, 3 as 3.0) is the same detail.
    replayed.detailJson =
        R"({ "target": [1, 2.0], "scored": "hit", "difficulty": 3.0, "angular_error_deg": 1.25, "aim_time": 0.5 })";
    EXPECT_EQ(firstDifference(logged, replayed), "");

    // A key on one side only, either side; the first in sorted key order is named.
    replayed.detailJson =
        R"({"aim_time":0.5,"angular_error_deg":1.25,"difficulty":3,"plane_z":-7.5,"scored":"hit","target":[1.0,2.0]})";
    EXPECT_EQ(firstDifference(logged, replayed), "field 'detail.plane_z' logged (absent), replayed -7.5");
    EXPECT_EQ(firstDifference(replayed, logged), "field 'detail.plane_z' logged -7.5, replayed (absent)");
    replayed.detailJson = R"({"aim_time":0.5,"difficulty":3})";
    EXPECT_EQ(firstDifference(logged, replayed), "field 'detail.angular_error_deg' logged 1.25, replayed (absent)");

    // Nested values compare inside; the top-level key is named.
    replayed.detailJson =
        R"({"aim_time":0.5,"angular_error_deg":1.25,"difficulty":3,"scored":"hit","target":[1.0,2.5]})";
    EXPECT_EQ(firstDifference(logged, replayed), "field 'detail.target' logged [1.0,2.0], replayed [1.0,2.5]");
    replayed.detailJson =
        R"({"aim_time":0.5,"angular_error_deg":1.25,"difficulty":3,"scored":"miss","target":[1.0,2.0]})";
    EXPECT_EQ(firstDifference(logged, replayed), "field 'detail.scored' logged \"hit\", replayed \"miss\"");

    // "" is no detail, the same as {}; not JSON at all compares as text.
    logged.detailJson = "";
    replayed.detailJson = "{}";
    EXPECT_EQ(firstDifference(logged, replayed), "");
    replayed.detailJson = R"({"difficulty":0})";
    EXPECT_EQ(firstDifference(logged, replayed), "field 'detail.difficulty' logged (absent), replayed 0");
    logged.detailJson = "{broken";
    EXPECT_EQ(firstDifference(logged, replayed),
              R"(field 'detail_json' logged '{broken', replayed '{"difficulty":0}')");

    // Frames' detail is compared the same way.
    FrameRecord frame;
    frame.detailJson = R"({"target":[1.0,2.0,-7.5]})";
    FrameRecord other = frame;
    other.detailJson = R"({"target":[1.0,2.0,-7.25]})";
    EXPECT_EQ(firstDifference(frame, other), "field 'detail.target' logged [1.0,2.0,-7.5], replayed [1.0,2.0,-7.25]");
}

TEST(Records, FirstDifferenceTellsNegativeZeroFromZero) {
    EventRecord logged;
    EventRecord replayed = logged;
    replayed.eventTime = -0.0;
    EXPECT_EQ(firstDifference(logged, replayed), "field 'event_time' logged 0, replayed -0");

    replayed = logged;
    logged.detailJson = R"({"aim_time":0.0})";
    replayed.detailJson = R"({"aim_time":-0.0})";
    EXPECT_EQ(firstDifference(logged, replayed), "field 'detail.aim_time' logged 0.0, replayed -0.0");

    InputRecord input;
    InputRecord negative = input;
    negative.mouseDx = -0.0;
    EXPECT_EQ(firstDifference(input, negative), "field 'mouse_dx' logged 0, replayed -0");
}

// ============================ the documented schema ============================

// docs/session-format.md's table for `table`: each row's backticked column names, in order,
// with the row's type cell.
std::vector<std::pair<std::string, std::string>> documentedColumns(const std::string& table) {
    std::ifstream doc(std::string(WARPLAB_SOURCE_DIR) + "/docs/session-format.md");
    EXPECT_TRUE(doc.good());
    std::vector<std::pair<std::string, std::string>> columns;
    std::string line;
    bool inSection = false;
    while (std::getline(doc, line)) {
        if (line.rfind("#", 0) == 0) {  // any heading ends a section
            if (inSection) break;
            inSection = line.rfind("### `" + table + "`", 0) == 0;
            continue;
        }
        if (!inSection || line.rfind("| `", 0) != 0) continue;
        const std::size_t cellEnd = line.find('|', 1);
        const std::string cell = line.substr(1, cellEnd - 1);
        const std::size_t typeEnd = line.find('|', cellEnd + 1);
        const std::string type = line.substr(cellEnd + 1, typeEnd - cellEnd - 1);
        for (std::size_t open = cell.find('`'); open != std::string::npos;) {
            const std::size_t close = cell.find('`', open + 1);
            columns.emplace_back(cell.substr(open + 1, close - open - 1), type);
            open = cell.find('`', close + 1);
        }
    }
    return columns;
}

template <class R>
void expectDocumented(const std::string& table, bool numbered) {
    SCOPED_TRACE("docs/session-format.md, table " + table);
    const auto documented = documentedColumns(table);
    std::vector<std::string> expected;
    if (numbered) expected.push_back("id");
    for (const Field<R>& field : fieldsOf<R>()) expected.push_back(field.column);
    std::vector<std::string> names;
    for (const auto& [name, type] : documented) names.push_back(name);
    EXPECT_EQ(names, expected);
    for (const Field<R>& field : fieldsOf<R>()) {
        const auto it =
            std::find_if(documented.begin(), documented.end(), [&](const auto& d) { return d.first == field.column; });
        if (it == documented.end()) continue;
        const char* type = field.storage == Storage::Integer ? "INTEGER"
            : field.storage == Storage::Real                 ? "REAL"
                                                             : "TEXT";
        EXPECT_NE(it->second.find(type), std::string::npos) << field.column << ":" << it->second;
        if (field.storage == Storage::JsonObject) {
            EXPECT_NE(it->second.find("JSON"), std::string::npos) << field.column;
        }
    }
}

// The page analysts read is the contract: its column tables list exactly the field tables'
// columns, in order, with their types.
TEST(Records, TheDocumentedSchemaIsTheFieldTables) {
    expectDocumented<InputRecord>("input", false);
    expectDocumented<FrameRecord>("frames", false);
    expectDocumented<EventRecord>("events", true);
}

// And the file's tables are the field tables too.
template <class R>
void expectFileColumns(sqlite3* db, const std::string& table, bool numbered) {
    SCOPED_TRACE(table);
    std::vector<std::string> expected, actual;
    if (numbered) expected.push_back("id INTEGER");
    for (const Field<R>& field : fieldsOf<R>())
        expected.push_back(std::string(field.column) +
                           (field.storage == Storage::Integer    ? " INTEGER"
                                : field.storage == Storage::Real ? " "
                                                                 : " TEXT"));
    sqlite3_stmt* s = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, ("PRAGMA table_info(" + table + ")").c_str(), -1, &s, nullptr), SQLITE_OK);
    while (sqlite3_step(s) == SQLITE_ROW)
        actual.push_back(std::string(reinterpret_cast<const char*>(sqlite3_column_text(s, 1))) + " " +
                         reinterpret_cast<const char*>(sqlite3_column_text(s, 2)));
    sqlite3_finalize(s);
    EXPECT_EQ(actual, expected);
}

TEST(Records, TheFileSchemaIsTheFieldTables) {
    TempDir dir;
    const std::string path = writeFinishedSession(dir.str(), 1);
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    expectFileColumns<InputRecord>(db, "input", false);
    expectFileColumns<FrameRecord>(db, "frames", false);
    expectFileColumns<EventRecord>(db, "events", true);
    sqlite3_close(db);
}

// ============================ names and folders ============================

TEST(SessionNames, ParticipantIdNeverEscapesTheResultsFolder) {
    TempDir root;
    const fs::path results = root.path() / "results";
    fs::create_directories(results / "a");  // so "a/b" would have somewhere to go
    const std::vector<std::string> ids = {"../../etc/passwd",
                                          "a/b",
                                          "..",
                                          ".",
                                          "",
                                          std::string("\x01\n", 2),
                                          std::string(500, 'q'),
                                          "Zoë 김 🎯",
                                          "-rf",
                                          std::string("nul\0byte", 8),
                                          "P07",
                                          "P07"};
    std::vector<std::string> paths;
    for (const std::string& id : ids) {
        SCOPED_TRACE("participant id of " + std::to_string(id.size()) + " bytes");
        SessionWriter w = SessionWriter::create(results.string(), sampleHeader(id));
        w.finish();
        const fs::path file = fs::canonical(w.path());
        EXPECT_EQ(file.parent_path(), fs::canonical(results));
        const std::string name = file.filename().string();
        EXPECT_LE(name.size(), 120u) << name;
        EXPECT_NE(name.front(), '-') << name;
        for (const char c : name)
            EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') << name;
        EXPECT_EQ(readSession(w.path()).header.participant, id);
        paths.push_back(file.string());
    }
    // The same id at the same start time gets its own file, never a shared one.
    EXPECT_NE(paths[paths.size() - 1], paths[paths.size() - 2]);
    EXPECT_EQ(filesIn(results).size(), ids.size() + 1);  // + the folder "a"
    EXPECT_TRUE(filesIn(results / "a").empty());
}

TEST(SessionNames, MissingOrUnwritableResultsFailsBeforeCreatingAnything) {
    TempDir root;
    const fs::path missing = root.path() / "no-such-folder";
    try {
        SessionWriter::create(missing.string(), sampleHeader());
        ADD_FAILURE() << "no error for a missing folder";
    } catch (const SessionError& e) {
        EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(missing));

    const fs::path file = root.path() / "results.txt";
    std::ofstream(file) << "not a folder";
    EXPECT_THROW(SessionWriter::create(file.string(), sampleHeader()), SessionError);
    EXPECT_THROW(SessionWriter::create("", sampleHeader()), SessionError);

    // A folder without write permission: refused by the permission itself, for root too (whom
    // the kernel lets write anywhere), since a lab that marks a folder read-only means it.
    const fs::path locked = root.path() / "locked";
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    try {
        SessionWriter::create(locked.string(), sampleHeader());
        ADD_FAILURE() << "no error for an unwritable folder";
    } catch (const SessionError& e) {
        EXPECT_NE(std::string(e.what()).find(locked.string()), std::string::npos) << e.what();
    }
    // One the kernel refuses whatever its permissions say.
    try {
        SessionWriter::create("/proc/self", sampleHeader());
        ADD_FAILURE() << "no error for /proc/self";
    } catch (const SessionError& e) {
        EXPECT_NE(std::string(e.what()).find("Results folder '/proc/self'"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(filesIn(locked).empty());
    EXPECT_EQ(filesIn(root.path()).size(), 2u);  // results.txt and locked, nothing else
}

}  // namespace
}  // namespace warplab::session
