#include "game/shooter/shooter_study.h"

#include "game/shooter/shooter_bot.h"
#include "game/shooter/shooter_game.h"
#include "protocol/shooter_protocol.h"

namespace warplab::game {
namespace {

class ShooterStudy final : public Study {
public:
    explicit ShooterStudy(protocol::ShooterProtocol p) : protocol_(std::move(p)) {}
    std::string game() const override { return protocol_.game; }
    std::string name() const override { return protocol_.name; }
    std::string protocolJson() const override { return protocol::toJson(protocol_); }
    double refreshHz() const override { return protocol_.refreshHz; }
    std::unique_ptr<Game> newGame(std::uint64_t seed, const DisplaySize& display) const override {
        return std::make_unique<ShooterGame>(protocol_, seed, display.aspect());
    }
    std::unique_ptr<FreePlayGame> newFreePlay(std::uint64_t seed, const DisplaySize& display, const std::string& mode,
                                              int difficulty) const override {
        auto game = std::make_unique<ShooterGame>(protocol_, seed, display.aspect());
        game->switchTo(mode, difficulty);
        return game;
    }
    std::unique_ptr<Player> newBot(std::uint64_t seed, const DisplaySize&) const override {
        return std::make_unique<ShooterBot>(seed, protocol_);
    }
    bool warnsOnRefreshMismatch() const override { return protocol_.refreshMismatch == "warn"; }
    double mouseRadiansPerCount() const override { return protocol_.mouseRadiansPerCount; }
    std::vector<std::string> modes() const override {
        std::vector<std::string> ids{protocol_.acclimationMode, protocol_.training.lowMode, protocol_.training.highMode};
        ids.insert(ids.end(), protocol_.conditions.begin(), protocol_.conditions.end());
        return ids;
    }

private:
    protocol::ShooterProtocol protocol_;
};

}  // namespace

std::unique_ptr<Study> parseShooterStudy(const std::string& jsonText, const std::string& sourceName) {
    return std::make_unique<ShooterStudy>(protocol::parseShooterProtocol(jsonText, sourceName, checkMode));
}

}  // namespace warplab::game
