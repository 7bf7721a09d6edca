#include "discrimination_bot.h"

#include <cmath>

#include "discrimination_game.h"
#include "scene/camera.h"

namespace warplab::discrimination {

DiscriminationBot::DiscriminationBot(std::uint64_t seed, const DiscriminationProtocol& protocol, BotSettings settings)
    : random_(seed ^ 0xD15C0B07ULL),
      protocol_(protocol),
      settings_(std::move(settings)),
      questions_(settings_.answerAfterS, kQuestionCursorPixelsPerCount) {}

double DiscriminationBot::pCorrect(const condition::Condition& a, const condition::Condition& b) const {
    // The dimension the two differ in, and by how much: 0 (a guess) where they do not differ.
    for (const condition::DimensionSpelling& d : condition::dimensionSpellings()) {
        const double la = condition::levelOf(a, d.dimension, protocol_.refreshHz);
        const double lb = condition::levelOf(b, d.dimension, protocol_.refreshHz);
        if (la == lb) continue;
        const double stimulus = std::abs(condition::stimulusOf(d.dimension, la, lb));
        const Observer& o = settings_.observer;
        return o.function.probability(stimulus, o.thresholds.at(d.dimension), o.slope, o.lapse);
    }
    return settings_.observer.function.guess;
}

game::FrameInput DiscriminationBot::next(const game::ShownFrame& shown) {
    game::FrameInput input;
    if (questions_.ready(shown)) {
        if (choice_ == 0) {
            // The better interval is the one the other is worse than; the observer finds it with
            // its function's probability, decided once per question.
            int better = 1;
            for (const condition::DimensionSpelling& d : condition::dimensionSpellings()) {
                const double a = condition::levelOf(seen_[0], d.dimension, protocol_.refreshHz);
                const double b = condition::levelOf(seen_[1], d.dimension, protocol_.refreshHz);
                if (a != b) {
                    better = condition::stimulusOf(d.dimension, a, b) > 0 ? 1 : 2;
                    break;
                }
            }
            choice_ = random_.uniform() < pCorrect(seen_[0], seen_[1]) ? better : 3 - better;
        }
        input = questions_.answer(shown, choice_);
    } else if (!shown.question) {
        choice_ = 0;
        if (prompt_.pressesEnter(shown, settings_.enterAfterS)) input.keys = game::kKeyEnter;
        for (int i : {1, 2})
            if (shown.phaseText == intervalText(i)) seen_[i - 1] = shown.condition;
        if (!shown.scene.objects.empty()) {
            // Follow the target as the frame shows it, from the view the frame shows.
            const glm::dvec3 d = glm::dvec3(shown.scene.objects.front().position) - glm::dvec3(shown.camera.eye);
            const double yaw = std::atan2(d.x, -d.z), pitch = std::atan2(d.y, std::hypot(d.x, d.z));
            const double step = settings_.gainPerS / protocol_.refreshHz;
            input.mouseDx = (yaw - shown.camera.yaw) * step / protocol_.mouseRadiansPerCount;
            input.mouseDy = -(pitch - shown.camera.pitch) * step / protocol_.mouseRadiansPerCount;
        }
    }
    if (buttonDown_) input.buttons = 0;  // one-frame presses
    buttonDown_ = input.buttons != 0;
    return input;
}

}  // namespace warplab::discrimination
