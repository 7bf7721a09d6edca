// The frame maker draws a source when a frame made needs it, not when the game steps the frame
// that renders it: a live session that skips display frames it cannot show then skips their
// renders too (window_loop.cpp), and the frames it does show are the pictures they would have
// been had every frame been made.
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "game/registry.h"
#include "gl/gl_test_support.h"
#include "present/frame_maker.h"

namespace warplab {
namespace {

constexpr int kWidth = 96, kHeight = 54;
const game::DisplaySize kDisplay{kWidth, kHeight};

std::unique_ptr<game::Study> studyFrom(const std::string& name) {
    const std::string path = std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + name + ".json";
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return game::parseStudy(text, path);
}

struct Made {
    int frames = 0;  // frames made
    std::int64_t renders = 0;  // conventional renders drawn for them
    std::int64_t stepped = 0;  // frames the game stepped
    std::int64_t rendersStepped = 0;  // ... that rendered a source
};

// Steps `mode` for `frames` display frames, the camera turning, every frame kept; makes every
// `every`-th one (as a session that shows one frame in `every`), its picture added to `pictures`.
Made play(const game::Study& study, const std::string& condition, int frames, int every,
          std::vector<image::ImageRGBA8>& pictures) {
    testing::glContext();
    auto game = study.newFreePlay(3, kDisplay, condition, 6);
    present::FrameMaker maker(testing::sourceDataPaths(), kWidth, kHeight, study.rendering());
    renderer::DisplayFrame display(kWidth, kHeight);
    Made made;
    for (int i = 0; i < frames; ++i) {
        const game::ShownFrame shown = game->step({3.0, 0.5, 0u, 0u, ""});
        game->takeEvents();
        maker.keepSource(shown);
        ++made.stepped;
        made.rendersStepped += shown.rendersNow;
        if (i % every != every - 1 || shown.blank) continue;
        maker.make(shown, display);
        ++made.frames;
        pictures.push_back(renderer::readBack(display, false).colour);
    }
    made.renders = maker.rendersDrawn();
    return made;
}

// At 120 Hz, conv15 renders every 8th display frame. A session showing one frame in 19 (a
// machine at about 6 frames a second) needs one render per frame shown; before, it drew all
// of them, every one of which cost as much as the frame it was meant to make room for.
TEST(FrameMaker, SkippedFramesDrawNoRenderNoShownFrameNeeds) {
    const auto shooter = studyFrom("shooter-quick");
    for (const std::string condition : {"conv15", "conv120", "warp15to120"}) {
        std::vector<image::ImageRGBA8> pictures;
        const Made all = play(*shooter, condition, 240, 1, pictures);
        const Made some = play(*shooter, condition, 240, 19, pictures);
        EXPECT_EQ(all.renders, all.rendersStepped) << condition << ": each render made once when every frame is shown";
        EXPECT_GT(some.rendersStepped, some.frames) << condition << ": the case must step more renders than it shows";
        EXPECT_LE(some.renders, some.frames) << condition << ": " << some.renders << " renders drawn for "
                                             << some.frames << " frames shown of " << some.stepped;
        EXPECT_GE(some.renders, 1);
    }
}

// A source drawn late is the picture it was: the world as the schedule sampled it. Made one
// frame in 7, every frame equals the same frame made in a run that made all of them (holds,
// warps, and bidirectional reprojection, whose in-between frames need the next render and
// whose renders carry their flow towards the one before). Bidirectional reprojection's
// latest-frame initialisation starts a B-frame's search from the B-frame made before it in
// the same interval (seed 000 eq. 18-19), so a B-frame is compared only where none was.
TEST(FrameMaker, AFrameMadeFromALateRenderIsTheFrameOfAnEagerOne) {
    const auto shooter = studyFrom("shooter-quick");
    const auto click = studyFrom("click-quick");
    struct Case {
        const game::Study* study;
        std::string condition;
    };
    for (const Case& c : {Case{shooter.get(), "conv15"}, Case{shooter.get(), "warp15to120"},
                          Case{click.get(), "bireproj15to60"}, Case{click.get(), "lag100"}}) {
        std::vector<image::ImageRGBA8> pictures;
        const Made skipping = play(*c.study, c.condition, 120, 7, pictures);
        ASSERT_GT(skipping.frames, 10) << c.condition;
        // The same frames from a maker that made every frame: compared at the 7th ones.
        auto game = c.study->newFreePlay(3, kDisplay, c.condition, 6);
        present::FrameMaker maker(testing::sourceDataPaths(), kWidth, kHeight, c.study->rendering());
        renderer::DisplayFrame display(kWidth, kHeight);
        std::size_t next = 0, compared = 0;
        std::int64_t lastInterval = -1;  // the previous source of the last B-frame made
        for (int i = 0; i < 120; ++i) {
            const game::ShownFrame shown = game->step({3.0, 0.5, 0u, 0u, ""});
            game->takeEvents();
            maker.keepSource(shown);
            if (shown.blank) continue;
            maker.make(shown, display);
            const bool interpolated = shown.schedule.made == condition::FrameKind::Interpolated;
            const bool afterAnother = interpolated && lastInterval == shown.sourceFrame;
            lastInterval = interpolated ? shown.sourceFrame : -1;
            if (i % 7 != 6) continue;
            if (!afterAnother) {
                EXPECT_EQ(renderer::readBack(display, false).colour.pixels, pictures.at(next).pixels)
                    << c.condition << ": frame " << shown.frame;
                ++compared;
            }
            ++next;
        }
        EXPECT_EQ(next, pictures.size()) << c.condition;
        EXPECT_GE(compared, pictures.size() / 3) << c.condition;
    }
}

}  // namespace
}  // namespace warplab
