// The games warplab knows, and the one protocol loader: it reads the protocol's "game" field
// and hands the file to that game's parser. Adding a game is one line in registry.cpp.
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

}  // namespace warplab::game
