#include "game/click/click_study.h"

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
    std::unique_ptr<Player> newBot(std::uint64_t seed, const DisplaySize& display) const override {
        return std::make_unique<ClickBot>(seed, protocol_, display);
    }
    std::vector<std::string> modes() const override { return protocol_.modes; }

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
        throw protocol::ProtocolError("protocol '" + sourceName + "': physics does not fit the box: " + e.what());
    }
    return std::make_unique<ClickStudy>(std::move(p));
}

}  // namespace warplab::game
