#include "game/registry.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "protocol/study_protocol.h"

namespace warplab::game {
namespace {

struct RegisteredGame {
    std::string name;
    StudyParser parse;
    std::vector<GameTable> tables;
    std::vector<std::string> shotColumns;
};

// Every known game, in the order registered: the app's (games/src/games.cpp) first.
std::vector<RegisteredGame>& registered() {
    static std::vector<RegisteredGame> games;
    return games;
}

std::vector<RegisteredGame> allGames() { return registered(); }

// The other known game whose protocol `jsonText` is, but for its "game" field: the file parses
// as that game's once its "game" names it. Only a file with fields some game has but not every
// one can say so; one of only shared fields (a bare header) is any game's.
std::optional<std::string> gameOfFields(const std::string& jsonText, const std::string& named,
                                        const std::vector<RegisteredGame>& games, const std::string& sourceName) {
    if (!protocol::hasGameFields(jsonText)) return std::nullopt;
    nlohmann::ordered_json document = nlohmann::ordered_json::parse(jsonText, nullptr, false);
    for (const auto& g : games) {
        if (g.name == named) continue;
        document["game"] = g.name;
        try {
            g.parse(document.dump(), sourceName);
            return g.name;
        } catch (const std::exception&) {}
    }
    return std::nullopt;
}

}  // namespace

std::vector<std::string> gameNames() {
    std::vector<std::string> names;
    for (const auto& g : allGames()) names.push_back(g.name);
    return names;
}

std::vector<std::pair<std::string, GameTable>> gameTables() {
    std::vector<std::pair<std::string, GameTable>> out;
    for (const auto& g : allGames())
        for (const GameTable& t : g.tables) out.emplace_back(g.name, t);
    return out;
}

std::vector<std::pair<std::string, std::vector<std::string>>> gameShotColumns() {
    std::vector<std::pair<std::string, std::vector<std::string>>> out;
    for (const auto& g : allGames()) out.emplace_back(g.name, g.shotColumns);
    return out;
}

void registerGame(const std::string& name, StudyParser parse, GameExport exports) {
    if (name.empty() || parse == nullptr)
        throw std::invalid_argument("registerGame: a game needs a name and a protocol parser");
    for (const auto& known : gameNames())
        if (known == name) throw std::invalid_argument("registerGame: a game named \"" + name + "\" is already known");
    std::vector<std::pair<std::string, std::vector<std::string>>> columns = gameShotColumns();
    columns.emplace_back(name, std::vector<std::string>{});
    for (const std::string& column : exports.shotColumns) {
        for (const auto& [game, theirs] : columns)
            if (std::find(theirs.begin(), theirs.end(), column) != theirs.end())
                throw std::invalid_argument("registerGame: " + name + "'s shots.csv column " + column + " is already " +
                                            (game == name ? "its own" : "the " + game + " game's"));
        columns.back().second.push_back(column);
    }
    std::vector<GameTable> own = exports.tables == nullptr ? std::vector<GameTable>{} : exports.tables();
    for (const GameTable& t : own)
        for (const auto& [game, other] : gameTables())
            if (other.file == t.file)
                throw std::invalid_argument("registerGame: " + name + "'s table " + t.file + " is already the " + game +
                                            " game's");
    registered().push_back({name, parse, std::move(own), std::move(exports.shotColumns)});
}

std::unique_ptr<Study> parseStudy(const std::string& jsonText, const std::string& sourceName) {
    const std::string game = protocol::protocolGame(jsonText, sourceName);
    const std::vector<RegisteredGame> games = allGames();
    for (const auto& g : games) {
        if (game != g.name) continue;
        try {
            return g.parse(jsonText, sourceName);
        } catch (const protocol::ProtocolError&) {
            // A shooter file with "game": "click" fails the click parser on a field or on its
            // format_version, neither of which is what is wrong with it.
            const auto other = gameOfFields(jsonText, game, games, sourceName);
            if (!other) throw;
            const auto version = nlohmann::ordered_json::parse(jsonText, nullptr, false).at("format_version");
            throw protocol::ProtocolError("protocol '" + sourceName + "': game is \"" + game +
                                          "\", but format_version " + version.dump() + " and the other fields are a " +
                                          *other + " protocol's (the file reads as one with \"game\": \"" + *other +
                                          "\")");
        }
    }
    std::string known;
    for (const auto& g : games) known += std::string(known.empty() ? "" : ", ") + "\"" + g.name + "\"";
    throw protocol::ProtocolError("protocol '" + sourceName + "': game \"" + game +
                                  "\" is not a known game (known: " + known + ")");
}

std::unique_ptr<Study> loadStudy(const std::string& path) { return parseStudy(protocol::readProtocolFile(path), path); }

}  // namespace warplab::game
