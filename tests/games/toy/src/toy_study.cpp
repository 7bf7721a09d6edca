// The toy's Study: its protocol bound to its game, and everything the rest of warplab asks of a
// game -- bots, results, progress, what a participant is told, the list a plan counterbalances.
#include <memory>

#include "game/event_detail.h"
#include "protocol/study_protocol.h"
#include "table/columns.h"
#include "toy/toy.h"
#include "toy_game.h"
#include "toy_protocol.h"

namespace warplab::toy {
namespace {

using game::Study;

// A row of toy_clicks.csv: a click, and where the sphere was against where it was shown.
struct Click {
    const session::EventRecord& event;
    game::EventDetail detail;
};

const std::vector<table::Column<Click>>& clickColumns() {
    using F = table::CellWriter;
    using R = Click;
    static const std::vector<table::Column<R>> columns = {
        {"click", [](F& f, const R& r) { f.integer(r.event.trial); }},
        {"condition", [](F& f, const R& r) { f.text(r.event.condition); }},
        {"shown_x_m", [](F& f, const R& r) { f.number(r.detail.number("shown_x")); }},
        {"true_x_m", [](F& f, const R& r) { f.number(r.detail.number("x")); }},
        // What the condition's latency moved the sphere by, as the participant saw it.
        {"shown_offset_m", [](F& f, const R& r) { f.number(r.detail.number("shown_x") - r.detail.number("x")); }},
        {"typed", [](F& f, const R& r) { f.text(r.detail.text("typed", "")); }},
    };
    return columns;
}

// The toy's own column of shots.csv: what the condition's latency moved the sphere by.
const std::vector<table::Column<game::EventDetail>>& shotColumns() {
    using F = table::CellWriter;
    using R = game::EventDetail;
    static const std::vector<table::Column<R>> columns = {
        {"toy_offset_m", [](F& f, const R& d) { f.number(d.number("shown_x") - d.number("x")); }},
    };
    return columns;
}

game::GameTable clicksTable() { return {"toy_clicks.csv", table::headerOf(clickColumns()), false, "", {}}; }

class ToyStudy final : public Study {
public:
    explicit ToyStudy(ToyProtocol p) : protocol_(std::move(p)) {}
    std::string game() const override { return protocol_.game; }
    std::string name() const override { return protocol_.name; }
    std::string protocolJson() const override { return toJson(protocol_); }
    double refreshHz() const override { return protocol_.refreshHz; }
    std::unique_ptr<game::Game> newGame(std::uint64_t seed, const game::DisplaySize&) const override {
        return std::make_unique<ToyGame>(protocol_, seed);
    }
    std::unique_ptr<game::FreePlayGame> newFreePlay(std::uint64_t seed, const game::DisplaySize&,
                                                    const std::string& condition, int difficulty) const override {
        auto game = std::make_unique<ToyGame>(protocol_, seed);
        game->switchTo(condition, difficulty);
        return game;
    }
    std::unique_ptr<game::Player> newBot(std::uint64_t, const game::DisplaySize&) const override {
        return std::make_unique<ToyBot>();
    }
    std::vector<std::string> conditionNames() const override { return protocol_.conditions; }
    const condition::ConditionTable& conditions() const override { return protocol_.conditionTable; }
    // The view does not turn: the participant waits for the sphere and clicks.
    game::Instructions instructions() const override {
        game::Instructions i;
        i.pointer = game::PointerKind::Reticle;
        i.verticalFovDeg = scene::CameraState{}.verticalFovDeg;
        i.radiansPerCount = 0.0;
        i.targets = game::Instructions::Targets::All;
        i.task = "Click while the sphere is under the reticle.";
        return i;
    }
    bool warnsOnRefreshMismatch() const override { return true; }
    protocol::RenderSettings rendering() const override { return {}; }
    game::SessionResults results(const std::vector<session::EventRecord>& events) const override {
        game::SessionResults out;
        out.measure = {"toy hits", "clicks"};
        out.tables = {clicksTable()};
        for (const auto& e : events) {
            if (e.type != "click") continue;
            game::GameTableRow row;
            row.condition = e.condition;
            row.scoredPhase = true;
            table::writeCells(row.cells, clickColumns(), Click{e, game::EventDetail(e.detailJson)});
            out.tables.front().rows.push_back(std::move(row));
            game::ShotResult r;
            r.phase = e.phase;
            r.scoredPhase = true;
            r.trial = e.trial;
            r.condition = e.condition;
            r.outcome = e.displayedOutcome;
            r.worldOutcome = e.worldOutcome;
            r.displayedOutcome = e.displayedOutcome;
            r.hit = r.outcome == "hit";
            r.time = e.eventTime;
            table::writeCells(r.own, shotColumns(), game::EventDetail(e.detailJson));
            out.shots.push_back(std::move(r));
        }
        return out;
    }
    // Clicks, of no planned number: the toy runs for a time.
    game::Progress progress(const std::vector<session::EventRecord>& events) const override {
        return {"clicks", results(events).shots.size(), 0};
    }
    std::optional<game::CounterbalancedList> counterbalanced() const override {
        return game::CounterbalancedList{protocol_.conditions, !protocol_.shuffle};
    }
    std::string withConditionOrder(const std::string& protocolText,
                                   const std::vector<std::string>& order) const override {
        return protocol::withList(protocolText, "play", "conditions", order);
    }

private:
    ToyProtocol protocol_;
};

}  // namespace

std::unique_ptr<Study> parseStudy(const std::string& jsonText, const std::string& sourceName) {
    return std::make_unique<ToyStudy>(parseToyProtocol(jsonText, sourceName));
}

std::vector<game::GameTable> tables() { return {clicksTable()}; }

game::GameExport exports() { return {table::headerOf(shotColumns()), tables}; }

}  // namespace warplab::toy
