// The HUD draws over colour only: the reticle at the centre or the cursor where it is, the
// banner in its colour, the rating screen, and the object ids untouched (the pointer's id
// cross-check reads them).
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "gl/gl_test_support.h"
#include "renderer/hud.h"
#include "renderer/mesh.h"

namespace warplab {
namespace {

constexpr int kW = 320;
constexpr int kH = 180;

// The frame every HUD test draws over: the hallway with the target, rendered.
testing::RenderedSource hallwayWithTarget() {
    const auto shooter = testing::shooterScene(kW, kH, 2);
    return testing::renderSource({shooter.restingCamera(), shooter.snapshot(0.5)}, kW, kH);
}

TEST(Hud, ReticleAndBannerOverColourIdsUntouched) {
    auto source = hallwayWithTarget();
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

// The click game's cursor lands on the pixel it names (y down, like the images), not at the
// centre; the ids under it stay the scene's.
TEST(Hud, CursorIsDrawnWhereItIs) {
    auto source = hallwayWithTarget();
    renderer::HudRenderer hud(testing::sourceDataPaths());
    renderer::HudContent content;
    content.reticle = false;
    content.cursor = glm::vec2(60.5f, 40.5f);
    hud.draw(content, source.frame->gbuffer);
    const auto after = renderer::readBack(source.frame->gbuffer);
    EXPECT_EQ(after.ids.data, source.images.ids.data);
    const std::uint8_t* at = after.colour.at(60, 40);
    EXPECT_GT(at[0], 200);
    EXPECT_GT(at[1], 200);
    EXPECT_GT(at[2], 200);
    // Nothing at the centre (no reticle) or at the mirrored row (y is not flipped).
    EXPECT_EQ(std::vector<std::uint8_t>(after.colour.at(kW / 2, kH / 2), after.colour.at(kW / 2, kH / 2) + 4),
              std::vector<std::uint8_t>(source.images.colour.at(kW / 2, kH / 2),
                                        source.images.colour.at(kW / 2, kH / 2) + 4));
    const std::uint8_t* mirrored = after.colour.at(60, kH - 1 - 40);
    const std::uint8_t* before = source.images.colour.at(60, kH - 1 - 40);
    EXPECT_TRUE(mirrored[0] == before[0] && mirrored[1] == before[1] && mirrored[2] == before[2]);
}

// A rating screen: a dark backdrop over everything, the highlighted box in blue, the others
// in slate, each where the game put it.
TEST(Hud, RatingScreenDrawsTheBoxesWhereTheGamePutThem) {
    auto source = hallwayWithTarget();
    renderer::HudRenderer hud(testing::sourceDataPaths());
    renderer::HudContent content;
    content.backdrop = true;
    content.reticle = false;
    renderer::HudQuestion rating;
    rating.prompt = "The animation was smooth";
    for (int i = 0; i < 7; ++i) rating.boxes.emplace_back(40.0f + i * 36.0f, 100.0f, 24.0f, 24.0f);
    rating.highlighted = 2;
    rating.minLabel = "strongly disagree";
    rating.maxLabel = "strongly agree";
    content.question = rating;
    hud.draw(content, source.frame->gbuffer);
    const auto after = renderer::readBack(source.frame->gbuffer);
    auto blueish = [&](int x, int y) {
        const std::uint8_t* p = after.colour.at(x, y);
        return p[2] > 180 && p[0] < 120;
    };
    // Inside box 2 near its corner (clear of the digit): lit; inside box 3: not.
    EXPECT_TRUE(blueish(40 + 2 * 36 + 3, 100 + 3));
    EXPECT_FALSE(blueish(40 + 3 * 36 + 3, 100 + 3));
    // The backdrop covers the scene: a corner far from the boxes is the backdrop's colour.
    const std::uint8_t* corner = after.colour.at(2, 170);
    EXPECT_LT(std::abs(corner[0] - 31), 3);
    EXPECT_LT(std::abs(corner[2] - 41), 3);
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
