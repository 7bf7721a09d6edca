// A frame shown in a real SDL window (GL 4.1 core through Mesa GLX, under Xvfb in CI) equals
// the same frame rendered headlessly: the window path adds nothing but the blit. And the
// window's text input carries what was typed.
#include <string>

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

// Typing reaches WindowInput::text as the window system sends it: text events of UTF-8 and
// Backspace as its key, kept in order, each Backspace as kTypedBackspace (not applied: the
// game edits its answer); keys still arrive as keys.
TEST(Window, InjectedTextAndBackspaceArriveAsTyped) {
    renderer::ContextOptions options;
    options.width = 64;
    options.height = 36;
    options.title = "warplab text input test";
    const auto window = renderer::createWindow(options);
    window->pumpEvents();  // whatever opening the window queued
    // More than a text event holds (31 bytes), with a three-byte dash where the first one
    // fills up: all of it arrives, in order.
    const std::string before = "the spheres stuttered at first", dash = "\xE2\x80\x94";
    const std::string b(1, renderer::kTypedBackspace);
    renderer::WindowInput typed;
    typed.text = before + dash + " then smooth" + b + b + "th \xC3\xA9" + b + "ok";
    typed.keysPressed = "4\r";
    window->injectInput(typed);
    const renderer::WindowInput got = window->pollInput();
    EXPECT_EQ(got.text, typed.text);
    EXPECT_EQ(got.keysPressed, "4\r");
    EXPECT_EQ(window->pollInput().text, "") << "a poll takes the text it returns";
}

}  // namespace
}  // namespace warplab
