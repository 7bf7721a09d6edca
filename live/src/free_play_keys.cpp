#include "free_play_keys.h"

#include <algorithm>

namespace warplab::live {
namespace {

// The first condition after (step +1) or before (-1) `current` that runs; `current` when none
// other does. A condition not in the list steps from before its start.
std::string stepCondition(const std::string& current, int step, const std::vector<std::string>& conditions,
                          const std::function<bool(const std::string&)>& runs) {
    const long count = static_cast<long>(conditions.size());
    const long at = std::find(conditions.begin(), conditions.end(), current) - conditions.begin();
    long i = at < count ? at : (step > 0 ? -1 : count);
    for (long tried = 0; tried < count; ++tried) {
        i = ((i + step) % count + count) % count;
        if (conditions[i] == current) break;
        if (runs(conditions[i])) return conditions[i];
    }
    return current;
}

}  // namespace

FreePlayChoice applyFreePlayKeys(FreePlayChoice choice, const std::string& keys,
                                 const std::vector<std::string>& conditions,
                                 const std::function<bool(const std::string&)>& runs) {
    for (const char c : keys) {
        if (c >= '1' && c <= '9' && static_cast<std::size_t>(c - '1') < conditions.size())
            choice.condition = conditions[c - '1'];
        if ((c == ']' || c == '[') && !conditions.empty())
            choice.condition = stepCondition(choice.condition, c == ']' ? 1 : -1, conditions, runs);
        if (c == 'u') ++choice.level;
        if (c == 'd') choice.level = std::max(0, choice.level - 1);
    }
    return choice;
}

}  // namespace warplab::live
