// A scripted player for headless runs: it looks at what is on screen (the displayed target
// and camera, after a reaction delay), turns towards where it predicts the target to be,
// with aiming noise, and clicks when the reticle seems to be on it. Enough for realistic hits
// and misses -- and for 15 Hz to be harder than 120 Hz -- not a model of perception (the
// simulated participant, participants/participant.h, is one). Deterministic from its seed.
#pragma once

#include <cstdint>
#include <string>
#include <deque>

#include "game/game.h"
#include "game/random.h"
#include "game/question_bot.h"
#include "shooter/shooter_protocol.h"

namespace warplab::game {

struct ShooterBotSettings {
    double reactionS = 0.18;  // what it acts on was on screen this long ago
    double gainPerS = 9.0;  // share of the aiming error corrected per second
    double noiseDeg = 0.05;  // per-frame hand tremor, standard deviation
    double clickWithin = 0.7;  // clicks when the predicted error is below this share of the target's angular radius
    double minAimS = 0.3;  // never clicks sooner than this after the target appears
    double enterAfterS = 0.5;  // the supervisor presses Enter this long after the prompt
    double answerAfterS = 0.6;  // a question is answered this long after it appears
};

class ShooterBot final : public Player {
public:
    ShooterBot(std::uint64_t seed, const protocol::ShooterProtocol& protocol, ShooterBotSettings settings = {});
    FrameInput next(const ShownFrame& shown) override;

private:
    struct Seen {
        double time;
        bool target;
        double yaw, pitch;  // direction of the displayed target from the eye
    };
    Random random_;
    protocol::ShooterProtocol protocol_;
    ShooterBotSettings settings_;
    std::deque<Seen> seen_;
    std::deque<Seen> history_;
    double aimYaw_ = 0.0, aimPitch_ = 0.0;  // where it knows its hand points
    double visibleSince_ = -1.0;
    bool clickedThisTarget_ = false;
    bool buttonDown_ = false;
    BotPromptReader prompt_;
    BotQuestionReader questions_;
};

}  // namespace warplab::game
