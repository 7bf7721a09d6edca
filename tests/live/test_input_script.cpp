// Input scripts without a window: what each line queues, and a bad line named by its number.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
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

}  // namespace
}  // namespace warplab::live
