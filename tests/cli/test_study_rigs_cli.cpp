// A study as a lab with several booths runs it: rigs running one plan at once, each into its own
// folder, read together by status, run --resume and export; a plan grown by `study add`; who
// played (people, bots) and who is still playing, as status tells them; check --study.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_support.h"
#include "session/session_store.h"

namespace {

namespace fs = std::filesystem;
using warplab::testing::contains;
using warplab::testing::runCommand;
using warplab::testing::warplab;

std::string scratch(const std::string& name) { return warplab::testing::scratch("cli-study-rigs", name); }

std::string protocolFile(const char* name) { return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name; }

nlohmann::json planOf(const std::string& dir) {
    std::ifstream in(dir + "/study.json");
    return nlohmann::json::parse(in);
}

std::string read(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> sessionsUnder(const std::string& dir) {
    std::vector<std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.path().extension() == ".warplab-session") files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

std::string init(const std::string& dir, const std::string& rest) {
    const auto made = warplab("study init " + dir + " --protocol " + protocolFile("shooter-quick.json") + " " + rest);
    EXPECT_EQ(made.status, 0) << made.output;
    return made.output;
}

// Two booths, one plan: both runs at once (each rig's lock is its own folder's), status and
// export reading both rigs, and a participant who played on both told rather than counted twice.
TEST(CliStudyRigs, TwoRigsRunOnePlanAtOnceAndExportReadsBoth) {
    const std::string base = scratch("two-rigs"), dir = base + "/study";
    init(dir, "--participants 2 --seed 3");
    const std::string run = std::string(WARPLAB_BINARY) + " run --study " + dir + " --headless --player bot:2";
    // Started together by one shell; each writes its exit status.
    const auto both = runCommand("(" + run + " --participant P01 --rig booth-a > " + base + "/a.log 2>&1; echo $? > " +
                                 base + "/a.status) & (" + run + " --participant P02 --rig booth-b > " + base +
                                 "/b.log 2>&1; echo $? > " + base + "/b.status) & wait");
    ASSERT_EQ(both.status, 0) << both.output;
    EXPECT_EQ(read(base + "/a.status"), "0\n") << read(base + "/a.log");
    EXPECT_EQ(read(base + "/b.status"), "0\n") << read(base + "/b.log");
    ASSERT_EQ(sessionsUnder(dir + "/results/booth-a").size(), 1u);
    ASSERT_EQ(sessionsUnder(dir + "/results/booth-b").size(), 1u);

    const auto status = warplab("study status " + dir);
    EXPECT_EQ(status.status, 0) << status.output;
    EXPECT_TRUE(contains(status.output, "2 of 2 participants have done every protocol: 2 bots")) << status.output;
    // A participant done on one rig is done on every rig.
    const auto again = warplab("run --study " + dir + " --participant P01 --rig booth-b --headless");
    EXPECT_EQ(again.status, 1) << again.output;
    EXPECT_TRUE(contains(again.output, "has done every protocol")) << again.output;

    const auto exported = warplab("export " + dir + " --out " + base + "/export");
    ASSERT_EQ(exported.status, 0) << exported.output;
    EXPECT_TRUE(contains(exported.output, "2 session files, 2 included")) << exported.output;
    const std::string participants = read(base + "/export/participants.csv");
    EXPECT_TRUE(contains(participants, "shooter-quick: done,bot\n")) << participants;
    EXPECT_FALSE(contains(participants, "not started")) << participants;

    // One rig's folder copied into the other's: one session, counted once.
    const std::string copied = sessionsUnder(dir + "/results/booth-a").front();
    fs::copy_file(copied, dir + "/results/booth-b/" + fs::path(copied).filename().string());
    const auto afterCopy = warplab("study status " + dir + " --csv");
    EXPECT_TRUE(contains(afterCopy.output, "P01,1,shooter-quick,done,1,")) << afterCopy.output;
    // The participant played again on the other rig: both rigs named, in status and export.
    ASSERT_EQ(
        warplab("run --study " + dir + " --participant P01 --rig booth-b --protocol shooter-quick --again --headless")
            .status,
        0);
    const auto twice = warplab("study status " + dir);
    EXPECT_TRUE(contains(twice.output, "was played to the end on 2 rigs (rig booth-a, rig booth-b)")) << twice.output;
    EXPECT_TRUE(contains(twice.output, "2 of 2 participants have done every protocol: 2 bots")) << twice.output;
    const auto exportedTwice = warplab("export " + dir + "/results --out " + base + "/export2");
    ASSERT_EQ(exportedTwice.status, 0) << exportedTwice.output;
    EXPECT_TRUE(contains(exportedTwice.output, "participant P01 has complete sessions of shooter-quick in 2 folders"))
        << exportedTwice.output;
    EXPECT_TRUE(fs::exists(base + "/export2/participants.csv")) << exportedTwice.output;

    // A rig's name is a folder's: refused on the command line.
    EXPECT_EQ(warplab("run --study " + dir + " --participant P02 --rig ../x --headless").status, 2);
    EXPECT_EQ(warplab("run --protocol " + protocolFile("shooter-quick.json") +
                      " --participant X --rig a --headless --out " + base)
                  .status,
              2);
}

// Runs `arguments` in the background and kills it with SIGKILL once its session in `dir` has
// `frames` committed input rows: an interrupted session. False when it ended first.
bool runKilledAtFrame(const std::string& dir, const std::string& arguments, std::size_t frames) {
    const std::string command = "exec " + std::string(WARPLAB_BINARY) + " " + arguments + " > /dev/null 2>&1";
    const pid_t pid = fork();
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    for (;;) {
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid) return false;
        const auto files = sessionsUnder(dir);
        try {
            if (!files.empty() && warplab::session::readSession(files.back()).inputs.size() >= frames) {
                kill(pid, SIGKILL);
                waitpid(pid, &status, 0);
                return true;
            }
        } catch (const warplab::session::SessionError&) {
            // Not readable yet: being created.
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

// A session still being written (its rig's lock names a live process) is running, not
// incomplete: status says who runs it and advises no --resume, and no rig may start it again.
TEST(CliStudyRigs, StatusShowsARunningSessionAsRunningWithoutResumeAdvice) {
    const std::string dir = scratch("in-progress") + "/study";
    init(dir, "--participants 2 --seed 4");
    ASSERT_TRUE(runKilledAtFrame(dir + "/results", "run --study " + dir + " --participant P01 --headless", 200));
    const auto interrupted = warplab("study status " + dir);
    ASSERT_TRUE(contains(interrupted.output, "--participant P01 --resume")) << interrupted.output;

    // The lock a run holds, naming this (live) test process, as if the session were still going.
    char host[HOST_NAME_MAX + 1] = {};
    gethostname(host, sizeof host - 1);
    const nlohmann::json lock = {{"pid", static_cast<long>(getpid())},
                                 {"host", host},
                                 {"participant", "P01"},
                                 {"protocol", "shooter-quick"},
                                 {"since", "2024-05-01T09:30:00.000Z"}};
    std::ofstream(dir + "/results/.warplab-lock") << lock.dump() << "\n";
    const auto running = warplab("study status " + dir);
    EXPECT_EQ(running.status, 0) << running.output;
    EXPECT_TRUE(contains(running.output,
                         "shooter-quick running (pid " + std::to_string(getpid()) + " on " + host +
                             ", since 2024-05-01T09:30:00.000Z; the results folder itself)"))
        << running.output;
    EXPECT_FALSE(contains(running.output, "--resume")) << running.output;
    EXPECT_TRUE(contains(running.output, "next: warplab run --study " + dir + " --participant P02")) << running.output;
    const auto csv = warplab("study status " + dir + " --csv");
    EXPECT_TRUE(contains(csv.output, "P01,1,shooter-quick,running,")) << csv.output;
    // Another rig may not carry on (or start) what is being played.
    const auto elsewhere = warplab("run --study " + dir + " --participant P01 --rig booth-b --resume --headless");
    EXPECT_EQ(elsewhere.status, 1) << elsewhere.output;
    EXPECT_TRUE(contains(elsewhere.output, "is playing shooter-quick now")) << elsewhere.output;
    EXPECT_EQ(sessionsUnder(dir + "/results").size(), 1u);

    // A lock whose process has ended (a kill -9 leaves the file) is not a running session.
    const pid_t gone = fork();
    if (gone == 0) _exit(0);
    waitpid(gone, nullptr, 0);
    nlohmann::json staleLock = lock;
    staleLock["pid"] = static_cast<long>(gone);
    std::ofstream(dir + "/results/.warplab-lock") << staleLock.dump() << "\n";
    const auto stale = warplab("study status " + dir);
    EXPECT_TRUE(contains(stale.output, "--participant P01 --resume")) << stale.output;
    EXPECT_FALSE(contains(stale.output, "running (")) << stale.output;
}

// Status names who played each participant's sessions and counts people and scripted players
// apart: here bots and a recorded session played again.
TEST(CliStudyRigs, StatusCountsPlayersByKind) {
    const std::string base = scratch("kinds"), dir = base + "/study";
    init(dir, "--participants 3 --seed 5");
    ASSERT_EQ(warplab("run --study " + dir + " --participant P01 --headless --player bot:1").status, 0);
    ASSERT_EQ(warplab("run --study " + dir + " --participant P02 --headless --player bot:2").status, 0);
    const std::string recorded = sessionsUnder(dir + "/results").front();
    ASSERT_EQ(warplab("run --study " + dir + " --participant P03 --headless --player replay:" + recorded).status, 0);
    const auto status = warplab("study status " + dir);
    EXPECT_TRUE(contains(status.output, "  P01 (bot):")) << status.output;
    EXPECT_TRUE(contains(status.output, "  P03 (replay):")) << status.output;
    EXPECT_TRUE(contains(status.output, "3 of 3 participants have done every protocol: 2 bots, 1 replay"))
        << status.output;
    const auto csv = warplab("study status " + dir + " --csv");
    EXPECT_TRUE(contains(csv.output, ",player_kind,complete_rigs\n")) << csv.output;
    EXPECT_TRUE(contains(csv.output, ",bot,\n")) << csv.output;
}

// A plan grown twice by `study add` is the plan made at that size at once: the same seeds,
// orders and ids, row for row; the rows there are never changed, and an id it has is refused.
TEST(CliStudyRigs, StudyAddTwiceGivesThePlanMadeAtThatSize) {
    const std::string base = scratch("add");
    const std::string protocols = protocolFile("shooter-quick.json") + "," + protocolFile("click-quick.json");
    ASSERT_EQ(warplab("study init " + base + "/once --protocol " + protocols + " --participants 9 --seed 21").status,
              0);
    ASSERT_EQ(warplab("study init " + base + "/grown --protocol " + protocols + " --participants 3 --seed 21").status,
              0);
    const nlohmann::json first = planOf(base + "/grown");
    const auto added = warplab("study add " + base + "/grown --participants 2");
    ASSERT_EQ(added.status, 0) << added.output;
    EXPECT_TRUE(contains(added.output, "next: warplab run --study " + base + "/grown --participant P04"))
        << added.output;
    ASSERT_EQ(warplab("study add " + base + "/grown --participants 4").status, 0);
    const nlohmann::json once = planOf(base + "/once"), grown = planOf(base + "/grown");
    EXPECT_EQ(grown["participants"], once["participants"]);
    EXPECT_EQ(grown["id"], first["id"]) << "the plan is the same plan, grown";
    EXPECT_EQ(grown["created_at"], first["created_at"]);

    // Named participants (a replacement); an id the plan has is refused, and nothing changes.
    const auto replacement = warplab("study add " + base + "/grown --ids P02b");
    ASSERT_EQ(replacement.status, 0) << replacement.output;
    const std::string before = read(base + "/grown/study.json");
    const auto taken = warplab("study add " + base + "/grown --ids P03");
    EXPECT_EQ(taken.status, 1) << taken.output;
    EXPECT_TRUE(contains(taken.output, "participant id \"P03\" is already in the plan")) << taken.output;
    EXPECT_EQ(read(base + "/grown/study.json"), before);
    EXPECT_EQ(warplab("study add " + base + "/grown --participants 2 --seed 3").status, 2);
    const auto run = warplab("run --study " + base + "/grown --participant P02b --headless");
    EXPECT_EQ(run.status, 0) << run.output;
}

// check --study takes the plan's protocol copy and the rig's results folder, as run --study.
TEST(CliStudyRigs, CheckReadsThePlan) {
    const std::string dir = scratch("check") + "/study";
    init(dir, "--participants 1");
    // No display: the window's checks fail, the folder's and the disk's still speak.
    const auto check = runCommand("DISPLAY= WAYLAND_DISPLAY= SDL_AUDIODRIVER=dummy " + std::string(WARPLAB_BINARY) +
                                  " check --study " + dir + " --participant P01 --rig booth-a");
    EXPECT_TRUE(contains(check.output, "results folder: '" + dir + "/results/booth-a' is writable")) << check.output;
    EXPECT_TRUE(contains(check.output, "a session of shooter-quick")) << check.output;
    const auto stranger = warplab("check --study " + dir + " --participant P09");
    EXPECT_EQ(stranger.status, 1) << stranger.output;
    EXPECT_TRUE(contains(stranger.output, "has no participant 'P09'")) << stranger.output;
    EXPECT_EQ(warplab("check --study " + dir + " --participant P01 --out /tmp").status, 2);
}

}  // namespace
