// The discrimination task's Study: its protocol bound to its game, and what the rest of warplab
// asks of a game -- bots, results, progress, what a participant is told.
#include "discrimination/discrimination_study.h"

#include <algorithm>
#include <memory>

#include "discrimination/discrimination_protocol.h"
#include "discrimination_bot.h"
#include "discrimination_game.h"
#include "discrimination_results.h"

namespace warplab::discrimination {
namespace {

class DiscriminationStudy final : public game::Study {
public:
    explicit DiscriminationStudy(DiscriminationProtocol p) : protocol_(std::move(p)) {}
    std::string game() const override { return protocol_.game; }
    std::string name() const override { return protocol_.name; }
    std::string protocolJson() const override { return toJson(protocol_); }
    double refreshHz() const override { return protocol_.refreshHz; }
    std::unique_ptr<game::Game> newGame(std::uint64_t seed, const game::DisplaySize& display) const override {
        return std::make_unique<DiscriminationGame>(protocol_, seed, display);
    }
    std::unique_ptr<game::FreePlayGame> newFreePlay(std::uint64_t seed, const game::DisplaySize& display,
                                                    const std::string& condition, int difficulty) const override {
        auto game = std::make_unique<DiscriminationGame>(protocol_, seed, display);
        game->switchTo(condition, difficulty);
        return game;
    }
    std::unique_ptr<game::Player> newBot(std::uint64_t seed, const game::DisplaySize&) const override {
        return std::make_unique<DiscriminationBot>(seed, protocol_);
    }
    // The procedures' references, in the protocol's order: the conditions whose trials it runs
    // (each test condition is a reference with one part changed).
    std::vector<std::string> conditionNames() const override {
        std::vector<std::string> names;
        for (const ProcedureSpec& spec : protocol_.procedures)
            if (std::find(names.begin(), names.end(), spec.reference) == names.end()) names.push_back(spec.reference);
        return names;
    }
    const condition::ConditionTable& conditions() const override { return protocol_.conditionTable; }
    double mouseRadiansPerCount() const override { return protocol_.mouseRadiansPerCount; }
    game::Instructions instructions() const override {
        game::Instructions i;
        i.pointer = game::PointerKind::Reticle;
        i.verticalFovDeg = protocol_.verticalFovDeg;
        i.radiansPerCount = protocol_.mouseRadiansPerCount;
        i.targets = game::Instructions::Targets::All;
        i.task = "Follow the ball in both intervals, then say which was more responsive.";
        return i;
    }
    bool warnsOnRefreshMismatch() const override {
        return protocol_.refreshMismatch == protocol::RefreshMismatch::Warn;
    }
    protocol::RenderSettings rendering() const override { return protocol_.rendering; }
    game::SessionResults results(const std::vector<session::EventRecord>& events) const override {
        game::SessionResults out;
        out.measure = {"correct answers", "trials"};
        out.tables = resultTables(protocol_, events);
        return out;
    }
    // Answered trials, of at most what the procedures plan (QUEST+ may stop sooner).
    game::Progress progress(const std::vector<session::EventRecord>& events) const override {
        std::size_t planned = 0;
        for (const ProcedureSpec& spec : protocol_.procedures)
            planned += spec.method == adaptive::Method::ConstantStimuli
                ? spec.levels.size() * static_cast<std::size_t>(spec.repeats)
                : static_cast<std::size_t>(spec.maxTrials);
        const auto done = static_cast<std::size_t>(std::count_if(
            events.begin(), events.end(), [](const session::EventRecord& e) { return e.type == "judgement"; }));
        return {"trials", done, planned};
    }

    // A study plan gives each participant a seed and a results folder; the procedures' trials
    // are interleaved at random by the session seed, so there is no order for it to balance
    // (not blocked: the file is played as it is).
    std::optional<game::CounterbalancedList> counterbalanced() const override {
        return game::CounterbalancedList{conditionNames(), false};
    }

private:
    DiscriminationProtocol protocol_;
};

}  // namespace

std::unique_ptr<game::Study> parseDiscriminationStudy(const std::string& jsonText, const std::string& sourceName) {
    return std::make_unique<DiscriminationStudy>(parseDiscriminationProtocol(jsonText, sourceName));
}

std::vector<game::GameTable> discriminationTables() { return emptyTables(); }

game::GameExport discriminationExport() { return {{}, discriminationTables}; }

}  // namespace warplab::discrimination
