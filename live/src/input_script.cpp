#include "input_script.h"

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace warplab::live {

InputScript::InputScript(const std::string& path) {
    std::ifstream file(path);
    if (!file) throw std::runtime_error("cannot read input script '" + path + "'");
    std::string line;
    for (int number = 1; std::getline(file, line); ++number) {
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
        } else {
            throw bad("unknown action '" + action + "' (key, move or click)");
        }
    }
}

void InputScript::inject(renderer::Window& window, const std::string& when) const {
    const auto it = at_.find(when);
    if (it != at_.end()) window.injectInput(it->second);
}

}  // namespace warplab::live
