#include "shooter_game.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "game/random.h"
#include "physics/ray.h"
#include "scene/camera.h"
#include "scene/hangar_layout.h"

namespace warplab::game {
namespace {

constexpr double kMaxPitch = 1.5;  // radians, ~86 degrees: the view never flips over

// Event details are JSON objects with sorted keys (nlohmann::json is map-backed), written
// with shortest round-trip numbers: the same values give the same text, which is what lets a
// version-1 session, whose shooter columns the store folds into the same keys, replay.
std::string detailText(const nlohmann::json& detail) { return detail.dump(); }

}  // namespace

const char* phaseName(Phase phase) {
    switch (phase) {
        case Phase::Acclimation: return "acclimation";
        case Phase::Training: return "training";
        case Phase::AwaitingSupervisor: return "awaiting_supervisor";
        case Phase::Test: return "test";
        case Phase::Done: return "done";
    }
    return "?";
}

const char* outcomeName(Outcome outcome) {
    switch (outcome) {
        case Outcome::None: return "";
        case Outcome::Hit: return "hit";
        case Outcome::Miss: return "miss";
        case Outcome::Timeout: return "timeout";
    }
    return "?";
}

ShooterGame::ShooterGame(const protocol::ShooterProtocol& protocol, std::uint64_t seed, const DisplaySize& display)
    : protocol_(protocol),
      seed_(seed),
      clickGate_(protocol.clickTiming == protocol::ClickTiming::InputReads),
      questions_(protocol.questions, protocol.refreshHz, display, /*legacyLayout=*/false),
      display_(display) {
    const double aspect = display.aspect();
    using L = scene::HangarLayout;
    restingCamera_.eye = {L::kEyeX, L::kEyeY, L::kEyeZ};
    restingCamera_.verticalFovDeg = static_cast<float>(protocol.verticalFovDeg);
    plane_ = physics::fitTargetPlane(restingCamera_, aspect, protocol.targetRadius);
    camera_ = restingCamera_;
    condition_ = protocol.acclimationCondition;
    schedule_.emplace(protocol.conditionTable.at(condition_), protocol.refreshHz, pacingSeed(seed, scheduleStart_));
}

std::optional<ShooterGame::TrialView> ShooterGame::currentTrial() const {
    if (!trial_) return std::nullopt;
    return TrialView{static_cast<double>(trial_->spawnFrame) / protocol_.refreshHz, trial_->motion, trial_->condition};
}

void ShooterGame::switchTo(const std::string& condition, int difficulty) {
    condition::ConditionSchedule(
        protocol_.conditionTable.at(condition),
        protocol_.refreshHz);  // throws for a condition this display cannot run, before anything changes
    freePlay_ = true;
    freeCondition_ = condition;
    freeLevel_ = std::max(0, difficulty);
    // The practice phase, endless: the next frame starts a fresh target in the new condition.
    phase_ = Phase::Acclimation;
    trial_.reset();
    frozenFrame_.reset();
    banner_.clear();
    if (frame_ >= 0) pauseUntil_ = frame_ + 1;  // before the first frame, the first frame starts it
}

bool ShooterGame::isOutcome(const session::EventRecord& e) const { return e.type == "shot" || e.type == "timeout"; }

std::optional<std::uint32_t> ShooterGame::displayedObject(const session::EventRecord& e) const {
    if (e.type != "shot") return std::nullopt;
    return e.displayedOutcome == "hit" ? scene::kIdTarget : scene::kIdNone;
}

PointerProbe ShooterGame::probePointer(const ShownFrame& shown) const {
    PointerProbe probe;
    if (shown.scene.objects.empty()) return probe;
    const glm::dvec3 eye(shown.camera.eye);
    const glm::dvec3 aim(scene::forwardDirection(shown.camera.yaw, shown.camera.pitch));
    const glm::dvec3 centre(shown.scene.objects.front().position);
    const double distance = glm::length(centre - eye);
    const double angularRadius = std::asin(std::min(1.0, protocol_.targetRadius / distance));
    const double offAxis = physics::angleBetweenRayAndPoint(eye, aim, centre);
    probe.objectId = offAxis <= angularRadius ? scene::kIdTarget : scene::kIdNone;
    probe.silhouetteMarginRad = std::abs(offAxis - angularRadius);
    return probe;
}

std::vector<session::EventRecord> ShooterGame::takeEvents() { return events_.take(); }

void ShooterGame::emit(session::EventRecord event) {
    event.frame = frame_;
    event.phase = phaseName(phase_);
    events_.push(std::move(event));
}

double ShooterGame::speedFor(int level) const {
    return protocol_.training.baseSpeed * std::pow(2.0, level / 6.0);  // seed 004 eq. 12
}

std::uint64_t ShooterGame::trialSeed(int phaseTag, int index) const { return subSeed(seed_, phaseTag, index); }

bool ShooterGame::timedOut(const Trial& trial) const {
    if (protocol_.legacyRules) {
        // Format 1: seconds compared after division, so rounding made the trial last N or
        // N + 1 frames. Kept so that version-1 sessions replay as they were recorded.
        return now() - static_cast<double>(trial.spawnFrame) / protocol_.refreshHz >= protocol_.timeoutS;
    }
    return frame_ - trial.spawnFrame >= std::llround(protocol_.timeoutS * protocol_.refreshHz);
}

std::optional<glm::dvec3> ShooterGame::targetAt(double time) const {
    if (!trial_) return std::nullopt;
    const double spawn = static_cast<double>(trial_->spawnFrame) / protocol_.refreshHz;
    if (time < spawn) return std::nullopt;
    const glm::dvec2 p = physics::positionAt(plane_, trial_->motion, time - spawn);
    return glm::dvec3(p, plane_.z);
}

std::optional<glm::dvec3> ShooterGame::displayedTarget(const condition::ScheduledFrame& f) const {
    const double refresh = protocol_.refreshHz;
    // The target at a session frame: where it is, and the velocity a warp moves it on by.
    struct Target {
        glm::dvec3 position;
        glm::dvec3 velocity;
    };
    auto at = [&](std::int64_t frame) -> std::optional<Target> {
        const double time = static_cast<double>(frame) / refresh;
        const auto p = targetAt(time);
        if (!p) return std::nullopt;
        const double spawn = static_cast<double>(trial_->spawnFrame) / refresh;
        return Target{*p, glm::dvec3(physics::velocityAt(plane_, trial_->motion, time - spawn), 0.0)};
    };
    auto move = [](Target t, double dt) {
        t.position = t.position + t.velocity * dt;
        return t;
    };
    auto blend = [](const Target& before, const Target& after, double weight, double) {
        return Target{before.position + (after.position - before.position) * weight, before.velocity};
    };
    const WorldDepiction d = depictWorld(schedule_->condition(), f, {scheduleStart_, refresh}, WorldClock::Session);
    const auto shown = depictedState<Target>(d, at, move, blend);
    if (!shown) return std::nullopt;
    return shown->position;
}

void ShooterGame::beginPhase(Phase phase) {
    phase_ = phase;
    phaseStartFrame_ = frame_;
    trialsInPhase_ = 0;
    commitPoint_ = true;
    // Targets spawn in the resting view; a participant who ended acclimation or training looking
    // at the ceiling would begin the next phase facing away from them. From format 7 the view
    // is the resting one again from the phase's next frame (and from a resumed session's
    // first, resumeHere): a rule of the game, so that replay sees it as the window did.
    recentre_ = protocol_.formatVersion >= protocol::kShooterRecentresSince &&
        (phase == Phase::Training || phase == Phase::Test);
    session::EventRecord event;
    event.type = "phase";
    event.eventTime = now();
    event.detailJson = detailText({{"difficulty", phase == Phase::Test ? testLevel_ : level_}});
    emit(event);
    switch (phase) {
        case Phase::Acclimation:
            if (protocol_.acclimationS <= 0.0 && !freePlay_) return beginPhase(Phase::AwaitingSupervisor);
            return openPhase(protocol_.acclimationInstructions);
        case Phase::Training: {
            level_ = protocol_.training.startLevel;
            missedYet_ = false;
            shotsPerCondition_ = protocol_.training.shotsPerLevelEasy;
            levelQueue_.clear();
            return openPhase(protocol_.trainingInstructions);
        }
        case Phase::AwaitingSupervisor:
            // Appendix B: after the practice the supervisor's Enter begins the recorded
            // experiment (training, then the test).
            if (!protocol_.supervisorStartsTest) return beginPhase(Phase::Training);
            return;
        case Phase::Test: {
            testQueue_.clear();
            for (int i = 0; i < protocol_.targetsPerCondition; ++i)
                for (const auto& c : protocol_.conditions) testQueue_.push_back(c);
            if (protocol_.interleaveConditions)
                shuffle(testQueue_, trialSeed(7, 0));
            else
                std::stable_sort(testQueue_.begin(), testQueue_.end(), [&](const std::string& a, const std::string& b) {
                    return std::find(protocol_.conditions.begin(), protocol_.conditions.end(), a) <
                        std::find(protocol_.conditions.begin(), protocol_.conditions.end(), b);
                });
            testNext_ = 0;
            return openPhase(protocol_.testInstructions);
        }
        case Phase::Done: return;
    }
}

void ShooterGame::resumeHere() { recentre_ = protocol_.formatVersion >= protocol::kShooterRecentresSince; }

void ShooterGame::openPhase(const std::string& instructions) {
    if (instructions.empty() || freePlay_) return scheduleNextTrial();
    reading_ = true;
}

void ShooterGame::finishReading() {
    reading_ = false;
    session::EventRecord event;
    event.type = "instructions";
    event.eventTime = now();
    event.detailJson = detailText({{"read_s", static_cast<double>(frame_ - phaseStartFrame_) / protocol_.refreshHz}});
    emit(event);
    commitPoint_ = true;
    phaseStartFrame_ = frame_;  // the phase's time limits count from here
    scheduleNextTrial();
}

ShownFrame ShooterGame::readingFrame() const {
    ShownFrame shown = screenShownFrame(frame_, now(), camera_, PointerKind::None);
    shown.instructions = phase_ == Phase::Acclimation ? protocol_.acclimationInstructions
        : phase_ == Phase::Training                   ? protocol_.trainingInstructions
                                                      : protocol_.testInstructions;
    shown.phaseText = "Press Enter when you have read this";
    shown.promptsEnter = true;
    return shown;
}

void ShooterGame::startTrial(const std::string& condition, int level) {
    Trial t;
    t.index = trialsInPhase_++;
    t.condition = condition;
    t.level = level;
    t.speed = speedFor(level);
    t.spawnFrame = frame_;
    t.motion = physics::spawnTarget(plane_, t.speed, trialSeed(static_cast<int>(phase_), t.index));
    trial_ = t;
    // Every trial starts its condition's schedule afresh (DESIGN: switching conditions starts clean).
    condition_ = condition;
    scheduleStart_ = frame_;
    schedule_.emplace(protocol_.conditionTable.at(condition), protocol_.refreshHz, pacingSeed(seed_, scheduleStart_));
}

void ShooterGame::finishTrainingLevel() {
    const double lowHit = levelShots_[0] ? double(levelHits_[0]) / levelShots_[0] : 1.0;
    const double highMiss = levelShots_[1] ? 1.0 - double(levelHits_[1]) / levelShots_[1] : 0.0;
    session::EventRecord event;
    event.type = "level";
    event.eventTime = now();
    event.detailJson = detailText({{"difficulty", level_},
                                   {"target_speed", speedFor(level_)},
                                   {"low_mode", protocol_.training.lowCondition},
                                   {"low_hit_rate", lowHit},
                                   {"high_mode", protocol_.training.highCondition},
                                   {"high_miss_rate", highMiss},
                                   {"shots_per_mode", shotsPerCondition_}});
    emit(event);
    commitPoint_ = true;
    // Stop where the fast condition's misses outnumber the slow condition's hits (seed 004 Figure 31).
    if (levelShots_[0] > 0 && highMiss > lowHit) {
        testLevel_ = level_;
        return beginPhase(Phase::Test);
    }
    if (levelHits_[0] < levelShots_[0] || levelHits_[1] < levelShots_[1]) missedYet_ = true;
    if (level_ >= protocol_.training.maxLevel) {
        testLevel_ = level_;
        return beginPhase(Phase::Test);
    }
    ++level_;
    // Few shots per level while everything is hit, more once rates start to drop.
    shotsPerCondition_ = missedYet_ ? protocol_.training.shotsPerLevelHard : protocol_.training.shotsPerLevelEasy;
}

void ShooterGame::scheduleNextTrial() {
    const double elapsed = static_cast<double>(frame_ - phaseStartFrame_) / protocol_.refreshHz;
    switch (phase_) {
        case Phase::Acclimation:
            if (freePlay_) return startTrial(freeCondition_, freeLevel_);
            if (elapsed >= protocol_.acclimationS) return beginPhase(Phase::AwaitingSupervisor);
            return startTrial(protocol_.acclimationCondition, protocol_.acclimationLevel);
        case Phase::Training: {
            const bool levelDone = levelQueue_.empty() && levelShots_[0] + levelShots_[1] > 0;
            // Format 2 judges a finished level before stopping for time; format 1 stopped
            // first and so started the test one level too low (kept for its replays).
            if (levelDone && !protocol_.legacyRules) {
                finishTrainingLevel();
                if (phase_ != Phase::Training) return;
            }
            if (elapsed >= protocol_.training.timeLimitS) {
                testLevel_ = level_;
                session::EventRecord event;
                event.type = "training_limit";
                event.eventTime = now();
                event.detailJson = detailText({{"difficulty", level_}});
                emit(event);
                return beginPhase(Phase::Test);
            }
            if (levelQueue_.empty()) {
                if (levelDone && protocol_.legacyRules) {
                    finishTrainingLevel();
                    if (phase_ != Phase::Training) return;
                }
                levelHits_[0] = levelHits_[1] = levelShots_[0] = levelShots_[1] = 0;
                for (int i = 0; i < shotsPerCondition_; ++i) {
                    levelQueue_.push_back(protocol_.training.lowCondition);
                    levelQueue_.push_back(protocol_.training.highCondition);
                }
                shuffle(levelQueue_, trialSeed(8, level_));
                levelTrials_ = levelQueue_.size();
            }
            const std::string condition = levelQueue_.back();
            levelQueue_.pop_back();
            return startTrial(condition, level_);
        }
        case Phase::Test:
            if (testNext_ >= testQueue_.size()) return beginPhase(Phase::Done);
            return startTrial(testQueue_[testNext_++], testLevel_);
        case Phase::AwaitingSupervisor:
        case Phase::Done: return;
    }
}

void ShooterGame::finishTrial(Outcome world, Outcome displayed, double shotTime, double angularErrorDeg) {
    const Trial& t = *trial_;
    const double spawn = static_cast<double>(t.spawnFrame) / protocol_.refreshHz;
    session::EventRecord event;
    event.type = world == Outcome::Timeout ? "timeout" : "shot";
    event.trial = t.index;
    event.condition = t.condition;
    event.eventTime = shotTime;
    event.worldOutcome = outcomeName(world);
    event.displayedOutcome = outcomeName(displayed);
    event.detailJson = detailText(
        {{"difficulty", t.level},
         {"target_speed", t.speed},
         {"spawn_time", spawn},
         {"aim_time", shotTime - spawn},
         {"angular_error_deg", angularErrorDeg},
         {"scored", protocol_.scoring == protocol::Scoring::World ? outcomeName(world) : outcomeName(displayed)},
         {"start_x", t.motion.start.x},
         {"start_y", t.motion.start.y},
         {"velocity_x", t.motion.velocity.x},
         {"velocity_y", t.motion.velocity.y},
         {"plane_z", plane_.z}});
    emit(event);

    const Outcome scored = protocol_.scoring == protocol::Scoring::World ? world : displayed;
    banner_ = scored == Outcome::Hit ? "HIT" : (scored == Outcome::Timeout ? "TIMEOUT" : "MISS");
    if (phase_ == Phase::Training) {
        const int which = t.condition == protocol_.training.lowCondition ? 0 : 1;
        ++levelShots_[which];
        levelHits_[which] += scored == Outcome::Hit;
    }
    trial_.reset();
    commitPoint_ = true;
    pauseUntil_ = frame_ + 1 + std::llround(protocol_.pauseS * protocol_.refreshHz);
    if (phase_ != Phase::Test || questions_.empty()) return;
    // The trial just ended is testQueue_[testNext_ - 1]; a block ends with the test, or where
    // blocked conditions change.
    const bool lastOfBlock = testNext_ >= testQueue_.size() ||
        (!protocol_.interleaveConditions && testQueue_[testNext_] != testQueue_[testNext_ - 1]);
    if (!lastOfBlock) return;
    questionsDue_ = true;
    blockCondition_ = protocol_.interleaveConditions ? "" : testQueue_[testNext_ - 1];
}

ShownFrame ShooterGame::questionFrame(const FrameInput& input) {
    cameraHistory_.record(frame_, camera_);  // the view stays where the block left it
    const bool click = (input.buttons & kButtonLeft) && !(previousButtons_ & kButtonLeft);
    const std::uint32_t pressed = input.keys & ~previousKeys_;
    previousButtons_ = input.buttons;
    previousKeys_ = input.keys;
    const glm::dvec2 moved = questionCursor_ + glm::dvec2(input.mouseDx, input.mouseDy) * kQuestionCursorPixelsPerCount;
    questionCursor_ = glm::clamp(moved, glm::dvec2(0.0), glm::dvec2(display_.width, display_.height));
    ShownFrame shown = screenShownFrame(frame_, now(), camera_, PointerKind::Cursor, questionCursor_);
    shown.question = questions_.prompt(questionCursor_);
    const int blocks = protocol_.interleaveConditions ? 1 : static_cast<int>(protocol_.conditions.size());
    shown.phaseText = "Test: block " + std::to_string(block_ + 1) + " of " + std::to_string(blocks) +
        " done. About the block you just played";
    if (const auto a = questions_.step(frame_, *shown.question, pressed, click, input.text)) {
        session::EventRecord event;
        event.type = "answer";
        event.trial = block_;
        event.condition = blockCondition_;
        event.eventTime = now();
        event.detailJson = questions_.answerDetail(*a).dump();
        emit(event);
        commitPoint_ = true;
        if (questions_.answeredAll()) {
            asking_ = false;
            ++block_;
            pauseUntil_ = frame_ + 1;  // the next frame goes on as after a trial's pause
        }
    }
    return shown;
}

void ShooterGame::openQuestionsIfDue() {
    if (!questionsDue_ || frame_ < pauseUntil_) return;
    // The block's last pause is over: its questions, from this frame.
    questionsDue_ = false;
    asking_ = true;
    pauseUntil_ = -1;
    frozenFrame_.reset();
    banner_.clear();
    // At the middle the cursor lay on the Likert row's middle box, lit as if chosen: from
    // format 7 it starts above every answer's box (they lie in the lower half), under the
    // status line.
    questionCursor_ = {display_.width * 0.5,
                       display_.height * (protocol_.formatVersion >= protocol::kShooterRecentresSince ? 0.25 : 0.5)};
    questions_.open(frame_ - 1);
}

void ShooterGame::turnCamera(const FrameInput& input) {
    const double sensitivity = protocol_.mouseRadiansPerCount;
    if (std::exchange(recentre_, false)) {
        camera_.yaw = restingCamera_.yaw;
        camera_.pitch = restingCamera_.pitch;
    }
    camera_.yaw = static_cast<float>(camera_.yaw + input.mouseDx * sensitivity);
    camera_.pitch = static_cast<float>(std::clamp(camera_.pitch - input.mouseDy * sensitivity, -kMaxPitch, kMaxPitch));
    cameraHistory_.record(frame_, camera_);
}

ShownFrame ShooterGame::frozenShownFrame() const {
    ShownFrame shown = *frozenFrame_;
    shown.frame = frame_;
    shown.inputFrame = frame_;  // the banner answers the shot at once, whatever the condition's lag
    shown.time = now();
    shown.frozen = true;
    shown.rendersNow = false;
    shown.banner = banner_;
    shown.bannerGood = banner_ == "HIT";
    return shown;
}

ShownFrame ShooterGame::scheduledFrame(const condition::ScheduledFrame& f) const {
    const double refresh = protocol_.refreshHz;
    const SchedulePlacement placement{scheduleStart_, refresh};
    ShownFrame shown = scheduledShownFrame(frame_, schedule_->condition(), f, placement);
    shown.camera = cameraHistory_.at(cameraFrame(f, placement));
    if (const auto p = displayedTarget(f)) {
        // Position as the frame depicts it; velocity the world's at that instant.
        const double spawn = static_cast<double>(trial_->spawnFrame) / refresh;
        scene::ObjectState target = physics::targetObject(
            plane_, trial_->motion, std::max(0.0, shown.scene.time - spawn), protocol_.targetRadius);
        target.position = glm::vec3(*p);
        shown.scene.objects.push_back(target);
    }
    if (f.rendersNow) {
        shown.render.camera = camera_;
        shown.render.scene.time = now();
        if (trial_) {
            const double spawn = static_cast<double>(trial_->spawnFrame) / refresh;
            shown.render.scene.objects.push_back(
                physics::targetObject(plane_, trial_->motion, now() - spawn, protocol_.targetRadius));
        }
    }
    return shown;
}

void ShooterGame::describePhase(ShownFrame& shown) const {
    switch (phase_) {
        case Phase::Acclimation: {
            if (freePlay_) {
                shown.phaseText = "Free play: " + condition_ + ", level " + std::to_string(freeLevel_);
                break;
            }
            // Appendix B: the supervisor and the participant see how much practice is left.
            const double left =
                protocol_.acclimationS - static_cast<double>(frame_ - phaseStartFrame_) / protocol_.refreshHz;
            const long seconds = std::max(0L, static_cast<long>(std::ceil(left)));
            char text[48];
            std::snprintf(text, sizeof text, "Acclimation: %ld:%02ld left", seconds / 60, seconds % 60);
            shown.phaseText = text;
            break;
        }
        case Phase::Training: {
            // The level's trials: a queue drawn when the level starts, the trial up taken from it.
            const std::size_t ofLevel = levelTrials_;
            const std::size_t trial = ofLevel - levelQueue_.size();
            shown.phaseText = "Training: level " + std::to_string(level_) + ", trial " + std::to_string(trial) +
                " of " + std::to_string(ofLevel);
            break;
        }
        case Phase::AwaitingSupervisor:
            shown.phaseText = "Press Enter to begin";
            shown.promptsEnter = true;
            break;
        case Phase::Test:
            shown.phaseText = "Test: trial " + std::to_string(testNext_) + " of " + std::to_string(testQueue_.size());
            break;
        case Phase::Done: shown.phaseText = "Thank you"; break;
    }
}

void ShooterGame::judgeTrial(bool click, ShownFrame& shown) {
    // The click first: the frame the timeout falls on still shows the target, so a click on
    // it is a shot at what the participant saw (aim time exactly timeout_s), not a timeout
    // (docs/shooter-study.md, "Test").
    if (click) {
        // World: the aim the mouse really has now against the world now. Displayed: what is
        // under the reticle of the frame on screen (its camera, its target).
        const auto world = targetAt(now());
        const glm::dvec3 eye(camera_.eye);
        const glm::dvec3 aim(scene::forwardDirection(camera_.yaw, camera_.pitch));
        const bool worldHit = world && physics::raySphereHit(eye, aim, *world, protocol_.targetRadius).has_value();
        const glm::dvec3 shownAim(scene::forwardDirection(shown.camera.yaw, shown.camera.pitch));
        const bool shownHit = !shown.scene.objects.empty() &&
            physics::raySphereHit(glm::dvec3(shown.camera.eye), shownAim,
                                  glm::dvec3(shown.scene.objects.front().position), protocol_.targetRadius)
                .has_value();
        const double error = world ? glm::degrees(physics::angleBetweenRayAndPoint(eye, aim, *world)) : 180.0;
        frozenFrame_ = shown;
        finishTrial(worldHit ? Outcome::Hit : Outcome::Miss, shownHit ? Outcome::Hit : Outcome::Miss, now(), error);
    } else if (timedOut(*trial_)) {
        const auto world = targetAt(now());
        const double error = world
            ? glm::degrees(physics::angleBetweenRayAndPoint(
                  glm::dvec3(camera_.eye), glm::dvec3(scene::forwardDirection(camera_.yaw, camera_.pitch)), *world))
            : 180.0;
        frozenFrame_ = shown;
        finishTrial(Outcome::Timeout, Outcome::Timeout, now(), error);
    }
    if (!trial_) shown.feedback = banner_ == "HIT" ? "hit" : (banner_ == "TIMEOUT" ? "timeout" : "miss");
}

ShownFrame ShooterGame::step(const FrameInput& input) {
    ++frame_;
    commitPoint_ = false;
    openQuestionsIfDue();
    if (asking_) return questionFrame(input);
    turnCamera(input);
    bool click = (input.buttons & kButtonLeft) && !(previousButtons_ & kButtonLeft);
    const bool enter = (input.keys & kKeyEnter) && !(previousKeys_ & kKeyEnter);
    previousButtons_ = input.buttons;
    previousKeys_ = input.keys;

    if (frame_ == 0) beginPhase(Phase::Acclimation);
    if (pauseUntil_ >= 0 && frame_ >= pauseUntil_) {
        pauseUntil_ = -1;
        frozenFrame_.reset();
        banner_.clear();
        scheduleNextTrial();
    }
    if (reading_ && enter && frame_ > phaseStartFrame_)  // a press made while the text is up
        finishReading();
    else if (phase_ == Phase::AwaitingSupervisor && enter)
        beginPhase(Phase::Training);
    if (reading_) {
        clickGate_.clear();
        return readingFrame();
    }
    if (frozenFrame_) {
        clickGate_.clear();
        return frozenShownFrame();
    }

    const condition::ScheduledFrame f = schedule_->frame(frame_ - scheduleStart_);
    ShownFrame shown = scheduledFrame(f);
    describePhase(shown);
    // A press while no target is up never waits for the next target.
    click = clickGate_.pass(click, f, trial_.has_value());
    if (trial_) judgeTrial(click, shown);
    return shown;
}

session::FrameRecord ShooterGame::frameRecord(const ShownFrame& shown) const {
    session::FrameRecord r = frameRecordOf(shown);
    if (!shown.scene.objects.empty()) {
        const auto& p = shown.scene.objects.front().position;
        r.detailJson = nlohmann::json{{"target", {p.x, p.y, p.z}}}.dump();
    }
    return r;
}

}  // namespace warplab::game
