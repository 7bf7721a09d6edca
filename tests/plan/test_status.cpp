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
#include "session/raw_access.h"
#include "session/session_store.h"
#include "runner/session_runner.h"

namespace warplab::plan {
namespace {

namespace fs = std::filesystem;
using session::testing::bytesRead;

std::string scratch(const std::string& name) {
    const fs::path dir = fs::path(WARPLAB_BINARY_DIR) / "test-output" / "plan-status" / name;
    fs::remove_all(dir);
    fs::create_directories(dir.parent_path());
    return dir.string();
}

std::string runParticipant(const std::string& dir, const StudyPlan& plan, int participant) {
    const ParticipantPlan& p = plan.participants[static_cast<std::size_t>(participant)];
    runner::HeadlessRun run;
    run.protocolPath = (fs::path(dir) / plan.protocols.front().file).string();
    run.protocolText = participantProtocolJson(dir, plan, p, 0);
    run.planId = plan.id;
    run.participant = p.id;
    run.resultsDir = resultsFolder(dir);
    run.player = "bot:" + std::to_string(participant + 1);
    run.seed = p.seed;
    std::ostringstream quiet;
    return runner::runHeadless(run, quiet);
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

// Who played, who is in the analysis, who is running: from the sessions' facts alone. Copies of
// one session in two rigs' folders count once; a second complete session on another rig is
// named by its rig.
TEST(StudyStatus, TellsPlayersFlagsRigsAndRunningSessions) {
    const std::string dir = scratch("kinds");
    const StudyPlan plan =
        makePlan(dir, {std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json"}, 4, {"A", "B", "C", "D"}, 7);
    const auto fact = [&](const std::string& participant, const std::string& player, const std::string& id,
                          const std::string& rig) {
        SessionFacts f;
        f.path = dir + "/results/" + (rig.empty() ? "" : rig + "/") + participant + "-" + id + ".warplab-session";
        f.header.participant = participant;
        f.header.player = player;
        f.header.sessionId = id;
        f.header.planId = plan.id;
        f.header.protocolJson = R"({"name": "shooter-quick"})";
        f.completed = true;
        f.rig = rig;
        return f;
    };
    std::vector<SessionFacts> facts = {fact("A", "bot:2", "a1", "booth-a"), fact("A", "bot:2", "a1", "booth-b"),
                                       fact("B", "human", "b1", ""), fact("B", "human", "b2", "booth-b"),
                                       fact("C", "bot:3", "c1", "")};
    facts.back().flags["missed_frames"] = "3 % of frames late";
    session::LockHolder holder;
    holder.pid = 4242;
    holder.host = "booth-a";
    holder.participant = "D";
    holder.protocol = "shooter-quick";
    holder.since = "2024-05-01T09:30:00.000Z";
    const auto status = studyStatus(plan, facts, {{"booth-a", holder}});
    ASSERT_EQ(status.size(), 4u);
    EXPECT_EQ(participantKind(status[0]), "bot");
    EXPECT_EQ(status[0].protocols[0].sessions, 1) << "a copy of one session is one session";
    EXPECT_EQ(participantKind(status[1]), "human");
    EXPECT_EQ(status[1].protocols[0].completeRigs, (std::vector<std::string>{"", "booth-b"}));
    EXPECT_TRUE(inAnalysis(status[0]));
    EXPECT_TRUE(inAnalysis(status[1]));
    EXPECT_EQ(status[2].protocols[0].state, SessionState::Flagged);
    EXPECT_FALSE(inAnalysis(status[2])) << "export leaves flagged sessions out by default";
    ASSERT_TRUE(status[3].protocols[0].running);
    EXPECT_EQ(stateLine(status[3].protocols[0]),
              "running (pid 4242 on booth-a, since 2024-05-01T09:30:00.000Z; rig booth-a)");
    EXPECT_EQ(participantKind(status[3]), "");
    EXPECT_EQ(nextParticipant(status), nullptr) << "D is running and the others are done";
}

}  // namespace
}  // namespace warplab::plan
