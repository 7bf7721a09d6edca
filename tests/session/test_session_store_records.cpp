// Replay's record comparison (firstDifference), the field tables against the documented and
// the file's schema, and participant ids that try to be paths.
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
