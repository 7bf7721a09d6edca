// A study's fallback where the GL context cannot run a condition's method (present/'s
// FrameMaker::method, renderer::methodUnavailable / methodFallback): warp-splat needs OpenGL 4.3,
// so on macOS's 4.1 a warp15to120-splat session shows warp-sparse8 and says so. llvmpipe has
// 4.5; WARPLAB_GL_VERSION=4.1 caps what the methods see, so the path runs here.
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "condition/condition.h"
#include "game/registry.h"
#include "gl/gl_test_support.h"
#include "present/frame_maker.h"

namespace warplab {
namespace {

constexpr int kWidth = 160, kHeight = 90;

// Sets an environment variable for its lifetime, then puts back what was there.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* was = std::getenv(name)) was_ = was;
        ::setenv(name, value, 1);
    }
    ~ScopedEnv() {
        if (was_)
            ::setenv(name_, was_->c_str(), 1);
        else
            ::unsetenv(name_);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* name_;
    std::optional<std::string> was_;
};

// warp15to120 with its fill made by warp-splat (docs/protocol.md's example), in free play: the
// camera turns every frame, so the warped frames differ from their sources.
std::vector<game::ShownFrame> splatFrames(const game::Study& study) {
    auto play = study.newFreePlay(3, {kWidth, kHeight}, "warp15to120-splat", 0);
    std::vector<game::ShownFrame> frames;
    for (int k = 0; k < 24; ++k) frames.push_back(play->step({k % 12 < 6 ? 6.0 : -4.0, 1.0, 0, 0}));
    return frames;
}

struct Made {
    std::vector<image::ImageRGBA8> warped;  // the warped frames' colour, in order
    std::vector<std::string> notes;
};

Made make(const game::Study& study, const std::vector<game::ShownFrame>& frames) {
    present::FrameMaker maker(testing::sourceDataPaths(), kWidth, kHeight, study.rendering());
    renderer::DisplayFrame display(kWidth, kHeight);
    Made made;
    for (const game::ShownFrame& shown : frames) {
        maker.keepSource(shown);
        if (shown.schedule.kind != condition::FrameKind::Warped) continue;
        maker.make(shown, display);
        made.warped.push_back(renderer::readBack(display, false).colour);
    }
    made.notes = maker.takeNotes();
    return made;
}

TEST(MethodFallback, WarpSplatBelowOpenGl43IsMadeByWarpSparse8AndSaysSo) {
    testing::glContext();
    const auto study = game::parseStudy(R"({"format_version": 3, "name": "splat", "game": "shooter",
        "conditions": {"warp15to120-splat": {"render_hz": 15, "fill": "warp-splat", "fill_hz": 120}},
        "acclimation": {"duration_s": 1.0, "level": 0, "mode": "warp15to120-splat"}})",
                                        "splat.json");
    const std::vector<game::ShownFrame> frames = splatFrames(*study);
    ASSERT_EQ(frames.front().condition.warpMethod(), "warp-splat");
    ASSERT_EQ(renderer::methodUnavailable("warp-splat"), "") << "this test wants a context that runs warp-splat";

    Made capped;
    {
        const ScopedEnv cap("WARPLAB_GL_VERSION", "4.1");
        EXPECT_NE(renderer::methodUnavailable("warp-splat"), "");
        capped = make(*study, frames);
    }
    ASSERT_EQ(capped.notes.size(), 1u);  // once per method, not per frame
    EXPECT_EQ(capped.notes.front().rfind("warp-splat needs OpenGL 4.3 compute shaders; this context is OpenGL 4.1 "
                                         "(capped by WARPLAB_GL_VERSION; the driver's is ",
                                         0),
              0u)
        << capped.notes.front();
    EXPECT_NE(capped.notes.front().find("; its frames are made with warp-sparse8 instead"), std::string::npos)
        << capped.notes.front();

    // The same frames told to use warp-sparse8, on the uncapped context: the pictures, bit for bit.
    std::vector<game::ShownFrame> sparse = frames;
    for (game::ShownFrame& shown : sparse) shown.condition = condition::preset("warp15to120");
    ASSERT_EQ(sparse.front().condition.warpMethod(), "warp-sparse8");
    const Made reference = make(*study, sparse);
    EXPECT_TRUE(reference.notes.empty());
    ASSERT_EQ(capped.warped.size(), reference.warped.size());
    ASSERT_GE(capped.warped.size(), 10u);
    for (std::size_t i = 0; i < capped.warped.size(); ++i)
        EXPECT_EQ(capped.warped[i].pixels, reference.warped[i].pixels) << "warped frame " << i;

    // And warp-splat's own frames are not those, so the comparison above tells the two apart.
    const Made splat = make(*study, frames);
    EXPECT_TRUE(splat.notes.empty());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < splat.warped.size(); ++i)
        differ += splat.warped[i].pixels != reference.warped[i].pixels;
    EXPECT_GT(differ, 0u);
}

TEST(MethodFallback, AVersionCapThatIsNoVersionIsNamed) {
    testing::glContext();
    const ScopedEnv cap("WARPLAB_GL_VERSION", "four");
    try {
        renderer::methodUnavailable("warp-splat");
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "WARPLAB_GL_VERSION='four' is not an OpenGL version such as 4.1");
    }
}

}  // namespace
}  // namespace warplab
