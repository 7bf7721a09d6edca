// The click game's registration: its protocol section parsed and bound to ClickGame and
// ClickBot. games/src/games.cpp registers it; nothing below the app names the click game.
#pragma once

#include <memory>
#include <string>

#include "game/game.h"

namespace warplab::game {

std::unique_ptr<Study> parseClickStudy(const std::string& jsonText, const std::string& sourceName);

}  // namespace warplab::game
