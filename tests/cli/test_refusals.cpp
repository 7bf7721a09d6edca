// What the README promises of bad input, command by command: one sentence naming the option or
// file, and exit 2 for a wrong command line or 1 for bad data or environment -- before any
// session, context or file is made, and never a line the user did not need.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cli/cli_support.h"

namespace {

namespace fs = std::filesystem;

using warplab::testing::contains;
using warplab::testing::Result;
using warplab::testing::warplab;

std::string scratch(const std::string& name) { return warplab::testing::scratch("refusals", name); }

std::string protocolFile(const std::string& name) { return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name; }

// The refusal `r` is one line, exits `status` and names `part`.
void expectRefused(const Result& r, int status, const std::string& part, const std::string& what) {
    EXPECT_EQ(r.status, status) << what << "\n" << r.output;
    EXPECT_EQ(r.lines(), 1) << what << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, part)) << what << "\n" << r.output;
}

std::size_t entriesIn(const std::string& dir) {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// A headless run with the bot draws nothing, but a --data-dir it is given is checked as every
// command checks it: it was read by no one, and a typo in a script passed unnoticed.
TEST(Refusals, AWrongDataDirEndsEveryRun) {
    const std::string dir = scratch("data-dir");
    const std::string file = dir + "/not-a-folder";
    std::ofstream(file) << "x";
    fs::create_directories(dir + "/out");
    const std::string run = "run --protocol " + protocolFile("shooter-quick.json") + " --participant P --out " + dir +
        "/out --headless --seed 1 --data-dir ";
    expectRefused(warplab(run + "''"), 2, "--data-dir", "blank");
    expectRefused(warplab(run + dir + "/missing"), 1, "option --data-dir: '" + dir + "/missing' does not exist",
                  "missing");
    expectRefused(warplab(run + file), 1, "option --data-dir: '" + file + "' is not a folder", "a file");
    expectRefused(warplab("render --width 16 --height 16 --out " + dir + "/f.png --data-dir " + file), 1,
                  "is not a folder", "render");
    EXPECT_EQ(entriesIn(dir + "/out"), 0u) << "a session was started";
    // The source tree is a data folder: given explicitly, it runs.
    EXPECT_EQ(warplab(run + WARPLAB_SOURCE_DIR).status, 0);
}

TEST(Refusals, AnEmptyNameInABenchListIsAWrongCommandLine) {
    const std::string dir = scratch("bench-list");
    for (const std::string list : {"pan,,track", "pan,", ",pan"})
        expectRefused(
            warplab("bench --quick --sequences " + list + " --out " + dir + "/b"), 2,
            "option --sequences of 'warplab bench' needs a list of sequence names separated by commas, got '" + list +
                "'",
            list);
    expectRefused(warplab("bench --quick --methods hold15,,blend --out " + dir + "/b"), 2, "--methods", "methods");
    expectRefused(warplab("bench --quick --shading-sweep 0,,256 --out " + dir + "/b"), 2, "--shading-sweep", "sweep");
    EXPECT_FALSE(fs::exists(dir + "/b"));
}

// --out naming a file: the bench said which GL it had, then failed to make its folder.
TEST(Refusals, ABenchOutThatIsAFileIsOneSentence) {
    const std::string dir = scratch("bench-out");
    const std::string file = dir + "/a-file";
    std::ofstream(file) << "x";
    expectRefused(warplab("bench --quick --sequences pan --methods hold15 --out " + file), 1,
                  "option --out: cannot make the folder '" + file + "' (a file of that name is there)", "bench");
}

TEST(Refusals, AnUnknownRenderMethodIsAWrongCommandLine) {
    const std::string dir = scratch("render-method");
    expectRefused(warplab("render --method bogus --out " + dir + "/f.png"), 2,
                  "option --method: unknown method 'bogus' (known: ", "bogus");
    EXPECT_EQ(entriesIn(dir), 0u);
}

// The README: `warplab demo` exits 2 when `--out` already holds sessions -- anywhere in it, not
// only in the results/ a demo writes.
TEST(Refusals, ADemoOutThatHoldsASessionIsAWrongCommandLine) {
    const std::string out = scratch("demo-out");
    fs::create_directories(out + "/earlier");
    const std::string kept = out + "/earlier/P1.warplab-session";
    fs::copy_file(std::string(WARPLAB_SOURCE_DIR) + "/tests/data/v4-click-quick.warplab-session", kept);
    expectRefused(warplab("demo --out " + out + " --player bot --participants 2 --protocols click-quick"), 2,
                  "option --out: '" + out + "' already holds sessions (" + kept + ")", "demo");
    EXPECT_FALSE(fs::exists(out + "/results")) << "the demo started";
}

// A recorded session to play that is not there: the run said the seed it drew, then failed.
TEST(Refusals, AReplayPlayerWithoutItsSessionIsOneSentence) {
    const std::string dir = scratch("replay-player");
    const std::string run = "run --protocol " + protocolFile("shooter-quick.json") + " --participant P --out " + dir +
        " --headless --player replay:";
    const Result missing = warplab(run + dir + "/none.warplab-session");
    expectRefused(missing, 1, dir + "/none.warplab-session", "missing");
    EXPECT_FALSE(contains(missing.output, "drawn at random")) << missing.output;
    expectRefused(warplab(run), 2, "--player replay:SESSION needs the SESSION file", "empty");
    EXPECT_EQ(entriesIn(dir), 0u) << "a session was started";
}

// A participant id is named quoted, with a line break shown as \n; a plan of thousands lists a
// few of its ids, not all of them.
TEST(Refusals, AnUnknownParticipantIsNamedOnOneShortLine) {
    const std::string dir = scratch("participants");
    ASSERT_EQ(warplab("study init " + dir + "/small --protocol " + protocolFile("shooter-quick.json") +
                      " --participants 2 --seed 1")
                  .status,
              0);
    const Result newline = warplab::testing::runCommand(std::string(WARPLAB_BINARY) + " run --study " + dir +
                                                        "/small --participant \"$(printf 'P\\nX')\" --headless");
    expectRefused(newline, 2, "option --participant must not hold control characters, got 'P\\nX'", "newline");
    const Result unknown = warplab("run --study " + dir + "/small --participant 'P 9' --headless");
    expectRefused(unknown, 1, "has no participant 'P 9' (it plans P01, P02)", "unknown");

    ASSERT_EQ(warplab("study init " + dir + "/large --protocol " + protocolFile("shooter-quick.json") +
                      " --participants 10000 --seed 1")
                  .status,
              0);
    const Result many = warplab("run --study " + dir + "/large --participant Q1 --headless");
    expectRefused(many, 1, "has no participant 'Q1' (it plans P00001, P00002, P00003, ... and 9,997 more)", "many");
    EXPECT_LT(many.output.size(), 300u) << many.output;
}

// A headless run into a folder without room for its session is refused before its first
// frame, as a window run is: with what is free, what the session needs and what to do, and no
// file. It used to fail partway ("database or disk is full"), leaving a damaged file. The full
// disk is a real one: a 256 kB tmpfs, mounted in a mount namespace of the test's own, which
// needs root (or a user namespace); without one the test says so and skips.
TEST(Refusals, AHeadlessRunWithoutRoomForItsSessionIsRefusedBeforeItStarts) {
    const std::string dir = scratch("no-room");
    const std::string mount = "mount -t tmpfs -o size=256k tmpfs " + dir;
    if (warplab::testing::runCommand("unshare -m sh -c '" + mount + "'").status != 0)
        GTEST_SKIP() << "no mount namespace to make a small disk in (needs root)";
    const std::string run = std::string(WARPLAB_BINARY) + " run --headless --protocol " +
        protocolFile("shooter-quick.json") + " --participant D --seed 1 --out " + dir;
    // What the run printed, then what the small disk held after it.
    const Result r = warplab::testing::runCommand("unshare -m sh -c '" + mount + " && " + run +
                                                  "; echo \"exit $?\"; ls " + dir + "'");
    EXPECT_TRUE(contains(r.output, "warplab run: Results folder '" + dir + "' has ")) << r.output;
    EXPECT_TRUE(contains(r.output, " kB free but a session of shooter-quick needs ")) << r.output;
    EXPECT_TRUE(contains(r.output, "; free some space, or use another --out.\nexit 1\n")) << r.output;
    EXPECT_FALSE(contains(r.output, ".warplab-session")) << "a session file was begun:\n" << r.output;
    EXPECT_EQ(r.lines(), 2) << r.output;
}

}  // namespace
