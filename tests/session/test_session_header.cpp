// Header entries stored beside the checksummed header (schema.h headerExtras): the photodiode
// marker a session's window drew. Set, it reads back; unset, nothing is stored; and since it is
// outside header_checksum, a file with or without it reads as any reader before it read it.
#include <gtest/gtest.h>

#include <sqlite3.h>

#include <string>

#include "session/session_store.h"
#include "raw_access.h"
#include "temp_dir.h"

namespace warplab::session {
namespace {

using testing::execSql;
using testing::TempDir;

int metaRows(const std::string& path, const std::string& key) {
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    EXPECT_EQ(sqlite3_prepare_v2(db, "SELECT count(*) FROM meta WHERE key = ?", -1, &s, nullptr), SQLITE_OK);
    sqlite3_bind_text(s, 1, key.c_str(), -1, SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(s), SQLITE_ROW);
    const int rows = sqlite3_column_int(s, 0);
    sqlite3_finalize(s);
    sqlite3_close(db);
    return rows;
}

std::string finishedSession(const std::string& dir, const std::string& photonMarker) {
    SessionHeader h;
    h.protocolJson = R"({"game": "shooter"})";
    h.participant = "P01";
    h.photonMarker = photonMarker;
    SessionWriter w = SessionWriter::create(dir, h);
    w.finish();
    return w.path();
}

TEST(SessionHeader, ThePhotonMarkerIsStoredBesideTheChecksummedHeader) {
    TempDir dir;
    const std::string marked = finishedSession(dir.str(), "top_right");
    EXPECT_EQ(readSessionHeader(marked).photonMarker, "top_right");
    EXPECT_EQ(readSession(marked).header.photonMarker, "top_right");
    EXPECT_EQ(metaRows(marked, "photon_marker"), 1);
    // Outside the checksum: taken out, as a file of a warplab before it lacks it, the header
    // still verifies, and it reads as none.
    execSql(marked, "DELETE FROM meta WHERE key = 'photon_marker'");
    const SessionData without = readSession(marked);
    EXPECT_EQ(without.header.photonMarker, "");
    EXPECT_TRUE(without.completed) << without.note;

    TempDir other;
    const std::string unmarked = finishedSession(other.str(), "");
    EXPECT_EQ(metaRows(unmarked, "photon_marker"), 0);
    EXPECT_EQ(readSessionHeader(unmarked).photonMarker, "");
    for (const char* fixture : {"v1-shooter-quick", "v2-click-quick", "v3-shooter-quick", "v4-click-quick"})
        EXPECT_EQ(readSessionHeader(std::string(WARPLAB_SOURCE_DIR) + "/tests/data/" + fixture + ".warplab-session")
                      .photonMarker,
                  "")
            << fixture;
}

}  // namespace
}  // namespace warplab::session

TEST(SessionHeader, PlayerKindNamesWhoPlayedFromThePlayerField) {
    EXPECT_EQ(warplab::session::playerKind("human (cm_per_360=0, dpi=800, invert_y=0)"), "human");
    EXPECT_EQ(warplab::session::playerKind("human"), "human");
    EXPECT_EQ(warplab::session::playerKind("bot:5"), "bot");
    EXPECT_EQ(warplab::session::playerKind("bot"), "bot");
    EXPECT_EQ(warplab::session::playerKind("sim:12"), "simulated");
    EXPECT_EQ(warplab::session::playerKind("replay:/data/P01.warplab-session"), "replay");
    // A name that only starts like one is none of them.
    EXPECT_EQ(warplab::session::playerKind("botany:1"), "");
    EXPECT_EQ(warplab::session::playerKind("simon"), "");
    EXPECT_EQ(warplab::session::playerKind(""), "");
}
