// A frame shown in a real SDL window (GL 4.1 core through Mesa GLX, under Xvfb in CI) equals
// the same frame rendered headlessly: the window path adds nothing but the blit.
#include <gtest/gtest.h>

#include "gl/gl_test_support.h"
#include "renderer/window.h"

namespace warplab {
namespace {

TEST(Window, ScreenshotMatchesHeadlessRender) {
    constexpr int kW = 200, kH = 112;
    const auto shooter = testing::shooterScene(kW, kH, 1);
    scene::FrameDescription frame{shooter.restingCamera(), shooter.snapshot(1.0)};

    image::ImageRGBA8 headless;
    {
        auto context = renderer::createContext({renderer::GlBackend::OSMesa});
        renderer::ConventionalRenderer conventional(testing::sourceDataPaths());
        renderer::GBuffer gbuffer(kW, kH);
        conventional.render(frame, gbuffer);
        headless = renderer::readBack(gbuffer).colour;
    }

    renderer::ContextOptions options;
    options.width = kW;
    options.height = kH;
    options.title = "warplab window test";
    const auto window = renderer::createWindow(options);
    ASSERT_EQ(window->drawableWidth(), kW);
    ASSERT_EQ(window->drawableHeight(), kH);
    renderer::ConventionalRenderer conventional(testing::sourceDataPaths());
    renderer::GBuffer gbuffer(kW, kH);
    conventional.render(frame, gbuffer);
    renderer::blitToDefaultFramebuffer(gbuffer, kW, kH);
    const image::ImageRGBA8 screenshot = renderer::readDefaultFramebuffer(kW, kH);
    window->swapBuffers();
    window->pumpEvents();
    EXPECT_TRUE(testing::imagesMatch(headless, screenshot, "window_vs_headless"));
    EXPECT_NE(window->info().backend.find("window"), std::string::npos);
}

}  // namespace
}  // namespace warplab
