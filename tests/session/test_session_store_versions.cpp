// Checksums as docs/session-format.md documents them, and the fixtures of format versions 1
// to 4 read and mapped onto today's records.
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

}  // namespace
}  // namespace warplab::session
