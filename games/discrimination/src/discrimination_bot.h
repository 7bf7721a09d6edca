// A scripted player for headless runs and tests: it follows the target it sees on screen and
// answers each trial as an observer with a stated psychometric function would -- a test double
// whose threshold is known, so that what the procedures recover can be checked against it. It
// reads the conditions of the two intervals from the frames (what drew them), which a person
// cannot: the simulated participant (participants/participant.h) is the one that judges what it
// sees. Deterministic from its seed.
#pragma once

#include <cstdint>
#include <map>
#include <optional>

#include "adaptive/psychometric.h"
#include "condition/stimulus.h"
#include "discrimination/discrimination_protocol.h"
#include "game/game.h"
#include "game/question_bot.h"
#include "game/random.h"

namespace warplab::discrimination {

struct Observer {
    adaptive::PsychometricFunction function{adaptive::Shape::Weibull, adaptive::Scale::Log, 0.5};
    // The threshold (the function's location, in stimulus units) for each dimension.
    std::map<condition::Dimension, double> thresholds{{condition::Dimension::LagFrames, 3.0},
                                                      {condition::Dimension::RenderHz, 40.0},
                                                      {condition::Dimension::JitterSdMs, 4.0}};
    double slope = 3.0;
    double lapse = 0.02;
};

struct BotSettings {
    double gainPerS = 6.0;  // share of the aiming error closed per second
    double enterAfterS = 0.5;  // Enter this long after a prompt
    double answerAfterS = 0.6;  // the question answered this long after it appears (after game::kAnswerSettleS)
    Observer observer;
};

class DiscriminationBot final : public game::Player {
public:
    DiscriminationBot(std::uint64_t seed, const DiscriminationProtocol& protocol, BotSettings settings = {});
    game::FrameInput next(const game::ShownFrame& shown) override;

    // The probability the observer answers a trial between these two conditions correctly.
    double pCorrect(const condition::Condition& a, const condition::Condition& b) const;

private:
    // The first dimension the two conditions differ in, and the stimulus of b against a as the
    // reference (positive where b is worse); none where they do not differ.
    struct Difference {
        condition::Dimension dimension;
        double stimulus;
    };
    std::optional<Difference> differenceOf(const condition::Condition& a, const condition::Condition& b) const;

    game::Random random_;
    DiscriminationProtocol protocol_;
    BotSettings settings_;
    condition::Condition seen_[2];  // what drew each interval of the trial
    game::BotPromptReader prompt_;
    game::BotQuestionReader questions_;
    bool buttonDown_ = false;
    int choice_ = 0;  // the answer to the question on screen, decided once (0: not yet)
};

}  // namespace warplab::discrimination
