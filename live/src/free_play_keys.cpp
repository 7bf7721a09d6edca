#include "free_play_keys.h"

#include <algorithm>

namespace warplab::live {
namespace {

// The first mode after (step +1) or before (-1) `current` that runs; `current` when none
// other does. A mode not in the list steps from before its start.
std::string stepMode(const std::string& current, int step, const std::vector<std::string>& modes,
                     const std::function<bool(const std::string&)>& runs) {
    const long count = static_cast<long>(modes.size());
    const long at = std::find(modes.begin(), modes.end(), current) - modes.begin();
    long i = at < count ? at : (step > 0 ? -1 : count);
    for (long tried = 0; tried < count; ++tried) {
        i = ((i + step) % count + count) % count;
        if (modes[i] == current) break;
        if (runs(modes[i])) return modes[i];
    }
    return current;
}

}  // namespace

FreePlayChoice applyFreePlayKeys(FreePlayChoice choice, const std::string& keys, const std::vector<std::string>& modes,
                                 const std::function<bool(const std::string&)>& runs) {
    for (const char c : keys) {
        if (c >= '1' && c <= '9' && static_cast<std::size_t>(c - '1') < modes.size()) choice.mode = modes[c - '1'];
        if ((c == ']' || c == '[') && !modes.empty())
            choice.mode = stepMode(choice.mode, c == ']' ? 1 : -1, modes, runs);
        if (c == 'u') ++choice.level;
        if (c == 'd') choice.level = std::max(0, choice.level - 1);
    }
    return choice;
}

}  // namespace warplab::live
