// The HUD draws over colour only: the reticle at the centre, the banner in its colour, and the
// object ids untouched (the reticle's id cross-check reads them).
#include <gtest/gtest.h>

#include "gl/gl_test_support.h"
#include "renderer/hud.h"
#include "renderer/mesh.h"

namespace warplab {
namespace {

constexpr int kW = 320;
constexpr int kH = 180;

TEST(Hud, ReticleAndBannerOverColourIdsUntouched) {
    const auto shooter = testing::shooterScene(kW, kH, 2);
    scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(0.5)};
    auto source = testing::renderSource(frame, kW, kH);
    renderer::HudRenderer hud(testing::sourceDataPaths());
    renderer::HudContent content;
    content.banner = "HIT";
    content.bannerGood = true;
    content.status = "Training: level 3";
    hud.draw(content, source.frame->gbuffer);
    const auto after = renderer::readBack(source.frame->gbuffer);

    EXPECT_EQ(after.ids.data, source.images.ids.data);
    const std::uint8_t* centre = after.colour.at(kW / 2, kH / 2);
    EXPECT_GT(centre[0], 200);  // the reticle's light cross
    EXPECT_GT(centre[1], 200);
    int green = 0;
    for (int y = 0; y < kH / 2; ++y)
        for (int x = 0; x < kW; ++x) {
            const std::uint8_t* p = after.colour.at(x, y);
            green += p[1] > 180 && p[0] < 120 && p[2] < 120;
        }
    EXPECT_GT(green, 50) << "no green HIT banner in the upper half";
    int changed = 0;
    for (std::size_t i = 0; i < after.colour.pixels.size(); ++i)
        changed += after.colour.pixels[i] != source.images.colour.pixels[i];
    EXPECT_LT(changed, static_cast<int>(after.colour.pixels.size() / 10)) << "the HUD should cover little of the frame";
}

TEST(Hud, MissingFontIsNamed) {
    testing::glContext();
    try {
        renderer::HudRenderer hud(testing::sourceDataPaths(), "/nowhere/font.ttf");
        FAIL() << "no error";
    } catch (const renderer::AssetError& e) {
        EXPECT_NE(std::string(e.what()).find("/nowhere/font.ttf"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace warplab
