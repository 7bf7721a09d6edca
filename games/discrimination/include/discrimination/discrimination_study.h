// The discrimination task's registration: its protocol section parsed and bound to
// DiscriminationGame and its bot. games/src/games.cpp registers it; nothing below the app names
// the task.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "game/game.h"
#include "game/registry.h"
#include "game/results.h"

namespace warplab::discrimination {

std::unique_ptr<game::Study> parseDiscriminationStudy(const std::string& jsonText, const std::string& sourceName);
// Its own export tables, without rows: discrimination_trials.csv and thresholds.csv
// (docs/discrimination-study.md).
std::vector<game::GameTable> discriminationTables();
// What it adds to the export: those tables (it has no shots).
game::GameExport discriminationExport();

}  // namespace warplab::discrimination
