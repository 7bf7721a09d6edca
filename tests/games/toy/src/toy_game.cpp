#include "toy_game.h"

#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

#include "game/random.h"

namespace warplab::toy {
namespace {

using game::kButtonLeft;

constexpr int kTagConditionOrder = 1;  // the seed's stream for the order of play.conditions

Dot dotAt(double t) { return {1.2 * std::sin(1.5 * t - 1.0), 1.8 * std::cos(1.5 * t - 1.0)}; }
bool underReticle(double x) { return std::abs(x) <= kRadius; }

}  // namespace

ToyGame::ToyGame(const ToyProtocol& p, std::uint64_t seed)
    : protocol_(p),
      order_(p.conditions),
      framesPerCondition_(std::llround(p.secondsPerCondition * p.refreshHz)),
      schedule_(p.conditionTable.at(p.conditions.front()), p.refreshHz),
      clickGate_(true) {
    if (p.shuffle) game::shuffle(order_, game::subSeed(seed, kTagConditionOrder, 0));
    startCondition(0, 0);
}

void ToyGame::startCondition(std::size_t index, std::int64_t atFrame) {
    current_ = index;
    schedule_ = condition::ConditionSchedule(protocol_.conditionTable.at(order_[index]), protocol_.refreshHz);
    scheduleStart_ = atFrame;
    clickGate_.clear();
}

game::ShownFrame ToyGame::step(const game::FrameInput& input) {
    ++frame_;
    commitPoint_ = false;
    const bool pressed = (input.buttons & kButtonLeft) && !(previousButtons_ & kButtonLeft);
    previousButtons_ = input.buttons;
    typed_ += input.text;
    const double now = static_cast<double>(frame_) / protocol_.refreshHz;
    if (frame_ == 0) emit("phase", {});
    history_.record(frame_, dotAt(now));

    // What the condition shows of the dot, through the two hooks.
    const game::SchedulePlacement placement{scheduleStart_, protocol_.refreshHz};
    const condition::ScheduledFrame f = schedule_.frame(frame_ - scheduleStart_);
    game::ShownFrame shown = game::scheduledShownFrame(frame_, schedule_.condition(), f, placement);
    const game::WorldDepiction d = game::depictWorld(schedule_.condition(), f, placement, game::WorldClock::Schedule);
    const Dot seen = *game::depictedState<Dot>(
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
        e.condition = schedule_.condition().name;
        e.worldOutcome = underReticle(dotAt(now).x) ? "hit" : "miss";
        e.displayedOutcome = underReticle(seen.x) ? "hit" : "miss";
        // Everything typed so far, as typed (Backspaces kept): replay, and a resumed
        // session's re-simulation, reproduce it only from the input record's text.
        e.detailJson = nlohmann::json{{"shown_x", seen.x}, {"typed", typed_}, {"x", dotAt(now).x}}.dump();
        shown.feedback = e.displayedOutcome;
        emit(e);
        commitPoint_ = true;
    }
    if (!freePlay_ && frame_ + 1 - scheduleStart_ >= framesPerCondition_) {
        if (current_ + 1 < order_.size()) {
            startCondition(current_ + 1, frame_ + 1);
            commitPoint_ = true;
        } else {
            done_ = true;
            emit("phase", {});
        }
    }
    return shown;
}

session::FrameRecord ToyGame::frameRecord(const game::ShownFrame& shown) const {
    session::FrameRecord r = game::frameRecordOf(shown);
    r.detailJson = nlohmann::json{{"x", shown.scene.objects.front().position.x}}.dump();
    return r;
}

game::PointerProbe ToyGame::probePointer(const game::ShownFrame& shown) const {
    const double x = shown.scene.objects.front().position.x - camera_.eye.x;
    return {underReticle(x) ? scene::kIdTarget : scene::kIdNone, std::abs(std::abs(x) - kRadius) / kDistance};
}

std::optional<std::uint32_t> ToyGame::displayedObject(const session::EventRecord& e) const {
    if (e.type != "click") return std::nullopt;
    return e.displayedOutcome == "hit" ? scene::kIdTarget : scene::kIdNone;
}

void ToyGame::switchTo(const std::string& condition, int) {
    order_ = {condition};
    startCondition(0, frame_ + 1);
    freePlay_ = true;
}

void ToyGame::emit(const char* type, session::EventRecord e) {
    e.type = type;
    emit(e);
}

void ToyGame::emit(session::EventRecord e) {
    e.frame = frame_;
    e.eventTime = static_cast<double>(frame_) / protocol_.refreshHz;
    e.phase = phase();
    events_.push(std::move(e));
}

game::FrameInput ToyBot::next(const game::ShownFrame& shown) {
    game::FrameInput in;
    if (shown.frame % 7 == 1) in.text = "a";
    if (shown.frame % 11 == 2) in.text += "Zoë 日本";
    if (shown.frame % 13 == 3) in.text += std::string(1, game::kTextBackspace);
    const double x = shown.scene.objects.empty() ? 1e9 : shown.scene.objects.front().position.x - camera_.eye.x;
    const bool near = std::abs(x) < kRadius * 0.5 || shown.frame == 10;
    if (near && shown.time >= quietUntil_) {
        in.buttons = kButtonLeft;
        quietUntil_ = shown.time + 0.5;
    }
    return in;
}

}  // namespace warplab::toy
