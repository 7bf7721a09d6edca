#include "game/registry.h"

#include <stdexcept>

#include "click/click_study.h"
#include "shooter/shooter_study.h"
#include "protocol/study_protocol.h"

namespace warplab::game {
namespace {

struct GameEntry {
    const char* name;  // the protocol's "game"
    std::unique_ptr<Study> (*parse)(const std::string& jsonText, const std::string& sourceName);
};

// The one list of built-in games. A new built-in game adds its folder and one line here.
constexpr GameEntry kGames[] = {
    {"shooter", parseShooterStudy},
    {"click", parseClickStudy},
};

struct RegisteredGame {
    std::string name;
    StudyParser parse;
};

// Games registered at run time, after the built-in ones.
std::vector<RegisteredGame>& registered() {
    static std::vector<RegisteredGame> games;
    return games;
}

// Every known game, built-in first.
std::vector<RegisteredGame> allGames() {
    std::vector<RegisteredGame> games;
    for (const auto& g : kGames) games.push_back({g.name, g.parse});
    games.insert(games.end(), registered().begin(), registered().end());
    return games;
}

}  // namespace

std::vector<std::string> gameNames() {
    std::vector<std::string> names;
    for (const auto& g : allGames()) names.push_back(g.name);
    return names;
}

void registerGame(const std::string& name, StudyParser parse) {
    if (name.empty() || parse == nullptr)
        throw std::invalid_argument("registerGame: a game needs a name and a protocol parser");
    for (const auto& known : gameNames())
        if (known == name) throw std::invalid_argument("registerGame: a game named \"" + name + "\" is already known");
    registered().push_back({name, parse});
}

std::unique_ptr<Study> parseStudy(const std::string& jsonText, const std::string& sourceName) {
    const std::string game = protocol::protocolGame(jsonText, sourceName);
    const std::vector<RegisteredGame> games = allGames();
    for (const auto& g : games)
        if (game == g.name) return g.parse(jsonText, sourceName);
    std::string known;
    for (const auto& g : games) known += std::string(known.empty() ? "" : ", ") + "\"" + g.name + "\"";
    throw protocol::ProtocolError("protocol '" + sourceName + "': game \"" + game +
                                  "\" is not a known game (known: " + known + ")");
}

std::unique_ptr<Study> loadStudy(const std::string& path) { return parseStudy(protocol::readProtocolFile(path), path); }

}  // namespace warplab::game
