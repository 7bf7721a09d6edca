// The games warplab knows, and the one protocol loader: it reads the protocol's "game" field
// and hands the file to that game's parser. Nothing here names a game: each is a module of its
// own (games/NAME/), registered at run time -- the built-in ones by the app
// (games::registerGames), a lab's own task or a test's by a registerGame call.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "game/game.h"

namespace warplab::game {

// Throws protocol::ProtocolError with one sentence naming the file and the field.
std::unique_ptr<Study> parseStudy(const std::string& jsonText, const std::string& sourceName);
std::unique_ptr<Study> loadStudy(const std::string& path);
std::vector<std::string> gameNames();

// Parses a protocol of one game; throws protocol::ProtocolError naming the file and the field.
using StudyParser = std::unique_ptr<Study> (*)(const std::string& jsonText, const std::string& sourceName);
// Makes `name` (the protocol's "game") known to parseStudy and gameNames, after the games
// registered before it. Throws std::invalid_argument when a game of that name is already known.
void registerGame(const std::string& name, StudyParser parse);

}  // namespace warplab::game
