// Every file a user hands warplab goes through the one strict reader (strict/): a study plan,
// its protocol copies and a population that are no regular file, too deep, or have bytes after
// their JSON are refused at once, in one sentence naming the file and the field or line, with
// the documented exit status 1, by each command that reads them (README, "Exit codes").
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli/cli_support.h"

namespace {

namespace fs = std::filesystem;
using warplab::testing::contains;
using warplab::testing::Result;

std::string scratch(const std::string& name) { return warplab::testing::scratch("cli-strict", name); }

std::string protocolFile(const char* name) { return std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name; }

// warplab, bounded: a reader that blocks (a FIFO) is killed after 20 s, and one that reads
// without end (/dev/zero) runs out of its 4 GB of address space rather than the machine's
// memory. Either shows as an exit status other than the one expected (137, or 1 with
// "std::bad_alloc" and no file named).
Result bounded(const std::string& arguments) {
    return warplab::testing::runCommand("ulimit -v 4000000; timeout -s KILL 20 " + std::string(WARPLAB_BINARY) + " " +
                                        arguments);
}

// Refused, exit 1, in one line that says `sentence`.
void expectRefused(const Result& r, const std::string& sentence, const std::string& what) {
    EXPECT_EQ(r.status, 1) << what << ":\n" << r.output;
    EXPECT_TRUE(contains(r.output, sentence)) << what << ":\n" << r.output << "\nlacks: " << sentence;
    EXPECT_EQ(r.lines(), 1) << what << ":\n" << r.output;
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `path` replaced by a FIFO, or by a link to a device.
void makeFifo(const std::string& path) {
    fs::remove(path);
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0) << path;
}
void linkTo(const std::string& path, const std::string& target) {
    fs::remove(path);
    fs::create_symlink(target, path);
}

// A plan of two participants over shooter-quick, in `dir`.
void makePlan(const std::string& dir) {
    const auto init = warplab::testing::warplab("study init " + dir + " --protocol " +
                                                protocolFile("shooter-quick.json") + " --participants 2 --seed 3");
    ASSERT_EQ(init.status, 0) << init.output;
}

// study status, run --study and export --study: each reads study.json and the protocol copies.
void expectEveryPlanCommandRefuses(const std::string& dir, const std::string& sentence, const std::string& what) {
    expectRefused(bounded("study status " + dir), sentence, what + ", study status");
    expectRefused(bounded("run --study " + dir + " --participant P01 --headless --player bot"), sentence,
                  what + ", run --study");
    expectRefused(bounded("export " + dir + "/results --out " + dir + "/csv --study " + dir), sentence,
                  what + ", export --study");
}

TEST(CliStrict, AStudyPlanThatIsNoRegularFileOrTooDeepIsRefusedAtOnce) {
    const std::string dir = scratch("plan");
    makePlan(dir);
    // One session, so that export has something to export before it reads the plan.
    const auto run = warplab::testing::warplab("run --study " + dir + " --participant P02 --headless --player bot");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string plan = dir + "/study.json", text = readText(plan);
    const std::string named = "study plan '" + plan + "': ";

    std::ofstream(plan, std::ios::binary) << std::string(100000, '[') + std::string(100000, ']');
    expectEveryPlanCommandRefuses(dir, named + "nested deeper than 32 levels at line 1", "100000 levels deep");
    std::ofstream(plan, std::ios::binary) << text << std::string(1, '\0') << "garbage";
    const auto lines = std::count(text.begin(), text.end(), '\n');
    expectEveryPlanCommandRefuses(dir,
                                  named + "has a NUL byte at line " + std::to_string(lines + 1) +
                                      ": a study plan is text, and nothing after it would be read",
                                  "a NUL and garbage after the JSON");
    makeFifo(plan);
    expectEveryPlanCommandRefuses(dir, named + "is a FIFO (a named pipe), not a regular file", "a FIFO");
    for (const char* device : {"/dev/zero", "/dev/urandom"}) {
        linkTo(plan, device);
        expectEveryPlanCommandRefuses(dir, named + "is a device, not a regular file", device);
    }
}

TEST(CliStrict, AProtocolCopyThatIsNoRegularFileIsRefusedNamingItsField) {
    const std::string dir = scratch("copy");
    makePlan(dir);
    const std::string copy = dir + "/protocols/shooter-quick.json";
    const std::string named =
        "study plan '" + dir + "/study.json': protocols[0].file \"protocols/shooter-quick.json\": ";
    makeFifo(copy);
    expectRefused(bounded("study status " + dir), named + "is a FIFO (a named pipe), not a regular file (" + copy + ")",
                  "a FIFO, study status");
    expectRefused(bounded("run --study " + dir + " --participant P01 --headless --player bot"),
                  named + "is a FIFO (a named pipe), not a regular file (" + copy + ")", "a FIFO, run --study");
    linkTo(copy, "/dev/zero");
    expectRefused(bounded("study status " + dir), named + "is a device, not a regular file (" + copy + ")",
                  "/dev/zero, study status");
}

TEST(CliStrict, APopulationThatIsNoRegularFileOrNotStrictJsonIsRefusedAtOnce) {
    const std::string dir = scratch("population");
    const std::string population = dir + "/population.json";
    const auto refusedBy = [&](const std::string& sentence, const std::string& what) {
        expectRefused(bounded("run --seed 1 --protocol " + protocolFile("shooter-quick.json") +
                              " --participant S1 --out " + dir + " --headless --player sim --population " + population),
                      sentence, what + ", run");
        expectRefused(bounded("demo --out " + dir + "/demo --protocols shooter-quick --population " + population),
                      sentence, what + ", demo");
    };
    const std::string named = "population file '" + population + "': ";
    makeFifo(population);
    refusedBy(named + "is a FIFO (a named pipe), not a regular file", "a FIFO");
    for (const char* device : {"/dev/zero", "/dev/urandom"}) {
        linkTo(population, device);
        refusedBy(named + "is a device, not a regular file", device);
    }
    fs::remove(population);
    std::string shipped = readText(std::string(WARPLAB_SOURCE_DIR) + "/assets/population.json");
    std::ofstream(population, std::ios::binary)
        << shipped.replace(shipped.find("\"median\": 0.2"), 13, "\"median\": 1e999");
    refusedBy(named + "unreadable JSON at line 5, number overflow parsing '1e999' (beyond what a double holds)",
              "1e999");
    EXPECT_TRUE(warplab::testing::sessionIn(dir).empty());
}

}  // namespace
