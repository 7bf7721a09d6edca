// The games warplab knows, and the one protocol loader: it reads the protocol's "game" field
// and hands the file to that game's parser. Adding a built-in game is one line in registry.cpp;
// a game built elsewhere (a lab's own task, a test's) registers itself at run time.
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
// Makes `name` (the protocol's "game") known to parseStudy and gameNames, after the built-in
// games. Throws std::invalid_argument when a game of that name is already known.
void registerGame(const std::string& name, StudyParser parse);

}  // namespace warplab::game
