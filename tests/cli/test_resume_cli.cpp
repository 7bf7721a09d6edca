// `warplab run --resume`, as a supervisor meets it: a session killed at a random instant and
// resumed is the session that was never interrupted, row for row; study status and export
// count it once; and what cannot be resumed is refused, naming the file, with nothing written.
#include <gtest/gtest.h>

#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_support.h"
#include "session/records.h"
#include "session/session_store.h"

namespace {

namespace fs = std::filesystem;
using warplab::session::readSession;
using warplab::session::SessionData;
using warplab::testing::contains;
using warplab::testing::warplab;

std::string scratch(const std::string& name) { return warplab::testing::scratch("cli-resume", name); }

std::string protocolFile(const char* name) { return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name; }

std::vector<std::string> sessionsIn(const std::string& dir) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".warplab-session") found.push_back(entry.path().string());
    std::sort(found.begin(), found.end());
    return found;
}

// The rows of `resumed` against those of `whole`, the same play uninterrupted: "" when every
// input, frame and event row is the same, else the first difference.
std::string differenceBetween(const SessionData& whole, const SessionData& resumed) {
    using warplab::session::firstDifference;
    if (whole.inputs.size() != resumed.inputs.size())
        return std::to_string(resumed.inputs.size()) + " input rows, not " + std::to_string(whole.inputs.size());
    if (whole.frames.size() != resumed.frames.size())
        return std::to_string(resumed.frames.size()) + " frame rows, not " + std::to_string(whole.frames.size());
    if (whole.events.size() != resumed.events.size())
        return std::to_string(resumed.events.size()) + " events, not " + std::to_string(whole.events.size());
    for (std::size_t i = 0; i < whole.inputs.size(); ++i)
        if (auto d = firstDifference(whole.inputs[i], resumed.inputs[i]); !d.empty())
            return "input " + std::to_string(i) + ": " + d;
    for (std::size_t i = 0; i < whole.frames.size(); ++i)
        if (auto d = firstDifference(whole.frames[i], resumed.frames[i]); !d.empty())
            return "frame " + std::to_string(i) + ": " + d;
    for (std::size_t i = 0; i < whole.events.size(); ++i)
        if (auto d = firstDifference(whole.events[i], resumed.events[i]); !d.empty())
            return "event " + std::to_string(i) + ": " + d;
    return "";
}

// Runs `arguments` in the background and kills it with SIGKILL once the session it writes into
// `dir` holds at least `frames` committed frames (a headless bot runs far faster than any
// timer could aim at). False when it ended first.
bool runKilledAtFrame(const std::string& dir, const std::string& arguments, std::size_t frames) {
    const std::string command = "exec " + std::string(WARPLAB_BINARY) + " " + arguments + " > /dev/null 2>&1";
    const pid_t pid = fork();
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    const std::size_t before = sessionsIn(dir).size();
    for (;;) {
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid) return false;
        const auto files = sessionsIn(dir);
        if (files.size() > before) {
            try {
                if (readSession(files.back()).inputs.size() >= frames) {
                    kill(pid, SIGKILL);
                    waitpid(pid, &status, 0);
                    return true;
                }
            } catch (const warplab::session::SessionError&) {
                // Not readable yet: being created.
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

// Kill -9 at random points of a bot session, then --resume (and once, kill the resumed run
// too and resume again): the result is the uninterrupted session, every row of it, its header
// names the session(s) it carries on, and it replays whole.
void expectResumedEqualsUninterrupted(const char* protocolName) {
    const std::string protocol = protocolFile(protocolName);
    const std::string play = " --headless --player bot:4 --seed 11 --width 640 --height 360";
    const std::string wholeDir = scratch(std::string("whole-") + protocolName);
    ASSERT_EQ(warplab("run --protocol " + protocol + " --participant R --out " + wholeDir + play).status, 0);
    const SessionData whole = readSession(sessionsIn(wholeDir).at(0));
    ASSERT_TRUE(whole.completed);

    // Kill points at random frames of the session (printed with any failure).
    std::random_device device;
    std::mt19937 random(device());
    std::uniform_int_distribution<std::size_t> frame(whole.inputs.size() / 10, whole.inputs.size() * 8 / 10);
    int resumedMidway = 0;
    for (int kill = 0; kill < 3; ++kill) {
        const std::size_t at = frame(random);
        SCOPED_TRACE(std::string(protocolName) + ", killed at frame " + std::to_string(at));
        const std::string dir = scratch(std::string("kill-") + protocolName + "-" + std::to_string(kill));
        if (!runKilledAtFrame(dir, "run --protocol " + protocol + " --participant R --out " + dir + play, at)) continue;
        std::vector<std::string> files = sessionsIn(dir);
        ASSERT_EQ(files.size(), 1u);
        const std::string killed = files[0];
        const SessionData before = readSession(killed);
        if (before.completed) continue;  // the kill came as it finished
        const std::string killedId = before.header.sessionId;
        if (kill == 0) {
            // The resumed run killed too, further on, then resumed in its turn: a chain of two.
            const std::size_t later = at + (whole.inputs.size() - at) / 2;
            if (runKilledAtFrame(dir, "run --resume " + killed + " --headless --player bot:4", later) &&
                !readSession(sessionsIn(dir).back()).completed) {
                files = sessionsIn(dir);
                ASSERT_EQ(files.size(), 2u);
                const std::string middle = files[1];
                const auto again = warplab("run --resume " + middle + " --headless --player bot:4");
                ASSERT_EQ(again.status, 0) << again.output;
                const SessionData last = readSession(sessionsIn(dir).back());
                ASSERT_EQ(last.header.resumed.size(), 2u);
                EXPECT_EQ(last.header.resumed[0].sessionId, killedId);
                EXPECT_EQ(last.header.resumed[1].sessionId, readSession(middle).header.sessionId);
                EXPECT_LE(last.header.resumed[0].frame, last.header.resumed[1].frame);
                EXPECT_EQ(differenceBetween(whole, last), "");
                EXPECT_EQ(warplab("replay " + sessionsIn(dir).back()).status, 0);
                ++resumedMidway;
                continue;
            }
            fs::remove(sessionsIn(dir).back());  // it finished before the kill: resumed again below
        }
        const auto resumed = warplab("run --resume " + killed + " --headless --player bot:4");
        ASSERT_EQ(resumed.status, 0) << resumed.output;
        EXPECT_TRUE(contains(resumed.output, "resuming " + killed + " at frame ")) << resumed.output;
        files = sessionsIn(dir);
        ASSERT_EQ(files.size(), 2u);
        const SessionData result = readSession(files[1]);
        EXPECT_TRUE(result.completed);
        ASSERT_EQ(result.header.resumed.size(), 1u);
        EXPECT_EQ(result.header.resumed[0].sessionId, killedId);
        EXPECT_EQ(result.header.resumed[0].file, fs::path(killed).filename().string());
        EXPECT_EQ(result.header.participant, "R");
        EXPECT_EQ(result.header.seed, 11u);
        EXPECT_NE(result.header.sessionId, killedId);
        // Where it was resumed: after the killed session's last completed trial or match, so
        // within what it had committed.
        EXPECT_LE(static_cast<std::size_t>(result.header.resumed[0].frame), before.inputs.size());
        EXPECT_GT(result.header.resumed[0].frame, 0);
        EXPECT_EQ(differenceBetween(whole, result), "");
        EXPECT_EQ(warplab("replay " + files[1]).status, 0);
        ++resumedMidway;
    }
    EXPECT_GE(resumedMidway, 2) << "the kills did not land while the session ran";
}

TEST(CliResume, AKilledShooterSessionResumedIsTheUninterruptedOne) {
    expectResumedEqualsUninterrupted("shooter-demo.json");
}

TEST(CliResume, AKilledClickSessionResumedIsTheUninterruptedOne) {
    expectResumedEqualsUninterrupted("click-demo.json");
}

// A session of format 4, before typed text, interrupted: it resumes into a format-5 session
// whose kept input rows are its own with text "", and which is the uninterrupted session.
TEST(CliResume, AVersion4SessionResumesIntoAVersion5One) {
    const std::string fixture = std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v4-click-quick.warplab-session";
    const SessionData whole = readSession(fixture);
    ASSERT_TRUE(whole.completed);
    // The fixture cut back to its first four commits (the first match and a rating), as a kill
    // after the fourth would leave it: still a version-4 file.
    const std::string dir = scratch("v4");
    const std::string cut = dir + "/v4-fixture.warplab-session";
    fs::copy_file(fixture, cut);
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(cut.c_str(), &db), SQLITE_OK);
    const char* cutBack =
        "DELETE FROM meta WHERE key = 'completed_at';"
        "DELETE FROM input WHERE frame > (SELECT last_frame FROM commits WHERE id = 4);"
        "DELETE FROM frames WHERE frame > (SELECT last_frame FROM commits WHERE id = 4);"
        "DELETE FROM events WHERE id > (SELECT event_rows FROM commits WHERE id = 4);"
        "DELETE FROM commits WHERE id > 4;";
    const int rc = sqlite3_exec(db, cutBack, nullptr, nullptr, nullptr);
    sqlite3_close(db);
    ASSERT_EQ(rc, SQLITE_OK);
    const SessionData before = readSession(cut);
    ASSERT_EQ(before.header.formatVersion, 4);
    ASSERT_FALSE(before.completed);
    ASSERT_FALSE(before.damaged) << before.note;
    ASSERT_EQ(before.inputs.size(), 131u);

    const auto resumed = warplab("run --resume " + cut + " --headless --player bot:3");
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    const std::vector<std::string> files = sessionsIn(dir);
    ASSERT_EQ(files.size(), 2u);
    const std::string result = files[0] == cut ? files[1] : files[0];
    const SessionData data = readSession(result);
    EXPECT_EQ(data.header.formatVersion, warplab::session::kSessionFormatVersion);
    EXPECT_TRUE(data.completed);
    ASSERT_EQ(data.header.resumed.size(), 1u);
    EXPECT_EQ(data.header.resumed[0].sessionId, whole.header.sessionId);
    EXPECT_EQ(differenceBetween(whole, data), "");
    const auto replay = warplab("replay " + result);
    EXPECT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "4/4 outcomes reproduced")) << replay.output;
}

// Cuts `session` back to its last commit before the test's first event, as a kill there leaves
// it. SQLITE_OK when done.
int cutBackBeforeTheTest(const std::string& session) {
    sqlite3* db = nullptr;
    if (sqlite3_open(session.c_str(), &db) != SQLITE_OK) return SQLITE_CANTOPEN;
    const char* cutBack =
        "CREATE TEMP TABLE kept AS SELECT MAX(id) AS id FROM commits"
        "  WHERE event_rows < (SELECT MIN(id) FROM events WHERE phase = 'test');"
        "DELETE FROM meta WHERE key = 'completed_at';"
        "DELETE FROM input WHERE frame > (SELECT last_frame FROM commits WHERE id = (SELECT id FROM kept));"
        "DELETE FROM frames WHERE frame > (SELECT last_frame FROM commits WHERE id = (SELECT id FROM kept));"
        "DELETE FROM events WHERE id > (SELECT event_rows FROM commits WHERE id = (SELECT id FROM kept));"
        "DELETE FROM commits WHERE id > (SELECT id FROM kept);";
    const int rc = sqlite3_exec(db, cutBack, nullptr, nullptr, nullptr);
    sqlite3_close(db);
    return rc;
}

// A session stopped before its test says what it keeps as the plan counts it: no test trial,
// and the training's shots apart. It said "3 scored outcome(s) ... kept" of a session that had
// done none of its 3 test trials.
TEST(CliResume, ASessionStoppedInTrainingSaysItKeepsNoTestTrial) {
    const std::string dir = scratch("in-training");
    ASSERT_EQ(warplab("run --protocol " + warplab::testing::tinyProtocol(dir) + " --participant T --out " + dir +
                      " --headless --player bot:3 --seed 4")
                  .status,
              0);
    const std::string session = sessionsIn(dir).at(0);
    ASSERT_EQ(cutBackBeforeTheTest(session), SQLITE_OK);
    const SessionData cut = readSession(session);
    ASSERT_FALSE(cut.completed);
    ASSERT_FALSE(cut.damaged) << cut.note;
    std::size_t outcomes = 0, ofTraining = 0;
    for (const auto& e : cut.events) {
        const bool outcome = e.type == "shot" || e.type == "timeout";
        outcomes += outcome;
        ofTraining += outcome && e.phase == "training";
    }
    ASSERT_GT(ofTraining, 0u) << "the cut keeps some of training";

    const auto resumed = warplab("run --resume " + session + " --headless --player bot:3");
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    EXPECT_TRUE(contains(resumed.output,
                         ": 0 of 3 test trials kept (" + std::to_string(outcomes) +
                             " scored outcome(s) in all, those of practice and training included)"))
        << resumed.output;
}

// A shooter protocol of format 7 re-centres the view where a resumed session goes on: a rule of
// the game, so the resumed file replays exactly, every outcome, and a resume of it again too.
TEST(CliResume, AFormat7SessionResumedFacingTheTargetsReplaysExactly) {
    const std::string dir = scratch("format-7");
    std::ofstream(dir + "/tiny7.json") << R"({"format_version":7,"name":"shooter-tiny7","game":"shooter",
 "display":{"refresh_mismatch":"warn"},
 "acclimation":{"duration_s":1.0,"level":0,"mode":"conv120","instructions":""},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.5,"instructions":""},
 "test":{"targets_per_condition":1,"timeout_s":0.5,"pause_s":0.25,"supervisor_starts":false,"instructions":""}})";
    ASSERT_EQ(warplab("run --protocol " + dir + "/tiny7.json --participant S --out " + dir +
                      " --headless --player bot:3 --seed 4")
                  .status,
              0);
    const std::string session = sessionsIn(dir).at(0);
    ASSERT_EQ(cutBackBeforeTheTest(session), SQLITE_OK);
    const auto resumed = warplab("run --resume " + session + " --headless --player bot:3");
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    const std::vector<std::string> files = sessionsIn(dir);
    ASSERT_EQ(files.size(), 2u);
    const std::string result = files[0] == session ? files[1] : files[0];
    const SessionData data = readSession(result);
    EXPECT_TRUE(data.completed);
    ASSERT_EQ(data.header.resumed.size(), 1u);
    const auto replay = warplab("replay " + result);
    EXPECT_EQ(replay.status, 0) << replay.output;
    EXPECT_TRUE(contains(replay.output, "outcomes reproduced (")) << replay.output;
}

// What cannot be resumed is refused with one sentence naming the file (exit 1), and nothing
// is written; options that the session itself answers are a usage error (exit 2).
TEST(CliResume, RefusesWhatCannotBeResumedAndWritesNothing) {
    const std::string dir = scratch("refusals");
    ASSERT_EQ(warplab("run --protocol " + protocolFile("shooter-quick.json") + " --participant Q --out " + dir +
                      " --headless --player bot:2 --seed 3")
                  .status,
              0);
    const std::string complete = sessionsIn(dir).at(0);
    auto r = warplab("run --resume " + complete + " --headless");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "session '" + complete + "' is complete: there is nothing to resume")) << r.output;
    EXPECT_EQ(sessionsIn(dir).size(), 1u);

    // A session whose input no longer gives its outcomes: written again, incomplete, with the
    // bot's shots taken out.
    SessionData data = readSession(complete);
    for (auto& input : data.inputs) input.buttons = 0;
    const std::string doctoredDir = scratch("refusals-doctored");
    std::string doctored;
    {
        auto writer = warplab::session::SessionWriter::create(doctoredDir, data.header);
        for (const auto& input : data.inputs) writer.addInput(input);
        for (const auto& frame : data.frames) writer.addFrame(frame);
        for (const auto& event : data.events) writer.addEvent(event);
        writer.commit();  // not finished: an interrupted session
        doctored = writer.path();
    }
    r = warplab("run --resume " + doctored + " --headless");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "session '" + doctored + "' does not replay as it was recorded (record "))
        << r.output;
    EXPECT_EQ(r.lines(), 1) << r.output;
    EXPECT_EQ(sessionsIn(doctoredDir).size(), 1u);

    r = warplab("run --resume " + dir + "/none.warplab-session --headless");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "none.warplab-session")) << r.output;

    for (const char* option : {"--protocol x.json", "--participant P", "--seed 4", "--width 800"}) {
        r = warplab("run --resume " + doctored + " --headless " + option);
        EXPECT_EQ(r.status, 2) << option << ": " << r.output;
        EXPECT_TRUE(contains(r.output, "comes from the session with --resume")) << r.output;
    }
    r = warplab("run --resume --headless");
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_TRUE(contains(r.output, "option --resume needs the SESSION")) << r.output;
    EXPECT_EQ(sessionsIn(doctoredDir).size(), 1u);
}

// Under a study plan: status says to resume, --resume finds the participant's incomplete
// session, and afterwards status and export count the protocol once, done.
TEST(CliResume, AStudyParticipantsInterruptedSessionResumesAndCountsOnce) {
    const std::string dir = scratch("study");
    ASSERT_EQ(warplab("study init " + dir + " --protocol " + protocolFile("click-demo.json") + "," +
                      protocolFile("shooter-quick.json") + " --participants 2")
                  .status,
              0);
    auto r = warplab("run --study " + dir + " --participant P01 --headless --resume");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(contains(r.output, "participant P01 has no incomplete session of ")) << r.output;

    // Interrupted: P01's first session killed a third of the way (the planned protocols run
    // a few thousand frames each).
    ASSERT_TRUE(runKilledAtFrame(dir + "/results", "run --study " + dir + " --participant P01 --headless", 1500));
    const std::string killed = sessionsIn(dir + "/results").at(0);
    ASSERT_FALSE(readSession(killed).completed);
    r = warplab("study status " + dir);
    EXPECT_TRUE(contains(r.output, "next: warplab run --study " + dir + " --participant P01 --resume")) << r.output;
    // How far it got, in the game's unit: the click game's matches (of 21 in click-demo), or
    // the shooter's test trials.
    EXPECT_TRUE(contains(r.output, " incomplete (")) << r.output;
    EXPECT_TRUE(contains(r.output, " matches)") || contains(r.output, " test trials)")) << r.output;

    r = warplab("run --study " + dir + " --participant P01 --headless --resume");
    ASSERT_EQ(r.status, 0) << r.output;
    r = warplab("study status " + dir + " --csv");
    // P01's first protocol: done, one session (the interrupted one is part of the resumed).
    std::istringstream rows(r.output);
    std::string line;
    std::getline(rows, line);
    std::getline(rows, line);
    EXPECT_TRUE(contains(line, "P01,1,")) << r.output;
    EXPECT_TRUE(contains(line, ",done,1,")) << r.output;

    const std::string out = scratch("study-export");
    r = warplab("export " + dir + "/results --out " + out + " --include-incomplete");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, fs::path(killed).filename().string() + ": excluded (resumed: carried on by "))
        << r.output;
    EXPECT_TRUE(contains(r.output, "1 included, 1 resumed")) << r.output;
}

}  // namespace
