// The session store: exact round trip, crash safety (a real SIGKILL mid-session), damaged
// files, format versions and participant ids that try to be paths.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "protocol/session_store.h"

namespace warplab::protocol {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class TempDir {
public:
    TempDir() {
        std::string pattern = (fs::temp_directory_path() / "warplab-session-XXXXXX").string();
        if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
        fs::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return path_; }
    std::string str() const { return path_.string(); }

private:
    fs::path path_;
};

std::vector<fs::path> filesIn(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& entry : fs::directory_iterator(dir)) out.push_back(entry.path());
    return out;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

SessionHeader sampleHeader(const std::string& participant = "P07") {
    SessionHeader h;
    h.protocolJson = R"({"study": "shooter", "modes": ["conv15", "conv120", "warp15to120"]})";
    h.seed = 18446744073709551557ull;  // above INT64_MAX: must not go through a signed column
    h.participant = participant;
    h.appVersion = "0.1.0";
    h.glRenderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
    h.glVersion = "4.5 (Core Profile) Mesa 22.3.6";
    h.refreshHz = 143.98 + 1.0 / 3.0;
    h.displayWidth = 2560;
    h.displayHeight = 1440;
    h.startedAt = "2024-05-01T12:34:56.789Z";
    h.player = "bot:7";
    return h;
}

// ---- what a study writes per trial: a pure function of the trial index ----

constexpr int kFramesPerTrial = 48;
constexpr int kEventsPerTrial = 2;

InputRecord trialInput(std::int64_t frame) {
    InputRecord r;
    r.frame = frame;
    r.displayTime = static_cast<double>(frame) / 120.0;
    r.mouseDx = std::sin(0.37 * static_cast<double>(frame)) * 3.25;
    r.mouseDy = frame % 5 == 0 ? -0.0 : 1.0 / static_cast<double>(frame + 3);
    r.buttons = frame % 7 == 0 ? 1u : 0u;
    r.keys = static_cast<std::uint32_t>(frame * 2654435761u);
    return r;
}

FrameRecord trialFrame(std::int64_t frame) {
    FrameRecord r;
    r.frame = frame;
    r.mode = frame % 3 == 0 ? "warp15to120" : "conv15";
    r.kind = frame % 8 == 0 ? "rendered" : "warped";
    r.frameMs = 8.0 + std::cos(static_cast<double>(frame));
    r.missedVsyncs = static_cast<int>(frame % 4 == 3);
    r.cameraYaw = 0.001 * static_cast<double>(frame);
    r.cameraPitch = -1.0 / 7.0;
    r.targetX = std::sqrt(static_cast<double>(frame));
    r.targetY = 4.5;
    r.targetZ = -7.31;
    r.targetVisible = frame % 2 == 0;
    return r;
}

EventRecord trialEvent(int trial, int k) {
    EventRecord e;
    const std::int64_t first = static_cast<std::int64_t>(trial) * kFramesPerTrial;
    e.frame = k == 0 ? first : first + kFramesPerTrial - 1;
    e.type = k == 0 ? "trial_start" : "shot";
    e.phase = "test";
    e.trial = trial;
    e.mode = "warp15to120";
    e.difficulty = trial % 4;
    e.targetSpeed = 1.5 * std::pow(2.0, (trial % 4) / 6.0);
    e.spawnTime = static_cast<double>(first) / 120.0;
    e.eventTime = static_cast<double>(e.frame) / 120.0;
    e.aimTime = e.eventTime - e.spawnTime;
    e.worldOutcome = k == 0 ? "" : (trial % 3 ? "hit" : "miss");
    e.displayedOutcome = k == 0 ? "" : (trial % 5 ? "hit" : "miss");
    e.angularErrorDeg = k == 0 ? 0.0 : 0.1 * trial + 1.0 / 3.0;
    e.detailJson = k == 0 ? "" : R"({"clicks": )" + std::to_string(trial % 3 + 1) + "}";
    return e;
}

void writeTrial(SessionWriter& w, int trial) {
    w.addEvent(trialEvent(trial, 0));
    for (int i = 0; i < kFramesPerTrial; ++i) {
        const std::int64_t frame = static_cast<std::int64_t>(trial) * kFramesPerTrial + i;
        w.addInput(trialInput(frame));
        w.addFrame(trialFrame(frame));
    }
    w.addEvent(trialEvent(trial, 1));
}

// ---- field-by-field, bit-exact comparisons ----

void expectSame(const InputRecord& a, const InputRecord& b) {
    EXPECT_EQ(a.frame, b.frame);
    EXPECT_TRUE(sameBits(a.displayTime, b.displayTime)) << a.frame;
    EXPECT_TRUE(sameBits(a.mouseDx, b.mouseDx)) << a.frame;
    EXPECT_TRUE(sameBits(a.mouseDy, b.mouseDy)) << a.frame;
    EXPECT_EQ(a.buttons, b.buttons);
    EXPECT_EQ(a.keys, b.keys);
}

void expectSame(const FrameRecord& a, const FrameRecord& b) {
    EXPECT_EQ(a.frame, b.frame);
    EXPECT_EQ(a.mode, b.mode);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_TRUE(sameBits(a.frameMs, b.frameMs)) << a.frame;
    EXPECT_EQ(a.missedVsyncs, b.missedVsyncs);
    EXPECT_TRUE(sameBits(a.cameraYaw, b.cameraYaw)) << a.frame;
    EXPECT_TRUE(sameBits(a.cameraPitch, b.cameraPitch)) << a.frame;
    EXPECT_TRUE(sameBits(a.targetX, b.targetX)) << a.frame;
    EXPECT_TRUE(sameBits(a.targetY, b.targetY)) << a.frame;
    EXPECT_TRUE(sameBits(a.targetZ, b.targetZ)) << a.frame;
    EXPECT_EQ(a.targetVisible, b.targetVisible);
}

void expectSame(const EventRecord& a, const EventRecord& b) {
    EXPECT_EQ(a.frame, b.frame);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.phase, b.phase);
    EXPECT_EQ(a.trial, b.trial);
    EXPECT_EQ(a.mode, b.mode);
    EXPECT_EQ(a.difficulty, b.difficulty);
    EXPECT_TRUE(sameBits(a.targetSpeed, b.targetSpeed));
    EXPECT_TRUE(sameBits(a.spawnTime, b.spawnTime));
    EXPECT_TRUE(sameBits(a.eventTime, b.eventTime));
    EXPECT_TRUE(sameBits(a.aimTime, b.aimTime));
    EXPECT_EQ(a.worldOutcome, b.worldOutcome);
    EXPECT_EQ(a.displayedOutcome, b.displayedOutcome);
    EXPECT_TRUE(sameBits(a.angularErrorDeg, b.angularErrorDeg));
    EXPECT_EQ(a.detailJson, b.detailJson);
}

void expectSame(const SessionHeader& a, const SessionHeader& b) {
    EXPECT_EQ(a.protocolJson, b.protocolJson);
    EXPECT_EQ(a.seed, b.seed);
    EXPECT_EQ(a.participant, b.participant);
    EXPECT_EQ(a.appVersion, b.appVersion);
    EXPECT_EQ(a.glRenderer, b.glRenderer);
    EXPECT_EQ(a.glVersion, b.glVersion);
    EXPECT_TRUE(sameBits(a.refreshHz, b.refreshHz));
    EXPECT_EQ(a.displayWidth, b.displayWidth);
    EXPECT_EQ(a.displayHeight, b.displayHeight);
    EXPECT_EQ(a.startedAt, b.startedAt);
    EXPECT_EQ(a.player, b.player);
    EXPECT_EQ(a.formatVersion, b.formatVersion);
}

// Holds when `data` is exactly trials 0 .. n-1 as writeTrial writes them; returns n.
// Anything else -- a partial trial, a changed value -- fails the calling test.
int expectWholeTrials(const SessionData& data) {
    const int trials = static_cast<int>(data.events.size()) / kEventsPerTrial;
    const auto whole = [&](std::size_t perTrial) {
        return static_cast<std::size_t>(trials) * perTrial;
    };
    const bool sized = data.events.size() == whole(kEventsPerTrial) &&
                       data.inputs.size() == whole(kFramesPerTrial) &&
                       data.frames.size() == whole(kFramesPerTrial);
    EXPECT_TRUE(sized) << "not whole trials: " << data.inputs.size() << " inputs, "
                       << data.frames.size() << " frames, " << data.events.size() << " events";
    if (!sized) return -1;
    for (std::size_t i = 0; i < data.inputs.size(); ++i) {
        expectSame(data.inputs[i], trialInput(static_cast<std::int64_t>(i)));
        expectSame(data.frames[i], trialFrame(static_cast<std::int64_t>(i)));
    }
    for (std::size_t i = 0; i < data.events.size(); ++i)
        expectSame(data.events[i], trialEvent(static_cast<int>(i) / kEventsPerTrial,
                                              static_cast<int>(i) % kEventsPerTrial));
    return trials;
}

// ---- raw SQLite access, to tamper with files the way the outside world might ----

void execSql(const std::string& path, const std::string& sql) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    char* error = nullptr;
    const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
    const std::string message = error ? error : "";
    sqlite3_free(error);
    sqlite3_close(db);
    ASSERT_EQ(rc, SQLITE_OK) << message;
}

// Copies a session to dst as if the disk had lost the rest: the main file cut to mainBytes
// (kWhole: all of it) and the WAL cut to walBytes (kWhole: all of it; kNoWal: not copied, as
// if deleted). Stale -shm files of earlier copies are removed first.
constexpr std::intmax_t kWhole = -1;
constexpr std::intmax_t kNoWal = -2;
void copySession(const std::string& src, const std::string& dst, std::intmax_t mainBytes,
                 std::intmax_t walBytes) {
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(dst + suffix);
    fs::copy_file(src, dst);
    if (mainBytes != kWhole) fs::resize_file(dst, static_cast<std::uintmax_t>(mainBytes));
    if (walBytes != kNoWal && fs::exists(src + "-wal")) {
        fs::copy_file(src + "-wal", dst + "-wal");
        if (walBytes != kWhole) fs::resize_file(dst + "-wal", static_cast<std::uintmax_t>(walBytes));
    }
}

// A finished session of `trials` trials, each committed on its own; returns its path.
std::string writeFinishedSession(const std::string& dir, int trials) {
    SessionWriter w = SessionWriter::create(dir, sampleHeader());
    const std::string path = w.path();
    for (int t = 0; t < trials; ++t) {
        writeTrial(w, t);
        w.commit();
    }
    w.finish();
    return path;
}

std::string errorOf(const std::string& path) {
    try {
        readSession(path);
    } catch (const SessionError& e) {
        return e.what();
    }
    return "";
}

// ============================ round trip ============================

TEST(SessionStore, RoundTripsEveryFieldBitExactly) {
    TempDir dir;
    SessionHeader header = sampleHeader("Zoë «P7»\n");
    header.protocolJson = std::string("{\"a\": \"nul\0inside\"}", 20);

    InputRecord input;
    input.frame = 0;
    input.displayTime = 1.0 / 3.0;
    input.mouseDx = -0.0;
    input.mouseDy = std::numeric_limits<double>::denorm_min();
    input.buttons = 0xffffffffu;
    input.keys = 0x80000001u;

    FrameRecord frame;
    frame.frame = 0;
    frame.mode = "bireproj15to60";
    frame.kind = "interpolated";
    frame.frameMs = 0.1 + 0.2;
    frame.missedVsyncs = -3;
    frame.cameraYaw = -std::numeric_limits<double>::max();
    frame.cameraPitch = std::nextafter(1.0, 2.0);
    frame.targetX = std::numeric_limits<double>::infinity();
    frame.targetY = -std::numeric_limits<double>::infinity();
    frame.targetZ = -7.3125e-300;
    frame.targetVisible = true;

    EventRecord event;
    event.frame = 0;
    event.type = "shot";
    event.phase = "training";
    event.trial = 224;
    event.mode = "lag200";
    event.difficulty = -5;
    event.targetSpeed = 2.0 / 3.0;
    event.spawnTime = 1e-17;
    event.eventTime = 12345.678901234567;
    event.aimTime = -0.0;
    event.worldOutcome = "hit";
    event.displayedOutcome = "miss";
    event.angularErrorDeg = std::numeric_limits<double>::quiet_NaN();
    event.detailJson = R"({"ids": [2, 16], "note": "ünï"})";

    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), header);
        path = w.path();
        w.addInput(input);
        w.addFrame(frame);
        w.addEvent(event);
        InputRecord second = input;
        second.frame = std::numeric_limits<std::int64_t>::max();
        w.addInput(second);
        w.finish();
    }
    const SessionData data = readSession(path);
    expectSame(data.header, header);
    ASSERT_EQ(data.inputs.size(), 2u);
    expectSame(data.inputs[0], input);
    EXPECT_EQ(data.inputs[1].frame, std::numeric_limits<std::int64_t>::max());
    ASSERT_EQ(data.frames.size(), 1u);
    expectSame(data.frames[0], frame);
    ASSERT_EQ(data.events.size(), 1u);
    // NaN is stored as SQL NULL: it comes back as a NaN, not bit for bit.
    EXPECT_TRUE(std::isnan(data.events[0].angularErrorDeg));
    EventRecord expected = event;
    expected.angularErrorDeg = data.events[0].angularErrorDeg;
    expectSame(data.events[0], expected);
    EXPECT_TRUE(data.completed);
    EXPECT_EQ(data.note, "");
    // finish() folds the WAL in: one self-contained file.
    EXPECT_EQ(filesIn(dir.path()).size(), 1u);
}

TEST(SessionStore, FillsInTheStartTimeWhenEmpty) {
    TempDir dir;
    SessionHeader header = sampleHeader();
    header.startedAt.clear();
    SessionWriter w = SessionWriter::create(dir.str(), header);
    w.finish();
    const std::string started = readSession(w.path()).header.startedAt;
    ASSERT_EQ(started.size(), 24u) << started;  // 2024-05-01T12:34:56.789Z
    EXPECT_EQ(started[10], 'T');
    EXPECT_EQ(started.back(), 'Z');
    EXPECT_NE(w.path().find(started.substr(0, 4)), std::string::npos) << w.path();
}

// Analysts read the tables with plain SQL: doubles are SQLite REALs holding the same bits.
TEST(SessionStore, DoublesAreSqlRealsWithTheSameBits) {
    TempDir dir;
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        writeTrial(w, 0);
        w.finish();
    }
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db,
                                 "SELECT frame, typeof(display_time), display_time, "
                                 "typeof(mouse_dy), mouse_dy FROM input ORDER BY frame",
                                 -1, &s, nullptr),
              SQLITE_OK);
    int rows = 0;
    while (sqlite3_step(s) == SQLITE_ROW) {
        const InputRecord expected = trialInput(sqlite3_column_int64(s, 0));
        EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(s, 1)), "real");
        EXPECT_TRUE(sameBits(sqlite3_column_double(s, 2), expected.displayTime));
        // -0.0 (frames 0, 5, ...) stays a REAL -0.0, not the integer 0.
        EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(s, 3)), "real");
        EXPECT_TRUE(sameBits(sqlite3_column_double(s, 4), expected.mouseDy));
        ++rows;
    }
    sqlite3_finalize(s);
    sqlite3_close(db);
    EXPECT_EQ(rows, kFramesPerTrial);
}

TEST(SessionStore, DiscardsTheUncommittedTail) {
    TempDir dir;
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        writeTrial(w, 0);
        writeTrial(w, 1);
        w.commit();
        writeTrial(w, 2);  // never committed: the writer goes away as in a crash
    }
    const SessionData data = readSession(path);
    EXPECT_EQ(expectWholeTrials(data), 2);
    EXPECT_FALSE(data.completed);
    EXPECT_EQ(data.note, "incomplete: ends after frame 95 (last commit, 1 in all)");
}

TEST(SessionStore, ReadsARunningSessionUpToItsLastCommit) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    EXPECT_EQ(readSession(w.path()).note, "incomplete: no trial was committed");
    writeTrial(w, 0);
    w.commit();
    writeTrial(w, 1);  // in an open transaction while we read
    const SessionData data = readSession(w.path());
    EXPECT_EQ(expectWholeTrials(data), 1);
    EXPECT_FALSE(data.completed);
    w.commit();
    EXPECT_EQ(expectWholeTrials(readSession(w.path())), 2);
}

TEST(SessionStore, RejectsRecordsOutOfOrderAndBadDetail) {
    TempDir dir;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    w.addInput(trialInput(10));
    EXPECT_THROW(w.addInput(trialInput(10)), std::invalid_argument);
    EXPECT_THROW(w.addInput(trialInput(9)), std::invalid_argument);
    w.addFrame(trialFrame(3));
    EXPECT_THROW(w.addFrame(trialFrame(2)), std::invalid_argument);
    EventRecord e = trialEvent(0, 1);
    e.detailJson = "[1, 2]";
    EXPECT_THROW(w.addEvent(e), std::invalid_argument);
    e.detailJson = "{not json";
    EXPECT_THROW(w.addEvent(e), std::invalid_argument);
    w.commit();
    const SessionData data = readSession(w.path());
    EXPECT_EQ(data.inputs.size(), 1u);
    EXPECT_EQ(data.frames.size(), 1u);
    EXPECT_EQ(data.events.size(), 0u);
    w.finish();
    EXPECT_THROW(w.addInput(trialInput(11)), std::logic_error);
    SessionWriter moved = std::move(w);
    EXPECT_THROW(w.commit(), std::logic_error);  // NOLINT(bugprone-use-after-move)
    EXPECT_TRUE(readSession(moved.path()).completed);
}

// ============================ kill -9 ============================

// A child writes a session one committed trial at a time, forever, and reports each commit
// that returned through a pipe; the parent SIGKILLs it after a random few milliseconds. The
// file must hold every reported trial (durable), at most one more (committed but killed before
// reporting), and nothing partial.
// Kills and reaps the child if an assertion leaves the test early, so it never outlives it.
struct ChildGuard {
    pid_t pid = -1;
    ~ChildGuard() {
        if (pid <= 0) return;
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
    }
};

TEST(SessionStoreKill, KeepsEveryCommittedTrialAndNothingPartial) {
    std::mt19937 rng(20240501u);
    std::uniform_int_distribution<int> delayUs(1000, 50000);
    int killedMidSession = 0;
    for (int iteration = 0; iteration < 12; ++iteration) {
        SCOPED_TRACE("iteration " + std::to_string(iteration));
        TempDir dir;
        int pipeFds[2];
        ASSERT_EQ(::pipe(pipeFds), 0);
        const pid_t pid = ::fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            // Child: no gtest here; any way out other than SIGKILL is a failure the parent sees.
            ::close(pipeFds[0]);
            try {
                SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
                if (::write(pipeFds[1], "R", 1) != 1) ::_exit(3);
                const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
                for (int trial = 0; std::chrono::steady_clock::now() < deadline; ++trial) {
                    writeTrial(w, trial);
                    w.commit();
                    if (::write(pipeFds[1], "c", 1) != 1) ::_exit(3);
                }
            } catch (...) {
                ::_exit(4);
            }
            ::_exit(5);  // never killed: the parent is gone
        }
        ChildGuard guard{pid};
        ::close(pipeFds[1]);
        char ready = 0;
        ASSERT_EQ(::read(pipeFds[0], &ready, 1), 1);
        ASSERT_EQ(ready, 'R');
        std::this_thread::sleep_for(std::chrono::microseconds(delayUs(rng)));
        ASSERT_EQ(::kill(pid, SIGKILL), 0);
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        guard.pid = -1;
        ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
            << "child ended otherwise, status " << status;
        int reported = 0;
        char buf[4096];
        for (ssize_t n; (n = ::read(pipeFds[0], buf, sizeof buf)) > 0;) reported += static_cast<int>(n);
        ::close(pipeFds[0]);

        std::vector<fs::path> sessions;
        for (const fs::path& p : filesIn(dir.path()))
            if (p.extension() == ".warplab-session") sessions.push_back(p);
        ASSERT_EQ(sessions.size(), 1u);
        const SessionData data = readSession(sessions[0].string());
        const int trials = expectWholeTrials(data);
        EXPECT_GE(trials, reported);
        EXPECT_LE(trials, reported + 1);
        EXPECT_FALSE(data.completed);
        EXPECT_EQ(data.note.rfind("incomplete: ", 0), 0u) << data.note;
        expectSame(data.header, sampleHeader());
        if (trials > 0) ++killedMidSession;
    }
    // The delays must have let some children get going, or the test proved nothing.
    EXPECT_GE(killedMidSession, 2);
}

// ============================ damaged files ============================

// A finished session cut at many byte offsets, as a full disk or a bad copy leaves it.
TEST(SessionStoreDamage, TruncatedFileKeepsWholeCommitsOrFailsNamingThePath) {
    TempDir dir;
    constexpr int kTrials = 40;
    const std::string path = writeFinishedSession(dir.str(), kTrials);
    const auto size = static_cast<std::intmax_t>(fs::file_size(path));
    ASSERT_GT(size, 16 * 4096);
    std::vector<std::intmax_t> cuts = {0, 1, 50, 99, 100, 101, 1000, size - 1};
    for (std::intmax_t page = 4096; page < size; page += 4096)
        for (std::intmax_t offset : {page - 1, page, page + 1, page + 2000}) cuts.push_back(offset);

    const std::string copy = (dir.path() / "copy.warplab-session").string();
    int partial = 0, refused = 0;
    for (const std::intmax_t cut : cuts) {
        if (cut >= size) continue;
        SCOPED_TRACE("cut at byte " + std::to_string(cut) + " of " + std::to_string(size));
        copySession(path, copy, cut, kNoWal);
        try {
            const SessionData data = readSession(copy);
            const int trials = expectWholeTrials(data);
            EXPECT_LT(trials, kTrials);
            EXPECT_FALSE(data.completed);
            EXPECT_FALSE(data.note.empty());
            if (trials > 0) ++partial;
        } catch (const SessionError& e) {
            EXPECT_NE(std::string(e.what()).find(copy), std::string::npos) << e.what();
            ++refused;
        }
        if (::testing::Test::HasFailure()) break;
    }
    // Both outcomes must really occur: early cuts lose the header, later ones keep trials.
    EXPECT_GT(partial, 0);
    EXPECT_GT(refused, 0);
}

// A session killed with its WAL not yet checkpointed, then the WAL cut short or lost.
TEST(SessionStoreDamage, TruncatedOrMissingWalKeepsWholeCommits) {
    TempDir dir;
    constexpr int kTrials = 12;
    SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
    for (int t = 0; t < kTrials; ++t) {
        writeTrial(w, t);
        w.commit();
    }
    const std::string path = w.path();
    ASSERT_TRUE(fs::exists(path + "-wal"));
    const auto walSize = static_cast<std::intmax_t>(fs::file_size(path + "-wal"));
    const std::string copy = (dir.path() / "copy.warplab-session").string();

    copySession(path, copy, kWhole, kWhole);
    EXPECT_EQ(expectWholeTrials(readSession(copy)), kTrials);

    int previous = -1;
    for (std::intmax_t cut = 0; cut < walSize; cut += 997) {
        SCOPED_TRACE("WAL cut at byte " + std::to_string(cut) + " of " + std::to_string(walSize));
        copySession(path, copy, kWhole, cut);
        const int trials = expectWholeTrials(readSession(copy));
        EXPECT_GE(trials, previous);  // more log, never fewer trials
        previous = trials;
        if (::testing::Test::HasFailure()) break;
    }
    EXPECT_LT(previous, kTrials);

    // The -wal deleted: the header was checkpointed into the main file, so it still reads.
    copySession(path, copy, kWhole, kNoWal);
    const SessionData data = readSession(copy);
    EXPECT_GE(expectWholeTrials(data), 0);
    EXPECT_FALSE(data.completed);
    expectSame(data.header, sampleHeader());
    w.finish();
}

// Garbage over whole pages: whatever survives, reading never crashes or throws anything but
// SessionError.
TEST(SessionStoreDamage, GarbagePagesNeverCrashTheReader) {
    TempDir dir;
    const std::string path = writeFinishedSession(dir.str(), 20);
    const auto size = fs::file_size(path);
    const std::string copy = (dir.path() / "copy.warplab-session").string();
    std::mt19937 rng(7);
    for (std::uintmax_t page = 0; page * 4096 < size; ++page) {
        SCOPED_TRACE("garbage in page " + std::to_string(page + 1));
        copySession(path, copy, kWhole, kNoWal);
        {
            std::fstream f(copy, std::ios::in | std::ios::out | std::ios::binary);
            f.seekp(static_cast<std::streamoff>(page * 4096 + (page == 0 ? 100 : 0)));
            for (int i = 0; i < 4096 - (page == 0 ? 100 : 0); ++i)
                f.put(static_cast<char>(rng() & 0xff));
        }
        try {
            const SessionData data = readSession(copy);
            EXPECT_LE(data.inputs.size(), 20u * kFramesPerTrial);
            EXPECT_LE(data.events.size(), 20u * kEventsPerTrial);
        } catch (const SessionError& e) {
            EXPECT_NE(std::string(e.what()).find(copy), std::string::npos) << e.what();
        }
    }
}

// SQLite would read most flipped bits as valid but different data. The per-commit checksums
// must turn every one of them into "fewer whole trials" or an error -- never wrong values.
TEST(SessionStoreDamage, FlippedBytesNeverPassAsData) {
    TempDir dir;
    constexpr int kTrials = 8;
    const std::string path = writeFinishedSession(dir.str(), kTrials);
    const auto size = static_cast<std::streamoff>(fs::file_size(path));
    const std::string copy = (dir.path() / "copy.warplab-session").string();
    int shortened = 0;
    for (std::streamoff offset = 3; offset < size; offset += 53) {
        SCOPED_TRACE("byte " + std::to_string(offset) + " flipped");
        copySession(path, copy, kWhole, kNoWal);
        {
            std::fstream f(copy, std::ios::in | std::ios::out | std::ios::binary);
            f.seekg(offset);
            const int byte = f.get();
            f.seekp(offset);
            f.put(static_cast<char>(byte ^ 0x5a));
        }
        try {
            const int trials = expectWholeTrials(readSession(copy));
            if (trials < kTrials) ++shortened;
        } catch (const SessionError& e) {
            EXPECT_NE(std::string(e.what()).find(copy), std::string::npos) << e.what();
        }
        if (::testing::Test::HasFailure()) break;
    }
    EXPECT_GT(shortened, 0);
}

TEST(SessionStoreDamage, NotASessionFailsNamingThePath) {
    TempDir dir;
    const std::string text = (dir.path() / "notes.warplab-session").string();
    std::ofstream(text) << "participant P07 was tired\n" << std::string(5000, 'x');
    const std::string textError = errorOf(text);
    EXPECT_NE(textError.find(text), std::string::npos) << textError;
    EXPECT_NE(textError.find("not a SQLite database"), std::string::npos) << textError;

    const std::string empty = (dir.path() / "empty.warplab-session").string();
    std::ofstream{empty};
    EXPECT_NE(errorOf(empty).find(empty), std::string::npos);

    const std::string other = (dir.path() / "other.sqlite").string();
    execSql(other, "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT)");
    const std::string otherError = errorOf(other);
    EXPECT_NE(otherError.find("not a warplab session"), std::string::npos) << otherError;

    const std::string missing = (dir.path() / "missing.warplab-session").string();
    EXPECT_NE(errorOf(missing).find(missing), std::string::npos);
    EXPECT_FALSE(fs::exists(missing));
}

TEST(SessionStoreDamage, OtherFormatVersionsNameBothVersions) {
    TempDir dir;
    std::string path;
    {
        SessionWriter w = SessionWriter::create(dir.str(), sampleHeader());
        path = w.path();
        w.finish();
    }
    for (const int version : {2, 0}) {
        execSql(path, "UPDATE meta SET value = '" + std::to_string(version) +
                          "' WHERE key = 'format_version'");
        const std::string error = errorOf(path);
        EXPECT_NE(error.find(path), std::string::npos) << error;
        EXPECT_NE(error.find("version " + std::to_string(version)), std::string::npos) << error;
        EXPECT_NE(error.find("version " + std::to_string(kSessionFormatVersion)), std::string::npos)
            << error;
    }
    execSql(path, "UPDATE meta SET value = '1' WHERE key = 'format_version'; "
                  "ALTER TABLE frames DROP COLUMN kind");
    const std::string schemaError = errorOf(path);
    EXPECT_NE(schemaError.find("schema"), std::string::npos) << schemaError;
    EXPECT_NE(schemaError.find("kind"), std::string::npos) << schemaError;
}

// ============================ names and folders ============================

TEST(SessionNames, ParticipantIdNeverEscapesTheResultsFolder) {
    TempDir root;
    const fs::path results = root.path() / "results";
    fs::create_directories(results / "a");  // so "a/b" would have somewhere to go
    const std::vector<std::string> ids = {
        "../../etc/passwd", "a/b", "..", ".", "", std::string("\x01\n", 2),
        std::string(500, 'q'), "Zoë 김 🎯", "-rf", std::string("nul\0byte", 8), "P07", "P07"};
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
            EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ||
                        c == '.')
                << name;
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

    const fs::path locked = root.path() / "locked";
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    if (::access(locked.c_str(), W_OK) == 0) {
        // Root writes anywhere; a folder the kernel itself refuses stands in.
        EXPECT_THROW(SessionWriter::create("/proc/self", sampleHeader()), SessionError);
    } else {
        try {
            SessionWriter::create(locked.string(), sampleHeader());
            ADD_FAILURE() << "no error for an unwritable folder";
        } catch (const SessionError& e) {
            EXPECT_NE(std::string(e.what()).find(locked.string()), std::string::npos) << e.what();
        }
    }
    EXPECT_TRUE(filesIn(locked).empty());
    EXPECT_EQ(filesIn(root.path()).size(), 2u);  // results.txt and locked, nothing else
}

}  // namespace
}  // namespace warplab::protocol
