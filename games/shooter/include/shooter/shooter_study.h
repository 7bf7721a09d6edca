// The shooter's registration: its protocol section parsed and bound to ShooterGame and
// ShooterBot. games/src/games.cpp registers it; nothing below the app names the shooter.
#pragma once

#include <memory>
#include <string>

#include "game/game.h"
#include "game/registry.h"

namespace warplab::game {

std::unique_ptr<Study> parseShooterStudy(const std::string& jsonText, const std::string& sourceName);

// What the shooter adds to the export: its columns of shots.csv.
GameExport shooterExport();

}  // namespace warplab::game
