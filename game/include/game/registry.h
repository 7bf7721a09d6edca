// The games warplab knows, and the one protocol loader: it reads the protocol's "game" field
// and hands the file to that game's parser. Nothing here names a game: each is a module of its
// own (games/NAME/), registered at run time -- the built-in ones by the app
// (games::registerGames), a lab's own task or a test's by a registerGame call.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "game/game.h"
#include "game/results.h"

namespace warplab::game {

// Throws protocol::ProtocolError with one sentence naming the file and the field.
std::unique_ptr<Study> parseStudy(const std::string& jsonText, const std::string& sourceName);
std::unique_ptr<Study> loadStudy(const std::string& path);
std::vector<std::string> gameNames();

// Parses a protocol of one game; throws protocol::ProtocolError naming the file and the field.
using StudyParser = std::unique_ptr<Study> (*)(const std::string& jsonText, const std::string& sourceName);
// The tables of a game's own that export writes (SessionResults::tables), without rows: every
// export writes them, header only where no session of the game is included, so that a folder
// exported again never keeps an older export's rows beside the new data.
using GameTables = std::vector<GameTable> (*)();
// What a game adds to the export beside what every game has (docs/export.md).
struct GameExport {
    // Its own columns of shots.csv, which its rows fill (ShotResult::own) and other games' rows
    // leave empty. A column is one game's, as a table's file is.
    std::vector<std::string> shotColumns;
    GameTables tables = nullptr;
};
// Makes `name` (the protocol's "game") known to parseStudy and gameNames, after the games
// registered before it. Throws std::invalid_argument when a game of that name is already known,
// when one of its tables has the file name of another game's, or when one of its shots.csv
// columns is another game's or its own twice.
void registerGame(const std::string& name, StudyParser parse, GameExport exports = {});

// Every registered game's own tables, in the order registered: (game, table without rows).
std::vector<std::pair<std::string, GameTable>> gameTables();
// Every registered game's own columns of shots.csv, in the order registered: (game, columns).
std::vector<std::pair<std::string, std::vector<std::string>>> gameShotColumns();

}  // namespace warplab::game
