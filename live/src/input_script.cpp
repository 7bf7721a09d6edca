#include "input_script.h"

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace warplab::live {
namespace {

// The text of a `type` action: as written, but \b is Backspace and \\ a backslash (a script
// is plain text, and Backspace has no character of its own). Empty when an escape is
// unknown (*bad names it).
std::string typedText(const std::string& written, std::string* bad) {
    std::string text;
    for (std::size_t i = 0; i < written.size(); ++i) {
        if (written[i] != '\\') {
            text += written[i];
        } else if (i + 1 < written.size() && written[i + 1] == 'b') {
            text += renderer::kTypedBackspace;
            ++i;
        } else if (i + 1 < written.size() && written[i + 1] == '\\') {
            text += '\\';
            ++i;
        } else {
            *bad = "unknown escape '" + written.substr(i, 2) + "' in type (\\b for Backspace, \\\\ for a backslash)";
            return {};
        }
    }
    return text;
}

}  // namespace

InputScript::InputScript(const std::string& path) {
    std::ifstream file(path);
    if (!file) throw std::runtime_error("cannot read input script '" + path + "'");
    std::string line;
    for (int number = 1; std::getline(file, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();  // written on Windows
        std::istringstream words(line);
        std::string when, action;
        if (!(words >> when) || when[0] == '#') continue;
        auto bad = [&](const std::string& why) {
            return std::runtime_error("input script '" + path + "' line " + std::to_string(number) + ": " + why);
        };
        if (!(words >> action)) throw bad("no action after '" + when + "'");
        if (when != "start" && when != "end" && when.find_first_not_of("0123456789") != std::string::npos)
            throw bad("'" + when + "' is not a frame number, start or end");
        renderer::WindowInput& in = at_[when];
        if (action == "click") {
            in.leftHeld = true;
        } else if (action == "move") {
            if (!(words >> in.mouseDx >> in.mouseDy)) throw bad("move needs DX DY");
        } else if (action == "key") {
            std::string key;
            words >> key;
            if (key == "enter")
                in.keysPressed += '\r';
            else if (key == "esc")
                in.keysPressed += '\x1b';
            else if (key == "pageup" || key == "[")
                in.keysPressed += '[';
            else if (key == "pagedown" || key == "]")
                in.keysPressed += ']';
            else if (key.size() == 1 && std::isalnum(static_cast<unsigned char>(key[0])))
                in.keysPressed += static_cast<char>(std::tolower(static_cast<unsigned char>(key[0])));
            else
                throw bad("unknown key '" + key + "' (enter, esc, pageup, pagedown, [, ], a letter or a digit)");
        } else if (action == "type") {
            // The rest of the line after one space, its spaces included: "type  a" types " a".
            const std::streamoff after = words.tellg();
            std::string written = after < 0 ? std::string() : line.substr(static_cast<std::size_t>(after));
            if (!written.empty()) written.erase(0, 1);
            if (written.empty()) throw bad("type needs the text to type");
            std::string why;
            const std::string text = typedText(written, &why);
            if (!why.empty()) throw bad(why);
            in.text += text;
        } else {
            throw bad("unknown action '" + action + "' (key, move, click or type)");
        }
    }
}

void InputScript::inject(renderer::Window& window, const std::string& when) const {
    const auto it = at_.find(when);
    if (it != at_.end()) window.injectInput(it->second);
}

}  // namespace warplab::live
