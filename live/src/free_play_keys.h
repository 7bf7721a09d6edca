// What the supervisor's keys do in free play (docs/live-sessions.md "Free play"), apart from
// the window so that it is tested with any list of conditions.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace warplab::live {

struct FreePlayChoice {
    std::string condition;
    int level = 0;  // the game's difficulty (the shooter's staircase level)
};

// The keys in the order pressed: '1'..'9' pick the first nine of `modes`; ']' steps to the
// next condition and '[' to the previous one, through all of `modes`, wrapping at the ends and
// passing over those `runs` refuses (the display's refresh cannot run them), so that every
// runnable condition is reachable however long the list; 'u' and 'd' raise and lower the level
// (not below 0). Other keys change nothing. A digit may pick a condition that cannot run: the game
// refuses it with the reason, which the supervisor should see.
FreePlayChoice applyFreePlayKeys(FreePlayChoice choice, const std::string& keys,
                                 const std::vector<std::string>& conditions,
                                 const std::function<bool(const std::string&)>& runs);

}  // namespace warplab::live
