// The toy: a third game that lives only in the test tree and proves the seam a new task plugs
// into, at run time and where its developer works. One sphere drifts across a fixed view; a
// click while it is under the reticle is a hit. It is a module of its own -- its strict
// protocol section (toy.md lists every key), game, bot, Study, the list a study plan
// counterbalances, what a participant is told and its own export table -- registered by one line:
//     game::registerGame(toy::kGameName, toy::parseStudy, toy::exports());
// Nothing else in warplab knows it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "game/game.h"
#include "game/registry.h"
#include "game/results.h"

namespace warplab::toy {

inline constexpr const char* kGameName = "toy";

// Throws protocol::ProtocolError, one sentence naming the file and the field.
std::unique_ptr<game::Study> parseStudy(const std::string& jsonText, const std::string& sourceName);
// Its own export table, toy_clicks.csv, without rows (README.md lists its columns).
std::vector<game::GameTable> tables();
// What it adds to the export: that table and its column of shots.csv.
game::GameExport exports();

// Every key of a toy protocol as a JSON path, header first, in the parser's table order.
std::vector<std::string> toyProtocolKeys();

// A protocol file's text for the toy playing `conditions` in order, `secondsEach` each, on a
// 120 Hz display (every condition runs on it, warp15to120 included).
std::string toyProtocol(const std::vector<std::string>& conditions, double secondsEach = 4.0, bool shuffle = false);
std::string toyProtocol(const std::string& condition, double seconds = 4.0);

}  // namespace warplab::toy
