// Input scripts without a window: what each line queues, and a bad line named by its number.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "input_script.h"

namespace warplab::live {
namespace {

// Keeps what the script injects instead of queueing it for a window.
class Recorder final : public renderer::Window {
public:
    std::vector<renderer::WindowInput> injected;
    void injectInput(const renderer::WindowInput& input) override { injected.push_back(input); }
    void swapBuffers() override {}
    bool pumpEvents() override { return true; }
    renderer::WindowInput pollInput() override { return {}; }
    void setRelativeMouse(bool) override {}
    double refreshHz() const override { return 0.0; }
    bool vsyncOn() const override { return false; }
    int drawableWidth() const override { return 0; }
    int drawableHeight() const override { return 0; }
};

std::string scriptPath(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("warplab-input-script-" + name + ".txt")).string();
}

std::string scriptFile(const std::string& name, const std::string& text) {
    std::ofstream(scriptPath(name)) << text;
    return scriptPath(name);
}

// What the script injects at `when`; nothing when it names no input there.
renderer::WindowInput at(const InputScript& script, const std::string& when) {
    Recorder window;
    script.inject(window, when);
    return window.injected.empty() ? renderer::WindowInput{} : window.injected.front();
}

std::string errorOf(const std::string& name, const std::string& text) {
    try {
        InputScript(scriptFile(name, text));
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "no error";
}

TEST(InputScript, TypeTypesTheRestOfTheLineWithItsSpaces) {
    const InputScript script(scriptFile("type",
                                        "12 type  smooth, but laggy \xE2\x80\x94 ok \n"
                                        "12 key enter\n"
                                        "# a comment is a line's first word only\n"
                                        "13 type #1 \\\\ not a comment\n"));
    const renderer::WindowInput typed = at(script, "12");
    EXPECT_EQ(typed.text, " smooth, but laggy \xE2\x80\x94 ok ");
    EXPECT_EQ(typed.keysPressed, "\r") << "text is typed as text only, Enter as a key";
    EXPECT_EQ(at(script, "13").text, "#1 \\ not a comment");
}

TEST(InputScript, BackslashBIsBackspaceAndTypeLinesAddUp) {
    const InputScript script(scriptFile("backspace", "start type lagy\\b\\b\r\nstart type ggy\n"));
    EXPECT_EQ(at(script, "start").text,
              std::string("lagy") + renderer::kTypedBackspace + renderer::kTypedBackspace + "ggy");
}

TEST(InputScript, ABadTypeIsNamedWithItsLine) {
    EXPECT_EQ(errorOf("bad-escape", "start key enter\n4 type fine\\x\n"),
              "input script '" + scriptPath("bad-escape") +
                  "' line 2: unknown escape '\\x' in type (\\b for Backspace, \\\\ for a backslash)");
    EXPECT_NE(errorOf("trailing", "7 type ok\\").find("line 1: unknown escape '\\'"), std::string::npos);
    EXPECT_NE(errorOf("empty", "1 key enter\n\n3 type\n").find("line 3: type needs the text to type"),
              std::string::npos);
    EXPECT_NE(errorOf("space-only", "3 type \n").find("line 1: type needs the text to type"), std::string::npos);
    EXPECT_NE(errorOf("unknown", "3 write hello\n").find("line 1: unknown action 'write' (key, move, click or type)"),
              std::string::npos);
}

// Numbers are read whole and checked: a frame no session reaches, or mouse counts no hand
// makes, would otherwise be taken without a word and never, or wildly, happen.
TEST(InputScript, AFrameOrACountOutOfRangeIsNamedWithItsLine) {
    EXPECT_EQ(errorOf("frame-2-64", "start key enter\n18446744073709551616 click\n"),
              "input script '" + scriptPath("frame-2-64") +
                  "' line 2: frame 18446744073709551616 is beyond the last frame a session can show "
                  "(9223372036854775807)");
    EXPECT_NE(errorOf("frame-2-63", "9223372036854775808 click\n").find("line 1: frame 9223372036854775808 is beyond"),
              std::string::npos);
    EXPECT_EQ(errorOf("frame-last", "9223372036854775807 click\n"), "no error");
    EXPECT_NE(errorOf("huge-move", "1 key enter\n2 move 1e300 5\n")
                  .find("line 2: move needs DX DY, mouse counts between -100000 and 100000, got '1e300' '5'"),
              std::string::npos);
    EXPECT_NE(errorOf("half-move", "2 move 40\n").find("line 1: move needs DX DY"), std::string::npos);
    EXPECT_NE(errorOf("unit-move", "2 move 40px 0\n").find("line 1: move needs DX DY"), std::string::npos);
    EXPECT_NE(errorOf("extra-word", "12 click twice\n").find("line 1: 'twice' after click: one action a line"),
              std::string::npos);
    EXPECT_NE(errorOf("extra-count", "12 move 1 2 3\n").find("line 1: '3' after move: one action a line"),
              std::string::npos);
}

// A frame is named as the display clock names it, whatever zeros lead it.
TEST(InputScript, AFrameNumberIsANumberNotAString) {
    const InputScript script(scriptFile("zeros", "007 click\n0012 move -3.5 2\n"));
    EXPECT_TRUE(at(script, "7").leftHeld);
    EXPECT_EQ(at(script, "12").mouseDx, -3.5);
    EXPECT_EQ(at(script, "12").mouseDy, 2);
}

// A script that is no regular file is refused at once: a FIFO would block the window for ever
// and /dev/zero fill memory. The read runs on a thread of its own, so that a reader that
// blocks fails the test after a few seconds instead of hanging it (the thread is left behind).
std::string errorWithin(const std::string& path) {
    auto done = std::make_shared<std::promise<std::string>>();
    std::future<std::string> answer = done->get_future();
    std::thread([done, path] {
        try {
            InputScript{path};
            done->set_value("no error");
        } catch (const std::runtime_error& e) {
            done->set_value(e.what());
        }
    }).detach();
    if (answer.wait_for(std::chrono::seconds(5)) != std::future_status::ready) return "(still reading after 5 s)";
    return answer.get();
}

TEST(InputScript, AScriptThatIsNoRegularFileIsRefusedAtOnce) {
    const std::string fifo = scriptPath("fifo");
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_EQ(errorWithin(fifo), "input script '" + fifo + "': is a FIFO (a named pipe), not a regular file");
    EXPECT_EQ(errorWithin("/dev/zero"), "input script '/dev/zero': is a device, not a regular file");
    EXPECT_EQ(errorWithin(scriptPath("none")), "input script '" + scriptPath("none") + "': no such file");
    EXPECT_EQ(errorWithin(scriptFile("nul", std::string("1 click\n2 cl\0ick\n", 17))),
              "input script '" + scriptPath("nul") + "' line 2: has a NUL byte: a script is text");
}

}  // namespace
}  // namespace warplab::live
