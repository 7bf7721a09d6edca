// What the session store's tests (test_session_store_*.cpp) share: a sample header, records
// built and compared through the field tables, whole trials written and checked, and raw
// access to a session's files, to copy, cut, read and relabel them as the outside world might.
#pragma once

#include <gtest/gtest.h>

#include <sqlite3.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "session/records.h"
#include "session/session_store.h"
#include "raw_access.h"

namespace warplab::session::testing {

namespace fs = std::filesystem;

inline std::vector<fs::path> filesIn(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& entry : fs::directory_iterator(dir)) out.push_back(entry.path());
    return out;
}

inline bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline SessionHeader sampleHeader(const std::string& participant = "P07") {
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
inline const std::vector<double> kDoubles = {-0.0,
                                             1.0 / 3.0,
                                             std::numeric_limits<double>::denorm_min(),
                                             -std::numeric_limits<double>::max(),
                                             std::nextafter(1.0, 2.0),
                                             std::numeric_limits<double>::infinity(),
                                             -std::numeric_limits<double>::infinity(),
                                             -7.3125e-300,
                                             0.1 + 0.2};
inline const std::vector<std::string> kTexts = {"warp15to120", "Zoë «P7»", std::string("nul\0inside", 10),
                                                "'; DROP TABLE frames; --", ""};
inline const std::vector<std::string> kJsonObjects = {"", R"({"ids": [2, 16], "note": "ünï", "x": -0.0})",
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

inline constexpr int kFramesPerTrial = 48;
inline constexpr int kEventsPerTrial = 2;

inline InputRecord trialInput(std::int64_t frame) { return sampleRecord<InputRecord>(frame); }
inline FrameRecord trialFrame(std::int64_t frame) { return sampleRecord<FrameRecord>(frame); }
inline EventRecord trialEvent(int trial, int k) {
    EventRecord e = sampleRecord<EventRecord>(trial * kEventsPerTrial + k);
    const std::int64_t first = static_cast<std::int64_t>(trial) * kFramesPerTrial;
    e.frame = k == 0 ? first : first + kFramesPerTrial - 1;
    return e;
}

inline void writeTrial(SessionWriter& w, int trial) {
    w.addEvent(trialEvent(trial, 0));
    for (int i = 0; i < kFramesPerTrial; ++i) {
        const std::int64_t frame = static_cast<std::int64_t>(trial) * kFramesPerTrial + i;
        w.addInput(trialInput(frame));
        w.addFrame(trialFrame(frame));
    }
    w.addEvent(trialEvent(trial, 1));
}

inline void expectSame(const SessionHeader& a, const SessionHeader& b) {
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
inline int expectWholeTrials(const SessionData& data) {
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
inline constexpr std::intmax_t kWhole = -1;
inline constexpr std::intmax_t kNoWal = -2;
inline void copySession(const std::string& src, const std::string& dst, std::intmax_t mainBytes,
                        std::intmax_t walBytes) {
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(dst + suffix);
    fs::copy_file(src, dst);
    if (mainBytes != kWhole) fs::resize_file(dst, static_cast<std::uintmax_t>(mainBytes));
    if (walBytes != kNoWal && fs::exists(src + "-wal")) {
        fs::copy_file(src + "-wal", dst + "-wal");
        if (walBytes != kWhole) fs::resize_file(dst + "-wal", static_cast<std::uintmax_t>(walBytes));
    }
}

// A finished session of `trials` trials, each committed on its own; returns its path.
inline std::string writeFinishedSession(const std::string& dir, int trials) {
    SessionWriter w = SessionWriter::create(dir, sampleHeader());
    const std::string path = w.path();
    for (int t = 0; t < trials; ++t) {
        writeTrial(w, t);
        w.commit();
    }
    w.finish();
    return path;
}

inline std::string errorOf(const std::string& path) {
    try {
        readSession(path);
    } catch (const SessionError& e) {
        return e.what();
    }
    return "";
}

// A statement's rows as column name -> value (NULL as an empty json), in order.
inline std::vector<nlohmann::json> sqlRows(const std::string& path, const std::string& sql) {
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
inline void relabel(const std::string& path, int version) {
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

}  // namespace warplab::session::testing
