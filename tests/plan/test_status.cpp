// Where a study stands (plan/status.h), from a plan's results folder: the same account as the
// sessions read whole give, while reading only each session's outline -- a participant waits
// for it at every `run --study`, so its cost must not grow with the sessions' lengths.
#include <gtest/gtest.h>

#include <sqlite3.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "game/registry.h"
#include "plan/status.h"
#include "plan/study_plan.h"
#include "session/session_store.h"
#include "study/session_runner.h"

namespace warplab::plan {
namespace {

namespace fs = std::filesystem;

std::string scratch(const std::string& name) {
    const fs::path dir = fs::path(WARPLAB_BINARY_DIR) / "test-output" / "plan-status" / name;
    fs::remove_all(dir);
    fs::create_directories(dir.parent_path());
    return dir.string();
}

// Bytes this process has read through read(2) and pread(2) (SQLite's unix VFS reads so).
std::uint64_t bytesRead() {
    std::ifstream io("/proc/self/io");
    std::string key;
    std::uint64_t value = 0;
    while (io >> key >> value)
        if (key == "rchar:") return value;
    ADD_FAILURE() << "/proc/self/io has no rchar";
    return 0;
}

std::string runParticipant(const std::string& dir, const StudyPlan& plan, int participant) {
    const ParticipantPlan& p = plan.participants[static_cast<std::size_t>(participant)];
    study::HeadlessRun run;
    run.protocolPath = (fs::path(dir) / plan.protocols.front().file).string();
    run.protocolText = participantProtocolJson(dir, plan, p, 0);
    run.planId = plan.id;
    run.participant = p.id;
    run.resultsDir = resultsFolder(dir);
    run.player = "bot:" + std::to_string(participant + 1);
    run.seed = p.seed;
    std::ostringstream quiet;
    return study::runHeadless(run, quiet);
}

TEST(StudyStatus, ReadsEachSessionsOutlineAndSaysWhatTheWholeSessionsSay) {
    const std::string dir = scratch("outline");
    const StudyPlan plan =
        makePlan(dir, {std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json"}, 3, {"A", "B", "C"}, 7);
    writePlan(dir, plan);
    fs::create_directories(resultsFolder(dir));
    const std::string done = runParticipant(dir, plan, 0);
    // B's session as a kill leaves it: its last commits kept, not marked complete.
    const std::string killed = runParticipant(dir, plan, 1);
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(killed.c_str(), &db), SQLITE_OK);
    const int rc = sqlite3_exec(db, "DELETE FROM meta WHERE key = 'completed_at'", nullptr, nullptr, nullptr);
    sqlite3_close(db);
    ASSERT_EQ(rc, SQLITE_OK);
    const std::uintmax_t sessionBytes = fs::file_size(done) + fs::file_size(killed);

    // The same account from the sessions read whole.
    std::vector<SessionFacts> facts;
    for (const std::string& path : {done, killed}) {
        const session::SessionData data = session::readSession(path);
        facts.push_back(factsOf(path, data, *game::parseStudy(data.header.protocolJson, path)));
    }
    const std::vector<ParticipantStatus> expected = studyStatus(plan, facts);

    const std::uint64_t before = bytesRead();
    const std::vector<ParticipantStatus> status = studyStatus(dir, plan);
    const std::uint64_t read = bytesRead() - before;

    ASSERT_EQ(status.size(), 3u);
    for (std::size_t i = 0; i < status.size(); ++i) {
        ASSERT_EQ(status[i].protocols.size(), 1u);
        const ProtocolStatus& s = status[i].protocols.front();
        const ProtocolStatus& e = expected[i].protocols.front();
        EXPECT_EQ(stateText(s), stateText(e)) << status[i].id;
        EXPECT_EQ(s.detail, e.detail) << status[i].id;
        EXPECT_EQ(s.done, e.done) << status[i].id;
        EXPECT_EQ(s.planned, e.planned) << status[i].id;
        EXPECT_EQ(s.sessions, e.sessions) << status[i].id;
        EXPECT_EQ(s.resumable, e.resumable) << status[i].id;
    }
    EXPECT_EQ(stateName(status[0].protocols.front().state), std::string("done"));
    EXPECT_EQ(stateName(status[1].protocols.front().state), std::string("incomplete"));
    EXPECT_EQ(status[1].protocols.front().resumable, killed);
    EXPECT_EQ(stateName(status[2].protocols.front().state), std::string("not started"));
    // The plan, its protocol copy, the headers and events, and the path down each table: a
    // small part of the sessions' bytes, which the whole reads take in full.
    EXPECT_LT(read, sessionBytes / 5) << read << " bytes read of sessions of " << sessionBytes;
    std::printf("study status read %llu bytes for sessions of %llu\n", static_cast<unsigned long long>(read),
                static_cast<unsigned long long>(sessionBytes));
}

}  // namespace
}  // namespace warplab::plan
