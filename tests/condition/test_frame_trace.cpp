// Frame-time traces of real games: MangoHud and PresentMon logs (samples written here from the
// formats' documentation: MangoHud's README and logging code, PresentMon's
// README-ConsoleApplication.md) and plain lists parse to the same frame times; each render of a
// trace is shown at the first refresh at or after it is ready; offset, loop and rescale.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "condition/frame_trace.h"
#include "condition/render_frames.h"
#include "condition/schedule.h"

namespace warplab::condition {
namespace {

const std::vector<double> kMs{16.7, 8.3, 33.4, 12.5, 16.7};

// MangoHud 0.7's log: a line of system fields, their values, then the per-frame columns.
const char* kMangoHud =
    "os,cpu,gpu,ram,kernel,driver,cpuscheduler\n"
    "Debian GNU/Linux 12,AMD Ryzen 7 5800X 8-Core Processor,AMD Radeon RX 6800,32768,6.1.0-27-amd64,Mesa 22.3.6,\n"
    "fps,frametime,cpu_load,gpu_load,cpu_temp,gpu_temp,gpu_core_clock,gpu_mem_clock,gpu_vram_used,gpu_power,"
    "ram_used,swap_used,elapsed\n"
    "59.88,16.7,31,88,61,70,2250,1000,5.1,190,9.8,0,16700000\n"
    "120.48,8.3,30,87,61,70,2250,1000,5.1,190,9.8,0,25000000\n"
    "29.94,33.4,29,86,61,70,2250,1000,5.1,190,9.8,0,58400000\n"
    "80,12.5,31,88,61,70,2250,1000,5.1,190,9.8,0,70900000\n"
    "59.88,16.7,31,88,61,70,2250,1000,5.1,190,9.8,0,87600000\n";

// PresentMon 1.x: msBetweenPresents; the swap chain's first present has none before it (0).
const char* kPresentMon1 =
    "Application,ProcessID,SwapChainAddress,Runtime,SyncInterval,PresentFlags,AllowsTearing,PresentMode,"
    "Dropped,TimeInSeconds,msInPresentAPI,msBetweenPresents,msBetweenDisplayChange,msUntilRenderComplete,"
    "msUntilDisplayed\r\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,0,1.000000,0.120,0.000,0.000,3.2,9.1\r\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,0,1.016700,0.110,16.7,16.7,3.1,9.0\r\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,0,1.025000,0.100,8.3,8.3,3.0,8.8\r\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,0,1.058400,0.130,33.4,33.4,3.3,9.4\r\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,0,1.070900,0.120,12.5,12.5,3.2,9.1\r\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,0,1.087600,0.120,16.7,16.7,3.2,9.1\r\n";

// PresentMon 2.x: the same metric as MsBetweenPresents.
const char* kPresentMon2 =
    "Application,ProcessID,SwapChainAddress,PresentRuntime,SyncInterval,PresentFlags,AllowsTearing,PresentMode,"
    "FrameType,CPUStartTime,MsBetweenSimulationStart,MsBetweenPresents,MsBetweenDisplayChange,MsInPresentAPI,"
    "MsRenderPresentLatency,MsUntilDisplayed\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,Application,1000.0,NA,16.7,16.7,0.1,3.2,9.1\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,Application,1016.7,NA,8.3,8.3,0.1,3.1,9.0\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,Application,1025.0,NA,33.4,33.4,0.1,3.0,8.8\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,Application,1058.4,NA,12.5,12.5,0.1,3.3,9.4\n"
    "game.exe,4242,0x1F2E3D4C5B6A,DXGI,1,0,0,Hardware: Independent Flip,Application,1070.9,NA,16.7,16.7,0.1,3.2,9.1\n";

// PresentMon 2.x's newer metrics: FrameTime.
const char* kPresentMonFrameTime =
    "Application,ProcessID,SwapChainAddress,PresentRuntime,SyncInterval,PresentFlags,AllowsTearing,PresentMode,"
    "FrameType,CPUStartTime,FrameTime,CPUBusy,CPUWait,GPULatency,GPUTime\n"
    "game.exe,4242,0x1F2E,DXGI,1,0,0,Hardware: Independent Flip,Application,1000.0,16.7,5,11.7,1,6\n"
    "game.exe,4242,0x1F2E,DXGI,1,0,0,Hardware: Independent Flip,Application,1016.7,8.3,5,3.3,1,6\n"
    "game.exe,4242,0x1F2E,DXGI,1,0,0,Hardware: Independent Flip,Application,1025.0,33.4,5,28.4,1,6\n"
    "game.exe,4242,0x1F2E,DXGI,1,0,0,Hardware: Independent Flip,Application,1058.4,12.5,5,7.5,1,6\n"
    "game.exe,4242,0x1F2E,DXGI,1,0,0,Hardware: Independent Flip,Application,1070.9,16.7,5,11.7,1,6\n";

// MangoHud 0.6 (Debian 12's) logs frametime in microseconds; its fps column tells them apart.
const char* kMangoHud06 =
    "os,cpu,gpu,ram,kernel,driver,cpuscheduler\n"
    "Debian GNU/Linux 12 (bookworm),AMD EPYC,,24683664,6.1.0,4.5 Mesa 22.3.6,\n"
    "fps,frametime,cpu_load,gpu_load,cpu_temp,gpu_temp,gpu_core_clock,gpu_mem_clock,gpu_vram_used,gpu_power,"
    "ram_used,elapsed\n"
    "59.88,16700,100,0,0,0,0,0,0,0,0.84,974463347\n"
    "120.48,8300,100,0,0,0,0,0,0,0,0.84,982763347\n"
    "29.94,33400,100,0,0,0,0,0,0,0,0.84,1016163347\n"
    "80,12500,100,0,0,0,0,0,0,0,0.84,1028663347\n"
    "59.88,16700,100,0,0,0,0,0,0,0,0.84,1045363347\n";

const char* kList = "# frame times, ms\n16.7\n8.3\n\n33.4\n12.5\n16.7\n";

std::vector<double> read(const std::string& text) { return parseTrace(text, detectTraceFormat(text)); }

TEST(FrameTrace, MangoHudPresentMonAndAListGiveTheSameFrameTimes) {
    EXPECT_EQ(detectTraceFormat(kMangoHud), "mangohud");
    EXPECT_EQ(detectTraceFormat(kPresentMon1), "presentmon");
    EXPECT_EQ(detectTraceFormat(kPresentMon2), "presentmon");
    EXPECT_EQ(detectTraceFormat(kPresentMonFrameTime), "presentmon");
    EXPECT_EQ(detectTraceFormat(kList), "list");
    EXPECT_EQ(read(kMangoHud), kMs);
    const std::vector<double> micro = read(kMangoHud06);
    ASSERT_EQ(micro.size(), kMs.size());
    for (std::size_t i = 0; i < kMs.size(); ++i) EXPECT_NEAR(micro[i], kMs[i], 1e-9);
    EXPECT_EQ(read(kPresentMon1), kMs);
    EXPECT_EQ(read(kPresentMon2), kMs);
    EXPECT_EQ(read(kPresentMonFrameTime), kMs);
    EXPECT_EQ(read(kList), kMs);
}

// The line at fault and what is allowed.
void expectRefused(const std::string& text, std::size_t line, const std::string& words) {
    try {
        read(text);
        ADD_FAILURE() << "accepted: " << text;
    } catch (const TraceError& e) {
        EXPECT_EQ(e.line(), line) << e.what() << " for " << text.substr(0, 60);
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what() << " for " << text.substr(0, 60);
    }
}

TEST(FrameTrace, BadTracesNameTheLineAndWhatIsAllowed) {
    expectRefused("", 0, "empty");
    expectRefused("\n\n", 0, "empty");
    expectRefused("time,value\n1,2\n", 0, "MangoHud CSV log");
    expectRefused("16.7\n0\n", 2, "above 0");
    expectRefused("16.7\n-3\n", 2, "above 0");
    expectRefused("16.7\nnan\n", 2, "not a number");
    expectRefused("16.7\n10000.5\n", 2, "at most 10000 ms");
    expectRefused("16.7\n16.7ms\n", 2, "not a number");
    expectRefused("os,cpu,gpu\nLinux,x,y\nfps,cpu_load\n60,3\n", 0, "frametime column");
    expectRefused("fps,frametime\n60,16.7\n60\n", 3, "has 1 fields where the header has 2");
    expectRefused("fps,frametime\n", 0, "no frame times");
    // A row each 100 ms (MangoHud's default log_interval) of 16.7 ms frames: not every frame.
    expectRefused("fps,frametime,elapsed\n60,16.7,0\n60,16.7,100000000\n60,16.7,200000000\n", 0,
                  "record with log_interval=0");
    expectRefused(std::string("Application,ProcessID,SwapChainAddress,msBetweenPresents\n") +
                      "a.exe,1,0x1,16.7\nb.exe,2,0x2,16.7\n",
                  3, "another swap chain");
    expectRefused("Application,ProcessID,msBetweenPresents\na.exe,1,16.7\na.exe,1,0\n", 3, "above 0");
    std::string tooLong;
    for (std::size_t i = 0; i <= kMaxTraceFrames; ++i) tooLong += "16.7\n";
    expectRefused(tooLong, kMaxTraceFrames + 1, "more than a trace may hold");
    EXPECT_THROW(parseTrace("16.7\n", "capframex"), TraceError);
}

Condition traced(const std::vector<double>& ms, double offsetS = 0.0, std::optional<double> meanHz = {}) {
    auto trace = std::make_shared<FrameTrace>();
    trace->recordedMs = ms;
    trace->offsetS = offsetS;
    trace->meanHz = meanHz;
    Condition c;
    c.name = "traced";
    c.frameTimes = trace;
    c.renderHz = trace->playedHz();
    return c;
}

// Each render is ready at the sum of the frame times before it and shown at the first refresh
// at or after that; renders ready within one refresh are superseded by the newest.
std::vector<std::int64_t> expectedFrames(const std::vector<double>& playedMs, double refreshHz, std::int64_t last) {
    std::vector<std::int64_t> frames{0};
    double t = 0.0;
    for (std::size_t i = 0;; i = (i + 1) % playedMs.size()) {
        t += playedMs[i];
        const auto frame = static_cast<std::int64_t>(std::ceil(t * refreshHz / 1000.0 - 1e-7));
        if (frame > last) return frames;
        if (frame > frames.back()) frames.push_back(frame);
    }
}

TEST(FrameTrace, EachRenderIsShownAtTheFirstRefreshAfterItIsReady) {
    // 3 ms renders come faster than 144 Hz's 6.94 ms refresh: some are never shown.
    const std::vector<double> ms{10.0, 20.0, 5.0, 30.0, 3.0, 3.0, 47.0};
    const ConditionSchedule s(traced(ms), 144.0);
    EXPECT_EQ(renderFrames(s, 1440), expectedFrames(ms, 144.0, 1440));
    EXPECT_EQ(renderFrames(s, 30), (std::vector<std::int64_t>{0, 2, 5, 6, 10, 11, 17, 19, 22, 23, 27, 28}));
    EXPECT_NEAR(traced(ms).renderHz, 1000.0 * 7 / 118.0, 1e-9);
}

TEST(FrameTrace, PlaysFromItsOffsetLoopedAndRescaledToItsMeanRate) {
    const std::vector<double> ms{10.0, 20.0, 30.0, 40.0};
    // 25 ms in is the second frame's: it plays 20, 30, 40, 10, 20 ...
    const ConditionSchedule offset(traced(ms, 0.025), 1000.0);
    EXPECT_EQ(renderFrames(offset, 130), (std::vector<std::int64_t>{0, 20, 50, 90, 100, 120}));
    // Rescaled from 40 to 20 frames a second: every frame twice as long.
    const Condition slow = traced(ms, 0.0, 20.0);
    EXPECT_DOUBLE_EQ(slow.renderHz, 20.0);
    const ConditionSchedule rescaled(slow, 1000.0);
    EXPECT_EQ(renderFrames(rescaled, 220), (std::vector<std::int64_t>{0, 20, 60, 120, 200, 220}));
    // An offset on a frame's start plays that frame first: 30 ms in plays 30, 40, 10 ...
    EXPECT_EQ(renderFrames(ConditionSchedule(traced(ms, 0.03), 1000.0), 130),
              (std::vector<std::int64_t>{0, 30, 70, 80, 100, 130}));
    // An offset past the end wraps: 125 ms is 25 ms into the 100 ms trace.
    EXPECT_EQ(renderFrames(ConditionSchedule(traced(ms, 0.125), 1000.0), 130), renderFrames(offset, 130));
}

TEST(FrameTrace, ProblemsNameTheTraceAndWhatIsAllowed) {
    Condition fast = traced({4.0, 4.0});  // 250 frames a second
    auto p = problem(fast, 144.0);
    ASSERT_TRUE(p);
    EXPECT_EQ(p->part, "frame_times");
    EXPECT_NE(p->reason.find("give frame_times.mean_hz up to 144 Hz"), std::string::npos) << p->reason;
    Condition jittered = traced({16.7});
    jittered.jitter = {JitterShape::Normal, 2.0, 0.0};
    p = problem(jittered, 144.0);
    ASSERT_TRUE(p);
    EXPECT_EQ(p->part, "frame_time_jitter");
    // A trace's longest frame bounds what a game must keep of its history.
    p = problem(traced({16.7, 9000.0}), 144.0);
    ASSERT_TRUE(p);
    EXPECT_EQ(p->part, "frame_times");
    EXPECT_FALSE(problem(traced({16.7, 1000.0}), 144.0));
}

}  // namespace
}  // namespace warplab::condition
