// A fill slower than the display shows each of its frames again until the next: on a 120 Hz
// display bireproj15to60 makes a frame every second refresh. The frame log calls the repeat
// held, I-frame and B-frame alike (docs/session-format.md, `kind`), and replay --render draws it
// as the frame it repeats -- a B-frame interpolated again, not the I-frame it is made from.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cli/cli_support.h"
#include "image/image.h"
#include "session/session_store.h"

namespace {

namespace fs = std::filesystem;

using warplab::testing::sessionIn;
using warplab::testing::warplab;

std::string framePng(const std::string& dir, std::int64_t frame) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%07lld.png", static_cast<long long>(frame));
    return dir + name;
}

TEST(RepeatedFrames, ARepeatedBFrameIsHeldAndDrawnAsTheBFrame) {
    const std::string dir = warplab::testing::scratch("repeated-frames", "bireproj-120");
    // Acclimation in bireproj15to60 at 120 Hz from the first frame: the bot turns and the target
    // moves, so an I-frame and the B-frames after it differ.
    std::ofstream(dir + "/p.json") << R"({"format_version":2,"name":"bireproj-120","game":"shooter",
 "acclimation":{"duration_s":1.0,"level":6,"mode":"bireproj15to60"},
 "training":{"start_level":12,"shots_per_level_easy":1,"shots_per_level_hard":1,"time_limit_s":0.5},
 "test":{"conditions":["bireproj15to60"],"targets_per_condition":1,"timeout_s":0.5,"pause_s":0.25,
         "supervisor_starts":false}})";
    fs::create_directories(dir + "/results");
    const auto run = warplab("run --protocol " + dir + "/p.json --participant R --out " + dir +
                             "/results --headless --player bot:2 --seed 4 --width 160 --height 90");
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string session = sessionIn(dir + "/results");
    const warplab::session::SessionData data = warplab::session::readSession(session);

    // A B-frame shown anew, then held: the held repeat must be that B-frame again.
    std::int64_t bFrame = -1, iFrame = -1;
    for (std::size_t i = 1; i + 1 < data.frames.size() && bFrame < 0; ++i) {
        const auto& f = data.frames[i];
        if (f.frame < 16 || f.condition != "bireproj15to60") continue;
        if (f.kind == "rendered") iFrame = f.frame;
        if (iFrame >= 0 && f.kind == "interpolated" && data.frames[i + 1].kind == "held") bFrame = f.frame;
    }
    ASSERT_GE(bFrame, 0) << "no B-frame logged held when shown again";
    EXPECT_LT(iFrame, bFrame);
    for (std::size_t i = 1; i < data.frames.size(); ++i)
        EXPECT_FALSE(data.frames[i].kind == "interpolated" && data.frames[i - 1].kind == "interpolated")
            << "frame " << data.frames[i].frame << ": a B-frame made twice in a row at 60 Hz";

    const std::string frames = dir + "/frames";
    const std::string range = std::to_string(iFrame) + ":" + std::to_string(bFrame + 1);
    const auto render = warplab("replay " + session + " --render " + frames + " --frames " + range);
    ASSERT_EQ(render.status, 0) << render.output;
    const auto shown = warplab::image::readPng(framePng(frames, bFrame));
    const auto repeat = warplab::image::readPng(framePng(frames, bFrame + 1));
    const auto iImage = warplab::image::readPng(framePng(frames, iFrame));
    EXPECT_TRUE(repeat.pixels == shown.pixels) << "the held repeat is not the B-frame it repeats";
    EXPECT_FALSE(repeat.pixels == iImage.pixels) << "the held repeat shows the I-frame";
}

}  // namespace
