// A scripted player for the click game: it looks at the frame on screen a reaction time ago,
// picks the green sphere nearest its cursor, leads it by its apparent motion, and clicks when
// the cursor seems to be on it -- so lag and low frame rates cost it as they cost a person,
// roughly. Ratings follow a fixed rule of the condition's frame rate and latency (documented in
// docs/click-study.md), answered by key for statements 1 and 3 and by clicking the box for
// 2 and 4, so headless sessions are complete and exercise both answers. Deterministic.
#pragma once

#include <cstdint>
#include <string>
#include <deque>
#include <map>

#include "condition/condition.h"
#include "game/game.h"
#include "game/question_bot.h"
#include "game/random.h"
#include "click/click_protocol.h"

namespace warplab::game {

struct ClickBotSettings {
    double reactionS = 0.2;  // what it acts on was on screen this long ago
    double gainPerS = 8.0;  // share of the cursor's error corrected per second
    double noisePx = 1.5;  // per-frame hand tremor, standard deviation, display pixels
    double clickWithin = 0.6;  // clicks when the predicted error is below this share of the sphere's radius on screen
    double minAimS = 0.25;  // follows a sphere at least this long before clicking it
    double answerAfterS = 0.6;  // a rating is answered this long after its statement appears
    double enterAfterS = 0.5;  // the supervisor presses Enter this long after the prompt
};

// The bot's rating of a condition on a display of refreshHz, by the rule in
// docs/click-study.md; statement 0 enjoyed, 1 difficult, 2 responsive, 3 smooth, clamped to
// [min, max].
int botRating(const condition::Condition& condition, double refreshHz, int statement, int min, int max);

class ClickBot final : public Player {
public:
    ClickBot(std::uint64_t seed, const protocol::ClickProtocol& protocol, const DisplaySize& display,
             ClickBotSettings settings = {});
    FrameInput next(const ShownFrame& shown) override;

private:
    struct Seen {
        double time;
        std::map<std::uint32_t, glm::dvec3> greens;  // id -> screen x, y and radius in pixels
    };
    FrameInput play(const ShownFrame& shown);
    FrameInput rate(const ShownFrame& shown, bool waited);
    void moveTowards(FrameInput& input, glm::dvec2 goal, glm::dvec2 rate, double dt);

    Random random_;
    protocol::ClickProtocol protocol_;
    DisplaySize display_;
    ClickBotSettings settings_;
    glm::dvec2 cursor_;  // where it knows its hand has put the cursor
    std::deque<Seen> seen_;
    std::uint32_t targetId_ = 0;
    bool hasTarget_ = false;
    double aimingSince_ = 0.0;
    std::map<std::uint32_t, double> clicked_;  // ids it clicked, and when
    bool buttonDown_ = false;
    BotPromptReader prompt_;
    std::string lastCondition_;
    BotQuestionReader reader_;
};

}  // namespace warplab::game
