// How a live session takes the display's refresh against its protocol's: said once, for
// `warplab run` (WindowLoop::open) and `warplab check`, so the pre-flight and the session
// refuse the same displays in the same words.
#pragma once

#include <string>

#include "game/game.h"

namespace warplab::live {

// The display runs at another refresh than the protocol's, or reports none (0 Hz: Xvfb, some
// virtual and remote displays), so the session's timing cannot be vouched for.
bool refreshMismatch(double reportedHz, double protocolHz);

// Whether a session refuses such a display: its protocol says "refuse"
// (display.refresh_mismatch) and the run was not given --allow-refresh-mismatch. A display
// that reports no rate may be running at any, so it is refused like one known to differ.
bool refusesRefresh(double reportedHz, const game::Study& study, bool allowMismatch);

// One sentence: the display's refresh against what `protocol` (a file or a name) needs, and,
// when `refused`, what to do about it.
std::string refreshText(double reportedHz, double protocolHz, const std::string& protocol, bool refused);

}  // namespace warplab::live
