#include "discrimination_game.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <nlohmann/json.hpp>

#include "game/random.h"
#include "physics/ray.h"
#include "scene/camera.h"
#include "scene/hangar_layout.h"

namespace warplab::discrimination {
namespace {

constexpr double kMaxPitch = 1.5;  // radians, ~86 degrees: the view never flips over
// The seed's streams: which interval is the test's, and the target's path of each trial.
constexpr int kTagOrder = 1, kTagMotion = 2;

// The question after each trial: which of the two intervals, by digit key or click.
protocol::Question choiceQuestion(const std::string& prompt) {
    protocol::Question q;
    q.id = "interval";
    q.kind = protocol::QuestionKind::Choice;
    q.prompt = prompt;
    q.options = {"the first", "the second"};
    return q;
}

}  // namespace

std::string intervalText(int interval) { return "Interval " + std::to_string(interval) + " of 2"; }

DiscriminationGame::DiscriminationGame(const DiscriminationProtocol& protocol, std::uint64_t seed,
                                       const game::DisplaySize& display)
    : protocol_(protocol),
      seed_(seed),
      display_(display),
      block_(
          [&] {
              std::vector<adaptive::ProcedureSettings> settings;
              for (const ProcedureSpec& spec : protocol.procedures)
                  settings.push_back(procedureSettings(protocol, spec));
              return settings;
          }(),
          seed),
      question_({choiceQuestion(protocol.question)}, protocol.refreshHz, display, /*legacyLayout=*/false) {
    using L = scene::HangarLayout;
    restingCamera_.eye = {L::kEyeX, L::kEyeY, L::kEyeZ};
    restingCamera_.verticalFovDeg = static_cast<float>(protocol.verticalFovDeg);
    plane_ = physics::fitTargetPlane(restingCamera_, display.aspect(), protocol.targetRadius);
    camera_ = restingCamera_;
}

std::string DiscriminationGame::phase() const {
    switch (stage_) {
        case Stage::Reading: return "instructions";
        case Stage::Done: return "done";
        default: return freePlay_ ? "free_play" : "test";
    }
}

std::int64_t DiscriminationGame::frames(double seconds) const { return std::llround(seconds * protocol_.refreshHz); }

void DiscriminationGame::emit(session::EventRecord event) {
    event.frame = frame_;
    event.phase = phase();
    event.eventTime = now();
    events_.push(std::move(event));
}

void DiscriminationGame::switchTo(const std::string& condition, int) {
    condition::ConditionSchedule(protocol_.conditionTable.at(condition), protocol_.refreshHz);  // throws first
    freePlay_ = true;
    trial_.reset();
    Trial t;
    t.test = protocol_.conditionTable.at(condition);
    t.motion = physics::spawnTarget(plane_, protocol_.targetSpeed, game::subSeed(seed_, kTagMotion, -1));
    trial_ = t;
    stage_ = Stage::Interval;
    interval_ = 0;  // the free-play interval: the condition named, without end
    stageStart_ = spawnFrame_ = scheduleStart_ = frame_ + 1;
    schedule_.emplace(t.test, protocol_.refreshHz, game::pacingSeed(seed_, scheduleStart_));
}

void DiscriminationGame::startTrial() {
    const std::optional<std::size_t> procedure = block_.nextProcedure();
    if (!procedure) {
        stage_ = Stage::Done;
        session::EventRecord done;
        done.type = "done";
        done.detailJson = nlohmann::json{{"trials", trials_}}.dump();
        emit(done);
        commitPoint_ = true;
        return;
    }
    const adaptive::Procedure& p = block_.procedure(*procedure);
    Trial t;
    t.index = trials_;
    t.procedure = *procedure;
    t.procedureTrial = static_cast<int>(p.trials());
    t.level = p.next();
    t.test = testCondition(protocol_, protocol_.procedures[*procedure], t.level);
    t.testInterval = game::Random(game::subSeed(seed_, kTagOrder, t.index)).uniform() < 0.5 ? 1 : 2;
    t.motion = physics::spawnTarget(plane_, protocol_.targetSpeed, game::subSeed(seed_, kTagMotion, t.index));
    trial_ = t;
    beginInterval(1);
}

void DiscriminationGame::beginInterval(int interval) {
    stage_ = Stage::Interval;
    interval_ = interval;
    stageStart_ = spawnFrame_ = scheduleStart_ = frame_;
    recentre_ = true;  // both intervals start from the same view: only the condition differs
    const ProcedureSpec& spec = protocol_.procedures[trial_->procedure];
    const condition::Condition& shown =
        interval == trial_->testInterval ? trial_->test : protocol_.conditionTable.at(spec.reference);
    // Every interval starts its condition's schedule afresh (DESIGN: switching conditions starts clean).
    schedule_.emplace(shown, protocol_.refreshHz, game::pacingSeed(seed_, scheduleStart_));
}

void DiscriminationGame::beginBlank(bool afterAnswer) {
    stage_ = Stage::Blank;
    stageStart_ = frame_;
    // The view rests from here, so that a lagged interval's first frames, which show the camera
    // of frames before it, show the resting view as the other interval's do.
    camera_ = restingCamera_;
    interval_ = 0;
    afterAnswer_ = afterAnswer;
    if (frames(protocol_.blankS) == 0) advanceStage();
}

void DiscriminationGame::advanceStage() {
    switch (stage_) {
        case Stage::Interval:
            if (interval_ == 1) return beginBlank(false);
            stage_ = Stage::Question;
            stageStart_ = frame_;
            interval_ = 0;
            // Above both answers' boxes (they lie in the lower half), under the status line.
            cursor_ = {display_.width * 0.5, display_.height * 0.25};
            question_.open(frame_ - 1);
            return;
        case Stage::Blank:
            if (afterAnswer_) return startTrial();
            return beginInterval(2);
        case Stage::Reading:
        case Stage::Question:
        case Stage::Done: return;
    }
}

std::optional<glm::dvec3> DiscriminationGame::targetAt(std::int64_t frame) const {
    // The target's path runs before the interval too, so that a lagged interval shows it from
    // its first frame where it was: appearing late would be a cue other than responsiveness.
    if (!trial_) return std::nullopt;
    const double t = static_cast<double>(frame - spawnFrame_) / protocol_.refreshHz;
    return glm::dvec3(physics::positionAt(plane_, trial_->motion, t), plane_.z);
}

std::optional<glm::dvec3> DiscriminationGame::displayedTarget(const condition::ScheduledFrame& f) const {
    struct Target {
        glm::dvec3 position, velocity;
    };
    auto at = [&](std::int64_t frame) -> std::optional<Target> {
        const auto p = targetAt(frame);
        if (!p) return std::nullopt;
        const double t = static_cast<double>(frame - spawnFrame_) / protocol_.refreshHz;
        return Target{*p, glm::dvec3(physics::velocityAt(plane_, trial_->motion, t), 0.0)};
    };
    auto move = [](Target t, double dt) {
        t.position += t.velocity * dt;
        return t;
    };
    auto blend = [](const Target& a, const Target& b, double weight, double) {
        return Target{a.position + (b.position - a.position) * weight, a.velocity};
    };
    const game::WorldDepiction d =
        game::depictWorld(schedule_->condition(), f, {scheduleStart_, protocol_.refreshHz}, game::WorldClock::Session);
    const auto shown = game::depictedState<Target>(d, at, move, blend);
    if (!shown) return std::nullopt;
    return shown->position;
}

game::ShownFrame DiscriminationGame::intervalFrame(const game::FrameInput& input) {
    if (std::exchange(recentre_, false)) camera_ = restingCamera_;
    const double sensitivity = protocol_.mouseRadiansPerCount;
    camera_.yaw = static_cast<float>(camera_.yaw + input.mouseDx * sensitivity);
    camera_.pitch = static_cast<float>(std::clamp(camera_.pitch - input.mouseDy * sensitivity, -kMaxPitch, kMaxPitch));
    cameraHistory_.record(frame_, camera_);

    const game::SchedulePlacement placement{scheduleStart_, protocol_.refreshHz};
    const condition::ScheduledFrame f = schedule_->frame(frame_ - scheduleStart_);
    game::ShownFrame shown = game::scheduledShownFrame(frame_, schedule_->condition(), f, placement);
    shown.camera = cameraHistory_.at(game::cameraFrame(f, placement));
    const double t = shown.scene.time - static_cast<double>(spawnFrame_) / protocol_.refreshHz;
    if (const auto p = displayedTarget(f)) {
        scene::ObjectState target = physics::targetObject(plane_, trial_->motion, t, protocol_.targetRadius);
        target.position = glm::vec3(*p);
        shown.scene.objects.push_back(target);
    }
    if (f.rendersNow) {
        shown.render.camera = camera_;
        shown.render.scene.time = now();
        const double age = static_cast<double>(frame_ - spawnFrame_) / protocol_.refreshHz;
        shown.render.scene.objects.push_back(
            physics::targetObject(plane_, trial_->motion, age, protocol_.targetRadius));
    }
    shown.phaseText = interval_ == 0 ? "Free play: " + schedule_->condition().name : intervalText(interval_);
    return shown;
}

game::ShownFrame DiscriminationGame::questionFrame(const game::FrameInput& input) {
    cameraHistory_.record(frame_, camera_);
    const bool click = (input.buttons & game::kButtonLeft) && !(previousButtons_ & game::kButtonLeft);
    const std::uint32_t pressed = input.keys & ~previousKeys_;
    cursor_ = glm::clamp(cursor_ + glm::dvec2(input.mouseDx, input.mouseDy) * kQuestionCursorPixelsPerCount,
                         glm::dvec2(0.0), glm::dvec2(display_.width, display_.height));
    game::ShownFrame shown = game::screenShownFrame(frame_, now(), camera_, game::PointerKind::Cursor, cursor_);
    shown.question = question_.prompt(cursor_);
    shown.phaseText = "Trial " + std::to_string(trials_ + 1);
    if (const auto a = question_.step(frame_, *shown.question, pressed, click, input.text)) answer(*a);
    return shown;
}

void DiscriminationGame::answer(const game::Answer& a) {
    const Trial& t = *trial_;
    const ProcedureSpec& spec = protocol_.procedures[t.procedure];
    const int chosen = a.value.value_or(0);
    // The better interval is the reference's: the test is worse by its stimulus.
    const bool correct = chosen != 0 && chosen != t.testInterval;
    const double reference = referenceLevel(protocol_, spec);
    session::EventRecord event;
    event.type = "judgement";
    event.trial = t.index;
    event.condition = spec.reference;
    event.detailJson = nlohmann::json{
        {"procedure", spec.name},
        {"procedure_trial", t.procedureTrial},
        {"dimension", condition::dimensionName(spec.dimension)},
        {"level", spec.levels[t.level]},
        {"stimulus", condition::stimulusOf(spec.dimension, reference, spec.levels[t.level])},
        {"test_condition", t.test.name},
        {"test_interval", t.testInterval},
        {"answer", chosen},
        {"correct", correct},
        {"answered_with", a.answeredWith},
        {"answer_s",
         a.answerS}}.dump();
    event.worldOutcome = event.displayedOutcome = correct ? "correct" : "wrong";
    emit(event);
    block_.answer(correct);
    ++trials_;
    commitPoint_ = true;
    beginBlank(true);
}

game::ShownFrame DiscriminationGame::step(const game::FrameInput& input) {
    ++frame_;
    commitPoint_ = false;
    const bool enter = (input.keys & game::kKeyEnter) && !(previousKeys_ & game::kKeyEnter);
    if (frame_ == 0 && !freePlay_ && protocol_.instructions.empty()) startTrial();
    // A stage whose time is up gives way to the next from this frame.
    if (stage_ == Stage::Interval && interval_ != 0 && frame_ - stageStart_ >= frames(protocol_.intervalS))
        advanceStage();
    else if (stage_ == Stage::Blank && frame_ - stageStart_ >= frames(protocol_.blankS))
        advanceStage();

    game::ShownFrame shown;
    if (stage_ == Stage::Reading) {
        cameraHistory_.record(frame_, camera_);
        shown = game::screenShownFrame(frame_, now(), camera_, game::PointerKind::None);
        shown.instructions = protocol_.instructions;
        shown.phaseText = "Press Enter when you have read this";
        shown.promptsEnter = true;
        if (enter && frame_ > 0) {  // a press made while the text is up
            session::EventRecord event;
            event.type = "instructions";
            event.detailJson = nlohmann::json{{"read_s", now()}}.dump();
            emit(event);
            commitPoint_ = true;
            beginBlank(true);
        }
    } else if (stage_ == Stage::Interval) {
        shown = intervalFrame(input);
    } else if (stage_ == Stage::Question) {
        shown = questionFrame(input);
    } else {
        cameraHistory_.record(frame_, camera_);
        shown = game::screenShownFrame(frame_, now(), camera_, game::PointerKind::None);
        shown.blank = true;
        shown.phaseText = stage_ == Stage::Done ? "Thank you" : "";
    }
    previousKeys_ = input.keys;
    previousButtons_ = input.buttons;
    return shown;
}

game::PointerProbe DiscriminationGame::probePointer(const game::ShownFrame& shown) const {
    game::PointerProbe probe;
    if (shown.scene.objects.empty()) return probe;
    const glm::dvec3 eye(shown.camera.eye);
    const glm::dvec3 aim(scene::forwardDirection(shown.camera.yaw, shown.camera.pitch));
    const glm::dvec3 centre(shown.scene.objects.front().position);
    const double angularRadius = std::asin(std::min(1.0, protocol_.targetRadius / glm::length(centre - eye)));
    const double offAxis = physics::angleBetweenRayAndPoint(eye, aim, centre);
    probe.objectId = offAxis <= angularRadius ? scene::kIdTarget : scene::kIdNone;
    probe.silhouetteMarginRad = std::abs(offAxis - angularRadius);
    return probe;
}

session::FrameRecord DiscriminationGame::frameRecord(const game::ShownFrame& shown) const {
    session::FrameRecord r = game::frameRecordOf(shown);
    if (!shown.scene.objects.empty()) {
        const auto& p = shown.scene.objects.front().position;
        r.detailJson = nlohmann::json{{"target", {p.x, p.y, p.z}}}.dump();
    }
    return r;
}

}  // namespace warplab::discrimination
