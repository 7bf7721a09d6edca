#include "toy/toy.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "game/depiction.h"
#include "game/frame_history.h"
#include "game/game.h"
#include "game/registry.h"
#include "protocol/study_protocol.h"

namespace warplab::game::toy {
namespace {

constexpr double kRadius = 0.3;  // metres; the sphere is 5 m straight ahead
constexpr double kDistance = 5.0;

struct ToyProtocol {
    std::string name;
    double refreshHz = 60.0;
    std::string mode = "conv60";
    double durationS = 4.0;
};

// The world: the sphere's sideways offset from the reticle swings, so a warp's straight-line
// continuation and a B-frame's blend each show something other than the world.
struct Dot {
    double x = 0.0, v = 0.0;
};
Dot dotAt(double t) { return {1.2 * std::sin(1.5 * t - 1.0), 1.8 * std::cos(1.5 * t - 1.0)}; }
bool underReticle(double x) { return std::abs(x) <= kRadius; }

class ToyGame final : public FreePlayGame {
public:
    explicit ToyGame(const ToyProtocol& p)
        : protocol_(p), schedule_(condition::ConditionTable().at(p.mode), p.refreshHz), clickGate_(true) {}

    ShownFrame step(const FrameInput& input) override {
        ++frame_;
        commitPoint_ = false;
        const bool pressed = (input.buttons & kButtonLeft) && !(previousButtons_ & kButtonLeft);
        previousButtons_ = input.buttons;
        typed_ += input.text;
        const double now = static_cast<double>(frame_) / protocol_.refreshHz;
        if (frame_ == 0) emit("phase", {});
        history_.record(frame_, dotAt(now));

        // What the mode shows of the dot, through the two hooks.
        const SchedulePlacement placement{scheduleStart_, protocol_.refreshHz};
        const condition::ScheduledFrame f = schedule_.frame(frame_ - scheduleStart_);
        ShownFrame shown = scheduledShownFrame(frame_, schedule_.mode(), f, placement);
        const WorldDepiction d = depictWorld(schedule_.mode(), f, placement, WorldClock::Schedule);
        const Dot seen = *depictedState<Dot>(
            d, [&](std::int64_t frame) -> std::optional<Dot> { return history_.at(frame); },
            [](Dot dot, double dt) {
                return Dot{dot.x + dot.v * dt, dot.v};
            },
            [](const Dot& a, const Dot& b, double w, double) {
                return Dot{a.x + (b.x - a.x) * w, a.v};
            });
        shown.camera = camera_;
        scene::ObjectState o;
        o.position = camera_.eye + glm::vec3(static_cast<float>(seen.x), 0.0f, static_cast<float>(-kDistance));
        o.halfExtents = glm::vec3(static_cast<float>(kRadius));
        shown.scene.objects.push_back(o);

        if (clickGate_.pass(pressed, f)) {
            session::EventRecord e;
            e.type = "click";
            e.trial = clicks_++;
            e.mode = schedule_.mode().name;
            e.worldOutcome = underReticle(dotAt(now).x) ? "hit" : "miss";
            e.displayedOutcome = underReticle(seen.x) ? "hit" : "miss";
            // Everything typed so far, as typed (Backspaces kept): replay, and a resumed
            // session's re-simulation, reproduce it only from the input record's text.
            e.detailJson = nlohmann::json{{"shown_x", seen.x}, {"typed", typed_}, {"x", dotAt(now).x}}.dump();
            shown.feedback = e.displayedOutcome;
            emit(e);
            commitPoint_ = true;
        }
        if (!freePlay_ && frame_ + 1 >= std::llround(protocol_.durationS * protocol_.refreshHz)) {
            done_ = true;
            emit("phase", {});
        }
        return shown;
    }
    bool finished() const override { return done_; }
    std::string phase() const override { return done_ ? "done" : "play"; }
    std::vector<session::EventRecord> takeEvents() override { return events_.take(); }
    bool atCommitPoint() const override { return commitPoint_; }
    session::FrameRecord frameRecord(const ShownFrame& shown) const override {
        session::FrameRecord r;
        r.frame = shown.frame;
        r.mode = shown.mode;
        r.kind = condition::frameKindName(shown.schedule.kind);
        r.detailJson = nlohmann::json{{"x", shown.scene.objects.front().position.x}}.dump();
        return r;
    }
    bool isOutcome(const session::EventRecord& e) const override { return e.type == "click"; }
    PointerProbe probePointer(const ShownFrame& shown) const override {
        const double x = shown.scene.objects.front().position.x - camera_.eye.x;
        return {underReticle(x) ? scene::kIdTarget : scene::kIdNone, std::abs(std::abs(x) - kRadius) / kDistance};
    }
    std::optional<std::uint32_t> displayedObject(const session::EventRecord& e) const override {
        if (e.type != "click") return std::nullopt;
        return e.displayedOutcome == "hit" ? scene::kIdTarget : scene::kIdNone;
    }
    void switchTo(const std::string& mode, int) override {
        schedule_ = condition::ModeSchedule(condition::ConditionTable().at(mode), protocol_.refreshHz);
        scheduleStart_ = frame_ + 1;
        freePlay_ = true;
    }

private:
    void emit(const char* type, session::EventRecord e) {
        e.type = type;
        emit(e);
    }
    void emit(session::EventRecord e) {
        e.frame = frame_;
        e.eventTime = static_cast<double>(frame_) / protocol_.refreshHz;
        e.phase = phase();
        events_.push(std::move(e));
    }

    ToyProtocol protocol_;
    condition::ModeSchedule schedule_;
    std::int64_t scheduleStart_ = 0;
    ClickGate clickGate_;
    EventQueue events_;
    FrameHistory<Dot> history_;
    scene::CameraState camera_;
    std::int64_t frame_ = -1;
    std::uint32_t previousButtons_ = 0;
    std::string typed_;
    int clicks_ = 0;
    bool done_ = false, freePlay_ = false, commitPoint_ = false;
};

// Clicks, one frame at a time, whenever the dot it sees is near the reticle, and once early on
// when it is far from it (a miss); then waits half a second. Types now and then meanwhile:
// letters, multi-byte UTF-8 and Backspaces.
class ToyBot final : public Player {
public:
    FrameInput next(const ShownFrame& shown) override {
        FrameInput in;
        if (shown.frame % 7 == 1) in.text = "a";
        if (shown.frame % 11 == 2) in.text += "Zoë 日本";
        if (shown.frame % 13 == 3) in.text += std::string(1, kTextBackspace);
        const double x = shown.scene.objects.empty() ? 1e9 : shown.scene.objects.front().position.x - camera_.eye.x;
        const bool near = std::abs(x) < kRadius * 0.5 || shown.frame == 10;
        if (near && shown.time >= quietUntil_) {
            in.buttons = kButtonLeft;
            quietUntil_ = shown.time + 0.5;
        }
        return in;
    }

private:
    scene::CameraState camera_;
    double quietUntil_ = 0.0;
};

class ToyStudy final : public Study {
public:
    explicit ToyStudy(ToyProtocol p) : protocol_(std::move(p)) {}
    std::string game() const override { return kGameName; }
    std::string name() const override { return protocol_.name; }
    std::string protocolJson() const override {
        return nlohmann::json{{"game", kGameName},
                              {"name", protocol_.name},
                              {"refresh_hz", protocol_.refreshHz},
                              {"mode", protocol_.mode},
                              {"duration_s", protocol_.durationS}}
            .dump(2);
    }
    double refreshHz() const override { return protocol_.refreshHz; }
    std::unique_ptr<Game> newGame(std::uint64_t, const DisplaySize&) const override {
        return std::make_unique<ToyGame>(protocol_);
    }
    std::unique_ptr<FreePlayGame> newFreePlay(std::uint64_t, const DisplaySize&, const std::string& mode,
                                              int difficulty) const override {
        auto game = std::make_unique<ToyGame>(protocol_);
        game->switchTo(mode, difficulty);
        return game;
    }
    std::unique_ptr<Player> newBot(std::uint64_t, const DisplaySize&) const override {
        return std::make_unique<ToyBot>();
    }
    std::vector<std::string> modes() const override { return {protocol_.mode}; }
    const condition::ConditionTable& conditions() const override { return table_; }
    Instructions instructions() const override {
        Instructions i;
        i.task = "click while the sphere is under the reticle";
        return i;
    }
    bool warnsOnRefreshMismatch() const override { return true; }
    protocol::RenderSettings rendering() const override { return {}; }
    SessionResults results(const std::vector<session::EventRecord>& events) const override {
        SessionResults out;
        out.measure = {"toy hits", "clicks"};
        for (const auto& e : events) {
            if (e.type != "click") continue;
            ShotResult r;
            r.phase = e.phase;
            r.scoredPhase = true;
            r.trial = e.trial;
            r.mode = e.mode;
            r.outcome = e.displayedOutcome;
            r.worldOutcome = e.worldOutcome;
            r.displayedOutcome = e.displayedOutcome;
            r.hit = r.outcome == "hit";
            r.time = e.eventTime;
            out.shots.push_back(std::move(r));
        }
        return out;
    }
    // Clicks, of no planned number: the toy game runs for a time.
    Progress progress(const std::vector<session::EventRecord>& events) const override {
        return {"clicks", results(events).shots.size(), 0};
    }

private:
    ToyProtocol protocol_;
    condition::ConditionTable table_;  // the presets: a toy protocol defines none
};

std::unique_ptr<Study> parseToyStudy(const std::string& jsonText, const std::string& sourceName) {
    const auto j = nlohmann::json::parse(jsonText, nullptr, false);
    auto fail = [&](const std::string& what) {
        return protocol::ProtocolError("protocol '" + sourceName + "': " + what);
    };
    if (!j.is_object()) throw fail("not a JSON object");
    ToyProtocol p;
    p.name = j.value("name", std::string("toy"));
    p.refreshHz = j.value("refresh_hz", p.refreshHz);
    p.mode = j.value("mode", p.mode);
    p.durationS = j.value("duration_s", p.durationS);
    if (const std::string why = condition::ConditionTable().check(p.mode, p.refreshHz); !why.empty())
        throw fail("mode: " + why);
    if (!(p.durationS > 0.0)) throw fail("duration_s must be positive");
    return std::make_unique<ToyStudy>(std::move(p));
}

}  // namespace

void registerToyGame() {
    static const bool once = (registerGame(kGameName, parseToyStudy), true);
    (void)once;
}

std::string toyProtocol(const std::string& mode, double durationS) {
    // 120 Hz: every mode runs on it, warp15to120 included.
    return nlohmann::json{
        {"game", kGameName}, {"name", "toy-" + mode}, {"refresh_hz", 120}, {"mode", mode}, {"duration_s", durationS}}
        .dump();
}

}  // namespace warplab::game::toy
