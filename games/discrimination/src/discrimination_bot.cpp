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

std::optional<DiscriminationBot::Difference> DiscriminationBot::differenceOf(const condition::Condition& a,
                                                                             const condition::Condition& b) const {
    for (const condition::DimensionSpelling& d : condition::dimensionSpellings()) {
        const double la = condition::levelOf(a, d.dimension, protocol_.refreshHz);
        const double lb = condition::levelOf(b, d.dimension, protocol_.refreshHz);
        if (la != lb) return Difference{d.dimension, condition::stimulusOf(d.dimension, la, lb)};
    }
    return std::nullopt;
}

double DiscriminationBot::pCorrect(const condition::Condition& a, const condition::Condition& b) const {
    const Observer& o = settings_.observer;
    const std::optional<Difference> difference = differenceOf(a, b);
    if (!difference) return o.function.guess;  // no difference: a guess
    return o.function.probability(std::abs(difference->stimulus), o.thresholds.at(difference->dimension), o.slope,
                                  o.lapse);
}

game::FrameInput DiscriminationBot::next(const game::ShownFrame& shown) {
    game::FrameInput input;
    if (questions_.ready(shown)) {
        if (choice_ == 0) {
            // The better interval is the one the other is worse than; the observer finds it with
            // its function's probability, decided once per question.
            const std::optional<Difference> difference = differenceOf(seen_[0], seen_[1]);
            const int better = !difference || difference->stimulus > 0 ? 1 : 2;
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
