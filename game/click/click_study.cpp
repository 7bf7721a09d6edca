#include "game/click/click_study.h"

#include <cctype>
#include <cstring>
#include <utility>

#include "game/click/click_bot.h"
#include "game/click/click_game.h"
#include "protocol/click_protocol.h"
#include "protocol/study_protocol.h"

namespace warplab::game {
namespace {

class ClickStudy final : public Study {
public:
    explicit ClickStudy(protocol::ClickProtocol p) : protocol_(std::move(p)) {}
    std::string game() const override { return protocol_.game; }
    std::string name() const override { return protocol_.name; }
    std::string protocolJson() const override { return protocol::toJson(protocol_); }
    double refreshHz() const override { return protocol_.refreshHz; }
    std::unique_ptr<Game> newGame(std::uint64_t seed, const DisplaySize& display) const override {
        return std::make_unique<ClickGame>(protocol_, seed, display);
    }
    std::unique_ptr<FreePlayGame> newFreePlay(std::uint64_t seed, const DisplaySize& display, const std::string& mode,
                                              int difficulty) const override {
        auto game = std::make_unique<ClickGame>(protocol_, seed, display);
        game->switchTo(mode, difficulty);
        return game;
    }
    std::unique_ptr<Player> newBot(std::uint64_t seed, const DisplaySize& display) const override {
        return std::make_unique<ClickBot>(seed, protocol_, display);
    }
    std::vector<std::string> modes() const override { return protocol_.modes; }
    bool warnsOnRefreshMismatch() const override { return protocol_.refreshMismatch == "warn"; }

private:
    protocol::ClickProtocol protocol_;
};

}  // namespace

std::unique_ptr<Study> parseClickStudy(const std::string& jsonText, const std::string& sourceName) {
    auto p = protocol::parseClickProtocol(jsonText, sourceName, checkMode);
    // What only the physics can judge (a radius too big for the box, more spheres than fit at
    // the start) is still the protocol's fault: say so before any session starts.
    try {
        ClickGame probe(p, 0, DisplaySize{});
    } catch (const std::invalid_argument& e) {
        // Name the protocol's field, not the physics struct's member.
        std::string why = e.what();
        const std::pair<const char*, const char*> names[] = {
            {"FallingSphereSettings.radius", "physics.sphere_radius_m"},
            {"FallingSphereSettings.sphereCount", "physics.sphere_count"},
            {"FallingSphereSettings.gravity", "physics.gravity_m_per_s2"},
            {"FallingSphereSettings.restitution", "physics.restitution"},
            {"FallingSphereSettings.stepRateHz", "physics.step_rate_hz"},
            {"FallingSphereSettings.greenShare", "physics.green_share"},
            {"FallingSphereSettings.spawnDelayS", "physics.spawn_delay_s"},
            {"FallingSphereSettings.spawnSpeed", "physics.spawn_speed_m_per_s"},
        };
        for (const auto& [member, field] : names)
            if (why.rfind(member, 0) == 0 && !std::isalpha(static_cast<unsigned char>(why[std::strlen(member)])))
                why = field + why.substr(std::strlen(member));
        throw protocol::ProtocolError("protocol '" + sourceName + "': " + why);
    }
    return std::make_unique<ClickStudy>(std::move(p));
}

}  // namespace warplab::game
