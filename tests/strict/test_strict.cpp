// The one strict reader (strict/): files that are not regular files refused before they are
// read (promptly: a FIFO must not block), sizes and depths bounded, JSON's repeated keys, NUL
// bytes and numbers beyond a double refused, numbers in text checked whole, each refusal one
// sentence naming the file and the field or line.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <string>
#include <thread>

#include "strict/file.h"
#include "strict/json.h"
#include "strict/number.h"

namespace warplab::strict {
namespace {

namespace fs = std::filesystem;

// An empty folder build/test-output/strict/<name>.
std::string scratch(const std::string& name) {
    const fs::path dir = fs::path(WARPLAB_BINARY_DIR) / "test-output" / "strict" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

std::string written(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

Source source(const std::string& path, std::size_t maxBytes = 1 << 20) { return {"test file", path, maxBytes}; }

// What reading the file says, or "(read)". On a thread of its own, so that a reader that
// blocks (a FIFO) fails the test after a few seconds instead of hanging it; the blocked thread
// is left behind, and ends with the process.
std::string problemWithin(const std::string& path, std::size_t maxBytes = 1 << 20) {
    auto done = std::make_shared<std::promise<std::string>>();
    std::future<std::string> answer = done->get_future();
    std::thread([done, path, maxBytes] {
        try {
            readFile(source(path, maxBytes));
            done->set_value("(read)");
        } catch (const Error& e) {
            done->set_value(e.what());
        }
    }).detach();
    if (answer.wait_for(std::chrono::seconds(5)) != std::future_status::ready) return "(still reading after 5 s)";
    return answer.get();
}

TEST(StrictFile, ReadsARegularFileWhole) {
    const std::string dir = scratch("regular");
    EXPECT_EQ(readFile(source(written(dir, "a.txt", std::string("a\0b\n", 4)))), std::string("a\0b\n", 4));
}

TEST(StrictFile, RefusesWhatIsNotARegularFileWithoutReadingIt) {
    const std::string dir = scratch("not-regular");
    const std::string fifo = dir + "/fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(problemWithin(fifo), "test file '" + fifo + "': is a FIFO (a named pipe), not a regular file");
    EXPECT_EQ(problemWithin("/dev/zero"), "test file '/dev/zero': is a device, not a regular file");
    EXPECT_EQ(problemWithin("/dev/urandom"), "test file '/dev/urandom': is a device, not a regular file");
    EXPECT_EQ(problemWithin(dir), "test file '" + dir + "': is a directory, not a file");
    EXPECT_EQ(problemWithin(dir + "/none"), "test file '" + dir + "/none': no such file");
    EXPECT_EQ(problemWithin(dir + "/none/deeper"), "test file '" + dir + "/none/deeper': no such file");
    // A link is read as what it points at.
    fs::create_symlink("/dev/zero", dir + "/zero.json");
    EXPECT_EQ(problemWithin(dir + "/zero.json"), "test file '" + dir + "/zero.json': is a device, not a regular file");
}

TEST(StrictFile, RefusesAFileOverItsKindsLimit) {
    const std::string dir = scratch("big");
    const std::string path = written(dir, "big.txt", std::string(101, 'x'));
    EXPECT_EQ(problemWithin(path, 100), "test file '" + path + "': is 101 bytes, more than a test file may be (100)");
    EXPECT_EQ(problemWithin(path, 101), "(read)");
}

TEST(StrictFile, RaisesTheReadersOwnErrorType) {
    struct Mine : std::runtime_error {
        using std::runtime_error::runtime_error;
    };
    const Source s{"plan", "p.json", 10, [](const std::string& sentence) { throw Mine(sentence); }};
    EXPECT_THROW(s.fail("id", "is bad"), Mine);
    try {
        s.failAtLine(3, "is bad");
    } catch (const Mine& e) {
        EXPECT_STREQ(e.what(), "plan 'p.json' line 3: is bad");
    }
}

// What parsing `text` says, or "(read)".
std::string jsonProblem(const std::string& text) {
    try {
        Reader(source("t.json")).parseObject(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "(read)";
}

TEST(StrictJson, RefusesWhatTheLibraryWouldAcceptOrDieOn) {
    EXPECT_EQ(jsonProblem("{\"a\": 1}"), "(read)");
    EXPECT_EQ(jsonProblem(std::string(100000, '[') + std::string(100000, ']')),
              "test file 't.json': nested deeper than 32 levels at line 1");
    EXPECT_EQ(jsonProblem(std::string("{\"a\": 1}\n\0{\"b\": 2}", 18)),
              "test file 't.json': has a NUL byte at line 2: a test file is text, and nothing after it would be read");
    EXPECT_EQ(jsonProblem("{\"a\": {\"b\": 1, \"b\": 2}}"), "test file 't.json': a.b appears more than once");
    EXPECT_EQ(jsonProblem("{\"a\": [{}, {\"c\": 1, \"c\": 1}]}"), "test file 't.json': a[1].c appears more than once");
    EXPECT_EQ(jsonProblem("{\n\"a\":\n1e999}"),
              "test file 't.json': unreadable JSON at line 3, number overflow parsing '1e999' (beyond what a double "
              "holds)");
    EXPECT_EQ(jsonProblem("{} x"),
              "test file 't.json': malformed JSON at line 1, column 4: syntax error while parsing "
              "value - invalid literal; last read: '{} x'; expected end of input");
    EXPECT_EQ(jsonProblem("[1]"), "test file 't.json': the top level must be a JSON object, got array [1]");
    EXPECT_EQ(jsonProblem(std::string(2 << 20, ' ')),
              "test file 't.json': is 2097152 bytes, more than a test file may "
              "be (1048576)");
}

TEST(StrictJson, ChecksEveryNumberForTypeAndRange) {
    const Reader r(source("t.json"));
    const Json document = r.parseObject(R"({"n": 18446744073709551615, "big": 18446744073709551616, "f": 2.5,
                                           "neg": -3, "s": "4", "z": null})");
    const auto problem = [&](auto read) -> std::string {
        try {
            read();
        } catch (const Error& e) {
            return e.what();
        }
        return "(read)";
    };
    EXPECT_EQ(r.unsignedAt(document["n"], "n", 0, UINT64_MAX), UINT64_MAX);
    // 2^64 is a double to the parser, so no integer field takes it.
    EXPECT_EQ(problem([&] { r.unsignedAt(document["big"], "big", 0, UINT64_MAX); }),
              "test file 't.json': big must be an integer between 0 and 18446744073709551615, got "
              "1.8446744073709552e+19");
    EXPECT_EQ(problem([&] { r.integerAt(document["n"], "n", -5, 5); }),
              "test file 't.json': n must be an integer between -5 and 5, got 18446744073709551615");
    EXPECT_EQ(problem([&] { r.integerAt(document["f"], "f", 0, 5); }),
              "test file 't.json': f must be an integer between 0 and 5, got 2.5");
    EXPECT_EQ(r.integerAt(document["neg"], "neg", -5, 5), -3);
    EXPECT_EQ(problem([&] {
                  r.numberAt(document["s"], "s", {0, false, 5, false});
              }),
              "test file 't.json': s must be a number between 0 and 5, got string \"4\"");
    EXPECT_EQ(problem([&] {
                  r.numberAt(document["z"], "z", {0, true, 5, false});
              }),
              "test file 't.json': z must be a number greater than 0 and at most 5, got null");
    EXPECT_EQ(problem([&] { r.required(document, "", "absent"); }),
              "test file 't.json': absent is required but missing");
    EXPECT_EQ(problem([&] {
                  r.requireKnownKeys(document, "", {"n", "big", "f", "neg", "s"});
              }),
              "test file 't.json': z is not a known field (the top level may have n, big, f, neg, s)");
}

TEST(StrictJson, APathNamesARowByItsNoteAndThenItsField) {
    EXPECT_EQ(joinPath("", "a"), "a");
    EXPECT_EQ(joinPath("a", "b"), "a.b");
    EXPECT_EQ(joinPath("participants[3] (\"P04\")", "seed"), "participants[3] (\"P04\") seed");
    EXPECT_EQ(elementPath("a.b", 2), "a.b[2]");
}

TEST(StrictNumber, WholeNumbersInTextAreDigitsAloneAndInRange) {
    EXPECT_EQ(wholeNumber("0", 10), 0u);
    EXPECT_EQ(wholeNumber("007", 10), 7u);
    EXPECT_EQ(wholeNumber("18446744073709551615", UINT64_MAX), UINT64_MAX);
    EXPECT_FALSE(wholeNumber("18446744073709551616", UINT64_MAX));  // 2^64
    EXPECT_FALSE(wholeNumber("11", 10));
    for (const char* bad : {"", "-1", "+1", " 1", "1 ", "1e3", "0x10", "1.0"})
        EXPECT_FALSE(wholeNumber(bad, 100)) << bad;
}

TEST(StrictNumber, DecimalNumbersInTextAreFiniteAndInRange) {
    const NumberRange range{-100, false, 100, false};
    EXPECT_EQ(decimalNumber("-12.5", range), -12.5);
    EXPECT_EQ(decimalNumber("1e2", range), 100.0);
    for (const char* bad : {"", "nan", "inf", "-inf", "1e999", "101", "12px", "0x10", " 1", "+1"})
        EXPECT_FALSE(decimalNumber(bad, range)) << bad;
}

}  // namespace
}  // namespace warplab::strict
