// The conditions (condition/) against the methods the renderer has: where the two meet, in
// present/, which draws every condition's frames with the methods its parts name.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "condition/condition.h"
#include "renderer/upconvert.h"

using namespace warplab::condition;
namespace renderer = warplab::renderer;

namespace {

bool has(const std::string& name) {
    const auto methods = renderer::methodNames();
    return std::find(methods.begin(), methods.end(), name) != methods.end();
}

}  // namespace

// Every preset must be drawable: the frames it makes between its renders use the methods its
// parts name, and held or rendered frames are copied by hold120 (present/src/frame_maker.cpp,
// which live sessions, replay --render and the simulated participant's eye all draw with).
TEST(Conditions, EveryPresetNamesMethodsTheRendererHas) {
    EXPECT_TRUE(has("hold120"));
    for (const auto& c : presets()) {
        if (c.fillKind() == Fill::Hold) {
            EXPECT_TRUE(c.sourceMethod().empty()) << c.name << " makes no frames between renders";
            continue;
        }
        EXPECT_TRUE(has(c.sourceMethod())) << c.name << " names method '" << c.sourceMethod() << "'";
    }
    EXPECT_EQ(preset("bireproj15to60").interpolationMethod(), "bireproj");
    EXPECT_EQ(preset("warp15to120").warpMethod(), "warp-sparse8");
}

// A fill names a renderer method, and so does each late warp.
TEST(Conditions, EveryFillAndLateWarpIsAMethodTheRendererHas) {
    for (const auto& s : fillSpellings()) {
        if (s.fill != Fill::Hold) {
            EXPECT_TRUE(has(s.name)) << "fill " << s.name << " is no renderer method";
        }
    }
    for (const char* late : {kRotationLateWarpMethod, kDepthLateWarpMethod}) EXPECT_TRUE(has(late)) << late;
    // Every mesh warp the renderer has is a fill.
    for (const auto& name : renderer::methodNames()) {
        if (name.rfind("warp-", 0) == 0 && name != "warp-search") {
            EXPECT_TRUE(fillNamed(name).has_value()) << name << " is a warp no condition can fill with";
        }
    }
}
