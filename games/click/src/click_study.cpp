#include "click/click_study.h"

#include <cctype>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

#include "click_bot.h"
#include "click_results.h"
#include "game/event_detail.h"
#include "game/questionnaire.h"
#include "click_game.h"
#include "click/click_protocol.h"
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
    std::unique_ptr<FreePlayGame> newFreePlay(std::uint64_t seed, const DisplaySize& display,
                                              const std::string& condition, int difficulty) const override {
        auto game = std::make_unique<ClickGame>(protocol_, seed, display);
        game->switchTo(condition, difficulty);
        return game;
    }
    std::unique_ptr<Player> newBot(std::uint64_t seed, const DisplaySize& display) const override {
        return std::make_unique<ClickBot>(seed, protocol_, display);
    }
    std::vector<std::string> conditionNames() const override { return protocol_.conditions; }
    const condition::ConditionTable& conditions() const override { return protocol_.conditionTable; }
    bool warnsOnRefreshMismatch() const override {
        return protocol_.refreshMismatch == protocol::RefreshMismatch::Warn;
    }
    Instructions instructions() const override {
        Instructions i;
        i.pointer = PointerKind::Cursor;
        i.verticalFovDeg = protocol_.verticalFovDeg;
        i.pixelsPerCount = protocol_.cursorPixelsPerCount;
        i.targets = Instructions::Targets::GreenOnly;
        i.task = "click the green spheres, never the red ones";
        return i;
    }
    protocol::RenderSettings rendering() const override { return protocol_.rendering; }
    SessionResults results(const std::vector<session::EventRecord>& events) const override {
        SessionResults out;
        out.measure = {"green hits", "clicks"};
        std::vector<MatchResult> matches;
        // Ratings follow their match's "match" event; match indices are unique in a session.
        std::map<int, std::size_t> matchAt;
        // A click counts once its match has ended: a match a session was cut short in has no
        // result (no matches.csv row), so its clicks, from part of a match, stay out of shots.csv
        // and hitrates.csv as well, as a shooter trial without its shot does.
        std::map<int, std::vector<ShotResult>> unfinished;
        for (const auto& e : events) {
            const EventDetail d(e.detailJson);
            if (e.type == "click") {
                ShotResult r;
                r.phase = e.phase;
                r.scoredPhase = roundScored(e.phase);
                r.trial = e.trial;
                r.condition = e.condition;
                r.worldOutcome = e.worldOutcome;
                r.displayedOutcome = e.displayedOutcome;
                r.outcome = d.text("scored",
                                   protocol_.scoring == protocol::Scoring::World ? e.worldOutcome : e.displayedOutcome);
                r.hit = r.outcome == "green";
                r.time = e.eventTime;
                writeClickShotCells(r.own, d);
                unfinished[e.trial].push_back(std::move(r));
            } else if (e.type == "match") {
                if (const auto clicks = unfinished.find(e.trial); clicks != unfinished.end()) {
                    for (auto& r : clicks->second) out.shots.push_back(std::move(r));
                    unfinished.erase(clicks);
                }
                MatchResult m;
                m.round = e.phase;
                m.scoredPhase = roundScored(e.phase);
                m.match = e.trial;
                m.condition = e.condition;
                m.standIn = d.text("stand_in");  // sessions recorded while blend stood in for bireproj
                m.greenHits = static_cast<int>(d.integer("green_hits", 0));
                m.redHits = static_cast<int>(d.integer("red_hits", 0));
                m.misses = static_cast<int>(d.integer("misses", 0));
                m.clicks = static_cast<int>(d.integer("clicks", 0));
                m.durationS = d.number("duration_s");
                m.endTime = e.eventTime;  // the match event is its last frame's
                matchAt[e.trial] = matches.size();
                matches.push_back(std::move(m));
            } else if (auto a = answerResult(e, protocol_.questions)) {
                a->scoredPhase = roundScored(e.phase);
                // A match's Likert answers are its ratings too (matches.csv, ratings.csv).
                const auto at = matchAt.find(e.trial);
                if (a->kind == "likert" && a->value && at != matchAt.end()) {
                    RatingResult r;
                    r.statementIndex = a->questionIndex;
                    r.statement = a->prompt;
                    r.value = *a->value;
                    r.answeredWith = a->answeredWith;
                    r.scaleMin = a->scaleMin;  // the stored protocol's: the one the participant answered on
                    r.scaleMax = a->scaleMax;
                    matches[at->second].ratings.push_back(std::move(r));
                }
                out.answers.push_back(std::move(*a));
            }
        }
        out.tables = clickTables(matches);
        return out;
    }
    Progress progress(const std::vector<session::EventRecord>& events) const override {
        Progress p{"matches", 0, 0};
        for (const auto& e : events) p.done += e.type == "match";
        for (const auto& round : protocol_.rounds)
            p.planned += protocol_.conditions.size() * static_cast<std::size_t>(round.matchesPerCondition);
        return p;
    }
    std::optional<CounterbalancedList> counterbalanced() const override {
        return CounterbalancedList{protocol_.conditions, !protocol_.shuffle};
    }
    std::string withConditionOrder(const std::string& protocolText,
                                   const std::vector<std::string>& order) const override {
        return protocol::withList(protocolText, "matches", protocol::conditionListKey(protocol_.formatVersion).c_str(),
                                  order);
    }

private:
    bool roundScored(const std::string& round) const {
        for (const auto& r : protocol_.rounds)
            if (r.name == round) return r.scored;
        return false;
    }

    protocol::ClickProtocol protocol_;
};

}  // namespace

std::unique_ptr<Study> parseClickStudy(const std::string& jsonText, const std::string& sourceName) {
    auto p = protocol::parseClickProtocol(jsonText, sourceName);
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
