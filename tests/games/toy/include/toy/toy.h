// A third game, only for the tests, that proves the seam a game plugs into: one sphere drifts
// across a fixed view, and a click while it is under the reticle is a hit. It is its own two
// files plus one registerGame call; the runner, replay and export know nothing of it.
//
// Protocol: {"game": "toy", "name": ..., "refresh_hz": 120, "mode": "bireproj15to60",
//            "duration_s": 4}
#pragma once

#include <string>

namespace warplab::game::toy {

inline constexpr const char* kGameName = "toy";

// Registers the toy with game/registry (once per process; later calls do nothing).
void registerToyGame();

// A protocol file's text for the toy in `mode`.
std::string toyProtocol(const std::string& mode, double durationS = 4.0);

}  // namespace warplab::game::toy
