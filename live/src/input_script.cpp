#include "input_script.h"

#include <cctype>
#include <cstdint>
#include <limits>
#include <sstream>

#include "strict/file.h"
#include "strict/number.h"

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

// The key a script names, added to `keys` as the window reports it; false for no such key.
bool addKey(const std::string& key, std::string& keys) {
    if (key == "enter")
        keys += '\r';
    else if (key == "esc")
        keys += '\x1b';
    else if (key == "pageup" || key == "[")
        keys += '[';
    else if (key == "pagedown" || key == "]")
        keys += ']';
    else if (key.size() == 1 && std::isalnum(static_cast<unsigned char>(key[0])))
        keys += static_cast<char>(std::tolower(static_cast<unsigned char>(key[0])));
    else
        return false;
    return true;
}

// A script holds a line per action; a frame each for an hour at 1000 Hz is some 60 MB.
constexpr std::size_t kMaxScriptBytes = 64u << 20;
// The display clock counts frames in an int64 (window_loop.cpp); a frame beyond it never comes.
constexpr std::uint64_t kLastFrame = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
// Mouse counts in one frame: a 16000 dpi mouse swept 6 inches within one frame is 100000; more
// is a slip of the keyboard.
constexpr double kMaxCounts = 100000;

}  // namespace

InputScript::InputScript(const std::string& path) {
    const strict::Source source{"input script", path, kMaxScriptBytes, nullptr};
    const std::string text = strict::readFile(source);
    std::istringstream lines(text);
    std::string line;
    for (std::size_t number = 1; std::getline(lines, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();  // written on Windows
        auto bad = [&](const std::string& why) { source.failAtLine(number, why); };
        if (line.find('\0') != std::string::npos) bad("has a NUL byte: a script is text");
        std::istringstream words(line);
        std::string when, action;
        if (!(words >> when) || when[0] == '#') continue;
        if (!(words >> action)) bad("no action after '" + when + "'");
        if (when != "start" && when != "end") {
            if (when.find_first_not_of("0123456789") != std::string::npos)
                bad("'" + when + "' is not a frame number, start or end");
            const auto frame = strict::wholeNumber(when, kLastFrame);
            if (!frame)
                bad("frame " + when + " is beyond the last frame a session can show (" + std::to_string(kLastFrame) +
                    ")");
            when = std::to_string(*frame);  // as the loop names it: 007 is frame 7
        }
        renderer::WindowInput& in = at_[when];
        if (action == "type") {
            // The rest of the line after one space, its spaces included: "type  a" types " a".
            const std::streamoff after = words.tellg();
            std::string written = after < 0 ? std::string() : line.substr(static_cast<std::size_t>(after));
            if (!written.empty()) written.erase(0, 1);
            if (written.empty()) bad("type needs the text to type");
            std::string why;
            const std::string typed = typedText(written, &why);
            if (!why.empty()) bad(why);
            in.text += typed;
            continue;
        }
        if (action == "click") {
            in.leftHeld = true;
        } else if (action == "move") {
            std::string dx, dy;
            words >> dx >> dy;
            const strict::NumberRange counts{-kMaxCounts, false, kMaxCounts, false};
            const auto x = strict::decimalNumber(dx, counts), y = strict::decimalNumber(dy, counts);
            if (!x || !y) bad("move needs DX DY, mouse counts " + counts.text() + ", got '" + dx + "' '" + dy + "'");
            in.mouseDx = *x;
            in.mouseDy = *y;
        } else if (action == "key") {
            std::string key;
            words >> key;
            if (!addKey(key, in.keysPressed))
                bad("unknown key '" + key + "' (enter, esc, pageup, pagedown, [, ], a letter or a digit)");
        } else {
            bad("unknown action '" + action + "' (key, move, click or type)");
        }
        if (std::string extra; words >> extra) bad("'" + extra + "' after " + action + ": one action a line");
    }
}

void InputScript::inject(renderer::Window& window, const std::string& when) const {
    const auto it = at_.find(when);
    if (it != at_.end()) window.injectInput(it->second);
}

}  // namespace warplab::live
