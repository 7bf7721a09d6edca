#include "game/registry.h"

#include "click/click_study.h"
#include "shooter/shooter_study.h"
#include "protocol/study_protocol.h"

namespace warplab::game {
namespace {

struct GameEntry {
    const char* name;  // the protocol's "game"
    std::unique_ptr<Study> (*parse)(const std::string& jsonText, const std::string& sourceName);
};

// The one list of games. A new game adds its folder and one line here.
constexpr GameEntry kGames[] = {
    {"shooter", parseShooterStudy},
    {"click", parseClickStudy},
};

}  // namespace

std::vector<std::string> gameNames() {
    std::vector<std::string> names;
    for (const auto& g : kGames) names.emplace_back(g.name);
    return names;
}

std::unique_ptr<Study> parseStudy(const std::string& jsonText, const std::string& sourceName) {
    const std::string game = protocol::protocolGame(jsonText, sourceName);
    for (const auto& g : kGames)
        if (game == g.name) return g.parse(jsonText, sourceName);
    std::string known;
    for (const auto& g : kGames) known += std::string(known.empty() ? "" : ", ") + "\"" + g.name + "\"";
    throw protocol::ProtocolError("protocol '" + sourceName + "': game \"" + game + "\" is not a known game (known: " +
                                  known + ")");
}

std::unique_ptr<Study> loadStudy(const std::string& path) { return parseStudy(protocol::readProtocolFile(path), path); }

}  // namespace warplab::game
