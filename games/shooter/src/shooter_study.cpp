#include "shooter/shooter_study.h"

#include <set>

#include "game/event_detail.h"
#include "game/questionnaire.h"
#include "shooter_bot.h"
#include "shooter_game.h"
#include "shooter/shooter_protocol.h"
#include "table/columns.h"

namespace warplab::game {
namespace {

// The shooter's own columns of shots.csv (docs/shooter-study.md), from a shot's or a timeout's
// event detail.
const std::vector<table::Column<EventDetail>>& shotColumns() {
    using F = table::CellWriter;
    using R = EventDetail;
    static const std::vector<table::Column<R>> columns = {
        {"angular_error_deg", [](F& f, const R& d) { f.number(d.number("angular_error_deg")); }},
        {"difficulty", [](F& f, const R& d) { f.number(d.number("difficulty")); }},
        {"target_speed", [](F& f, const R& d) { f.number(d.number("target_speed")); }},
    };
    return columns;
}

class ShooterStudy final : public Study {
public:
    explicit ShooterStudy(protocol::ShooterProtocol p) : protocol_(std::move(p)) {}
    std::string game() const override { return protocol_.game; }
    std::string name() const override { return protocol_.name; }
    std::string protocolJson() const override { return protocol::toJson(protocol_); }
    double refreshHz() const override { return protocol_.refreshHz; }
    std::unique_ptr<Game> newGame(std::uint64_t seed, const DisplaySize& display) const override {
        return std::make_unique<ShooterGame>(protocol_, seed, display);
    }
    std::unique_ptr<FreePlayGame> newFreePlay(std::uint64_t seed, const DisplaySize& display,
                                              const std::string& condition, int difficulty) const override {
        auto game = std::make_unique<ShooterGame>(protocol_, seed, display);
        game->switchTo(condition, difficulty);
        return game;
    }
    std::unique_ptr<Player> newBot(std::uint64_t seed, const DisplaySize&) const override {
        return std::make_unique<ShooterBot>(seed, protocol_);
    }
    bool warnsOnRefreshMismatch() const override {
        return protocol_.refreshMismatch == protocol::RefreshMismatch::Warn;
    }
    protocol::RenderSettings rendering() const override { return protocol_.rendering; }
    double mouseRadiansPerCount() const override { return protocol_.mouseRadiansPerCount; }
    Instructions instructions() const override {
        Instructions i;
        i.pointer = PointerKind::Reticle;
        i.verticalFovDeg = protocol_.verticalFovDeg;
        i.radiansPerCount = protocol_.mouseRadiansPerCount;
        i.targets = Instructions::Targets::All;
        i.task = "shoot the target";
        return i;
    }
    const condition::ConditionTable& conditions() const override { return protocol_.conditionTable; }
    std::vector<std::string> conditionNames() const override {
        std::vector<std::string> ids{protocol_.acclimationCondition, protocol_.training.lowCondition,
                                     protocol_.training.highCondition};
        ids.insert(ids.end(), protocol_.conditions.begin(), protocol_.conditions.end());
        return ids;
    }
    std::vector<std::string> analysedConditions() const override { return protocol_.conditions; }
    SessionResults results(const std::vector<session::EventRecord>& events) const override {
        SessionResults out;
        out.canTimeOut = true;
        out.measure = {"hits", "shots"};  // a timeout is a shot that missed
        for (const auto& e : events) {
            if (auto a = answerResult(e, protocol_.questions)) {
                a->scoredPhase = true;  // asked after blocks of the test
                out.answers.push_back(std::move(*a));
                continue;
            }
            if (e.type != "shot" && e.type != "timeout") continue;
            const EventDetail d(e.detailJson);
            ShotResult r;
            r.phase = e.phase;
            r.scoredPhase = e.phase == "test";  // acclimation and training set up the test; only it is analysed
            r.trial = e.trial;
            r.condition = e.condition;
            r.worldOutcome = e.worldOutcome;
            r.displayedOutcome = e.displayedOutcome;
            r.outcome =
                d.text("scored", protocol_.scoring == protocol::Scoring::World ? e.worldOutcome : e.displayedOutcome);
            r.hit = r.outcome == "hit";
            r.timeout = r.outcome == "timeout";
            r.time = e.eventTime;
            r.spawnTime = d.number("spawn_time");
            r.aimTime = d.number("aim_time");
            table::writeCells(r.own, shotColumns(), d);
            out.shots.push_back(std::move(r));
        }
        return out;
    }
    Progress progress(const std::vector<session::EventRecord>& events) const override {
        // A test trial ends with its one shot, or its timeout.
        std::set<int> ended;
        for (const ShotResult& shot : results(events).shots)
            if (shot.scoredPhase) ended.insert(shot.trial);
        return {"test trials", ended.size(),
                protocol_.conditions.size() * static_cast<std::size_t>(protocol_.targetsPerCondition)};
    }
    std::optional<CounterbalancedList> counterbalanced() const override {
        return CounterbalancedList{protocol_.conditions, !protocol_.interleaveConditions};
    }
    std::string withConditionOrder(const std::string& protocolText,
                                   const std::vector<std::string>& order) const override {
        return protocol::withList(protocolText, "test", "conditions", order);
    }

private:
    protocol::ShooterProtocol protocol_;
};

}  // namespace

std::unique_ptr<Study> parseShooterStudy(const std::string& jsonText, const std::string& sourceName) {
    return std::make_unique<ShooterStudy>(protocol::parseShooterProtocol(jsonText, sourceName));
}

GameExport shooterExport() { return {table::headerOf(shotColumns()), nullptr}; }

}  // namespace warplab::game
