#include "click_bot.h"

#include <algorithm>
#include <cmath>

#include "condition/schedule.h"
#include "game/screen.h"

namespace warplab::game {

int botRating(const condition::Condition& condition, double refreshHz, int statement, int min, int max) {
    // The rate new frames reach the screen: the renders when they are held, else the fill's (a
    // late warp makes one every display frame).
    const double shownRate = condition.lateWarp != condition::LateWarp::None ? refreshHz
        : condition.fillKind() == condition::Fill::Hold                      ? condition.renderHz
                                                                             : condition.fillHz.value_or(refreshHz);
    // Average time from an input to its frame: what the schedule shows a mouse step at a render
    // with (the queue; bidirectional reprojection's wait for the next I-frame), plus half a
    // render period of holding.
    const condition::ConditionSchedule schedule(condition, refreshHz);
    const double latencyMs = 1000.0 * schedule.viewLatency(0.0) + 500.0 / condition.renderHz;
    const int smooth = static_cast<int>(std::lround(1.0 + 6.0 * std::min(1.0, shownRate / 60.0)));
    const int responsive = std::clamp(static_cast<int>(std::lround(7.0 - latencyMs / 25.0)), 1, 7);
    const int enjoyed = static_cast<int>(std::lround((smooth + responsive) / 2.0));
    const int values[4] = {enjoyed, 8 - enjoyed, responsive, smooth};
    return std::clamp(values[statement % 4], min, max);
}

ClickBot::ClickBot(std::uint64_t seed, const protocol::ClickProtocol& protocol, const DisplaySize& display,
                   ClickBotSettings settings)
    : random_(seed ^ 0xC11C4B07ULL),
      protocol_(protocol),
      display_(display),
      settings_(settings),
      cursor_(display.width * 0.5, display.height * 0.5),
      reader_(settings.answerAfterS, protocol.cursorPixelsPerCount) {}

void ClickBot::moveTowards(FrameInput& input, glm::dvec2 goal, glm::dvec2 rate, double dt) {
    const double step = std::min(1.0, settings_.gainPerS * dt);
    glm::dvec2 move = rate * dt + (goal - cursor_) * step;
    move += glm::dvec2(random_.gaussian(), random_.gaussian()) * settings_.noisePx;
    const double perCount = protocol_.cursorPixelsPerCount;
    input.mouseDx = move.x / perCount;
    input.mouseDy = move.y / perCount;
    // The game clamps the cursor to the display; the bot's hand knows where it ends up.
    cursor_.x = std::clamp(cursor_.x + input.mouseDx * perCount, 0.0, static_cast<double>(display_.width));
    cursor_.y = std::clamp(cursor_.y + input.mouseDy * perCount, 0.0, static_cast<double>(display_.height));
}

FrameInput ClickBot::rate(const ShownFrame& shown, bool waited) {
    FrameInput input;
    const QuestionPrompt& r = *shown.question;
    if (r.kind != protocol::QuestionKind::Likert)
        return waited ? reader_.answer(shown, BotQuestionReader::choiceFor(r)) : input;
    const int value =
        botRating(protocol_.conditionTable.at(lastCondition_), protocol_.refreshHz, r.index, r.min, r.max);
    const glm::dvec4 box = r.boxes[static_cast<std::size_t>(value - r.min)];
    const glm::dvec2 centre(box.x + box.z * 0.5, box.y + box.w * 0.5);
    // Even statements by key, odd ones by mouse; a value no digit key gives always by mouse.
    if (r.index % 2 == 0 && value >= 1 && value <= 9) {
        if (waited) input.keys = digitKey(value);
        return input;
    }
    moveTowards(input, centre, {0.0, 0.0}, 1.0 / protocol_.refreshHz);
    // Click once the cursor is well inside the box (the game judges the cursor as shown).
    const glm::dvec2 off = glm::abs(shown.cursor - centre);
    if (waited && off.x < box.z * 0.3 && off.y < box.w * 0.3) input.buttons = kButtonLeft;
    return input;
}

FrameInput ClickBot::play(const ShownFrame& shown) {
    FrameInput input;
    const double dt = 1.0 / protocol_.refreshHz;
    const ScreenMapping screen(shown.camera, display_);
    Seen now{shown.time, {}};
    for (const auto& o : shown.scene.objects) {
        if (o.colour.g < o.colour.r) continue;  // red: leave it alone
        const auto centre = screen.project(glm::dvec3(o.position));
        if (!centre) continue;
        const double distance = glm::length(glm::dvec3(o.position) - screen.eye());
        const double radiusPx = std::asin(std::min(1.0, o.halfExtents.x / distance)) / screen.radiansPerPixel();
        now.greens[o.id] = {centre->x, centre->y, radiusPx};
    }
    seen_.push_back(now);
    // seen_.front(): the newest frame at least a reaction time old; one 50 ms before it
    // gives the apparent motion.
    while (seen_.size() > 2 && seen_[1].time <= shown.time - settings_.reactionS - 0.05) seen_.pop_front();
    const Seen* old = nullptr;
    const Seen* earlier = &seen_.front();
    for (const auto& s : seen_)
        if (s.time <= shown.time - settings_.reactionS) old = &s;
    if (old == nullptr) return input;

    for (auto it = clicked_.begin(); it != clicked_.end();)
        it = shown.time - it->second > 1.0 ? clicked_.erase(it) : std::next(it);
    if (hasTarget_ && (!old->greens.count(targetId_) || clicked_.count(targetId_))) hasTarget_ = false;
    if (!hasTarget_) {
        double best = 1e30;
        for (const auto& [id, g] : old->greens) {
            const double d = glm::length(glm::dvec2(g) - cursor_);
            if (!clicked_.count(id) && d < best) {
                best = d;
                targetId_ = id;
                hasTarget_ = true;
                aimingSince_ = shown.time;
            }
        }
    }
    if (!hasTarget_) return input;
    const glm::dvec3 g = old->greens.at(targetId_);
    glm::dvec2 rate(0.0);
    const auto before = earlier->greens.find(targetId_);
    if (before != earlier->greens.end() && old->time > earlier->time)
        rate = (glm::dvec2(g) - glm::dvec2(before->second)) / (old->time - earlier->time);
    const glm::dvec2 predicted = glm::dvec2(g) + rate * settings_.reactionS;
    moveTowards(input, predicted, rate, dt);
    if (shown.time - aimingSince_ >= settings_.minAimS &&
        glm::length(predicted - cursor_) < settings_.clickWithin * g.z) {
        input.buttons = kButtonLeft;
        clicked_[targetId_] = shown.time;
        hasTarget_ = false;
    }
    return input;
}

FrameInput ClickBot::next(const ShownFrame& shown) {
    FrameInput input;
    if (prompt_.pressesEnter(shown, settings_.enterAfterS)) input.keys = kKeyEnter;
    if (!shown.condition.name.empty()) lastCondition_ = shown.condition.name;
    // Screens show the cursor live, so there the bot sees exactly where it is; in a match it
    // keeps track itself, since the frame shows the cursor as late as the condition shows it.
    if (shown.blank) cursor_ = shown.cursor;
    const bool waited = reader_.ready(shown);
    if (shown.question) {
        input = rate(shown, waited);
        seen_.clear();
        hasTarget_ = false;
    } else if (!shown.blank) {
        input = play(shown);
    }
    // One-frame presses: the game scores the press, not the hold.
    if (buttonDown_) input.buttons = 0;
    buttonDown_ = input.buttons != 0;
    return input;
}

}  // namespace warplab::game
