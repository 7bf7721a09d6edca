#include "shooter_bot.h"
#include "shooter_game.h"

#include <algorithm>
#include <cmath>

namespace warplab::game {
namespace {

constexpr double kPi = 3.14159265358979323846;

double wrapAngle(double a) {
    while (a > kPi) a -= 2.0 * kPi;
    while (a < -kPi) a += 2.0 * kPi;
    return a;
}

}  // namespace

ShooterBot::ShooterBot(std::uint64_t seed, const protocol::ShooterProtocol& protocol, ShooterBotSettings settings)
    : random_(seed ^ 0xB07B07B07ULL),
      protocol_(protocol),
      settings_(settings),
      questions_(settings.answerAfterS, kQuestionCursorPixelsPerCount) {}

FrameInput ShooterBot::next(const ShownFrame& shown) {
    FrameInput input;
    const double dt = 1.0 / protocol_.refreshHz;

    Seen s{shown.time, !shown.scene.objects.empty() && !shown.frozen, 0.0, 0.0};
    if (s.target) {
        const glm::dvec3 d = glm::dvec3(shown.scene.objects.front().position) - glm::dvec3(shown.camera.eye);
        s.yaw = std::atan2(d.x, -d.z);
        s.pitch = std::atan2(d.y, std::sqrt(d.x * d.x + d.z * d.z));
    }
    seen_.push_back(s);
    // seen_.front() is the newest observation at least a reaction time old; history_ keeps a
    // little more behind it for the motion estimate.
    while (seen_.size() > 1 && seen_[1].time <= shown.time - settings_.reactionS) {
        history_.push_back(seen_.front());
        seen_.pop_front();
    }
    while (history_.size() > 1 && history_[1].time <= shown.time - settings_.reactionS - 0.1) history_.pop_front();
    if (!seen_.front().target) history_.clear();

    // Questions after a block: answered from the keyboard (the cursor only where no key gives
    // the answer), a Likert scale at its middle.
    if (questions_.ready(shown)) {
        const QuestionPrompt& q = *shown.question;
        const int value =
            q.kind == protocol::QuestionKind::Likert ? q.min + (q.max - q.min) / 2 : BotQuestionReader::choiceFor(q);
        input = questions_.answer(shown, value);
        if (buttonDown_) input.buttons = 0;  // one-frame presses
        buttonDown_ = input.buttons != 0;
        return input;
    }
    if (shown.question) return input;  // still reading it

    // The supervisor's Enter.
    if (prompt_.pressesEnter(shown, settings_.enterAfterS)) input.keys = kKeyEnter;

    const Seen& old = seen_.front();  // what it perceives now: the screen a reaction time ago
    if (!s.target) {
        visibleSince_ = -1.0;
        clickedThisTarget_ = false;
    } else if (visibleSince_ < 0.0) {
        visibleSince_ = shown.time;
    }

    if (old.target && !clickedThisTarget_) {
        // Predict where the target is now from its apparent motion as seen a reaction time ago
        // (over the 50 ms before that, so held frames at 15 Hz blur the estimate as they would
        // a person's), and follow that motion while closing the remaining error.
        double yaw = old.yaw, pitch = old.pitch, rateYaw = 0.0, ratePitch = 0.0;
        const Seen* earlier = nullptr;
        for (const Seen& e : history_)
            if (e.target && e.time <= old.time - 0.05) earlier = &e;
        if (earlier != nullptr && old.time > earlier->time) {
            rateYaw = wrapAngle(old.yaw - earlier->yaw) / (old.time - earlier->time);
            ratePitch = (old.pitch - earlier->pitch) / (old.time - earlier->time);
            yaw += rateYaw * settings_.reactionS;
            pitch += ratePitch * settings_.reactionS;
        }
        const double errorYaw = wrapAngle(yaw - aimYaw_), errorPitch = pitch - aimPitch_;
        const double step = std::min(1.0, settings_.gainPerS * dt);
        const double noise = settings_.noiseDeg * kPi / 180.0;
        const double turnYaw = rateYaw * dt + errorYaw * step + noise * random_.gaussian();
        const double turnPitch = ratePitch * dt + errorPitch * step + noise * random_.gaussian();
        input.mouseDx = turnYaw / protocol_.mouseRadiansPerCount;
        input.mouseDy = -turnPitch / protocol_.mouseRadiansPerCount;
        aimYaw_ += turnYaw;
        aimPitch_ = std::clamp(aimPitch_ + turnPitch, -1.5, 1.5);

        const double distance = glm::length(glm::dvec3(shown.scene.objects.empty()
                                                           ? glm::vec3(0.0f, 0.0f, -7.0f)
                                                           : shown.scene.objects.front().position - shown.camera.eye));
        const double angularRadius = std::asin(std::min(1.0, protocol_.targetRadius / std::max(distance, 1e-3)));
        const double error = std::hypot(errorYaw * std::cos(pitch), errorPitch);
        if (visibleSince_ >= 0.0 && shown.time - visibleSince_ >= settings_.minAimS &&
            error < settings_.clickWithin * angularRadius) {
            input.buttons = kButtonLeft;
            clickedThisTarget_ = true;
        }
    }
    // One-frame press: the game scores the press, not the hold.
    if (buttonDown_) input.buttons = 0;
    buttonDown_ = input.buttons != 0;
    return input;
}

}  // namespace warplab::game
