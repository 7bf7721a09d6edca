// The click game's registration: its protocol section parsed and bound to ClickGame and
// ClickBot. games/src/games.cpp registers it; nothing below the app names the click game.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "game/game.h"
#include "game/registry.h"
#include "game/results.h"

namespace warplab::game {

std::unique_ptr<Study> parseClickStudy(const std::string& jsonText, const std::string& sourceName);
// The click game's own export tables, without rows: matches.csv and ratings.csv
// (docs/click-study.md).
std::vector<GameTable> clickTables();
// What the click game adds to the export: its column of shots.csv and those tables.
GameExport clickExport();

}  // namespace warplab::game
