// The modes (game/) against the methods the renderer has: where the two meet, in present/,
// which draws every mode's frames with the method the mode names.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "condition/schedule.h"
#include "renderer/upconvert.h"

using namespace warplab::condition;
namespace renderer = warplab::renderer;

// Every mode must be drawable: the frames a mode makes between its renders use the method it
// names, and held or rendered frames are copied by hold120 (present/src/frame_maker.cpp, which
// live sessions, replay --render and the simulated participant's eye all draw with).
TEST(Modes, EveryModeNamesAMethodTheRendererHas) {
    const auto methods = renderer::methodNames();
    auto has = [&](const std::string& name) {
        return std::find(methods.begin(), methods.end(), name) != methods.end();
    };
    EXPECT_TRUE(has("hold120"));
    for (const auto& id : modeIds()) {
        const ModeSpec& mode = modeSpec(id);
        if (mode.upconversion == Upconversion::None) {
            EXPECT_TRUE(mode.method.empty()) << id << " makes no frames between renders";
            continue;
        }
        EXPECT_TRUE(has(mode.method)) << id << " names method '" << mode.method << "', which the renderer lacks";
    }
    EXPECT_EQ(modeSpec("bireproj15to60").method, "bireproj");
}
