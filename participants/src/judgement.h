// What the simulated participant makes of a display's delay, and of the two intervals of a
// two-interval forced-choice task (games/discrimination): how late the picture followed its hand
// in each interval and how often the picture changed, and which interval it names when the
// question asks which was the more responsive or the smoother. Private to the participant:
// participant.cpp feeds it what it sees and its hand, never the world.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "game/random.h"

namespace warplab::participants {

// Positions in time, in time order: the hand's log (where it commanded its hand to be as each
// frame was shown), or the pointer as each new image showed it.
using TimedLog = std::deque<std::pair<double, glm::dvec2>>;

// Where `log` (not empty) puts the point at `time`: linear between entries, held outside them.
glm::dvec2 positionAt(const TimedLog& log, double time);

// How late the pointer on screen follows the hand: the delay, on a grid of `step` seconds from
// 0 to 0.4 s, that best lines up how far the pointer moved between new images a quarter second
// apart with how far the hand moved over the same span that much earlier. None where no two
// images are that far apart, or where the pointer moved too little against the fit's error (a
// still hand shows no delay).
std::optional<double> fitDelay(const TimedLog& pointer, const TimedLog& hand, double step);

// What it made of one interval.
struct IntervalJudgement {
    std::optional<double> delayS;  // how late the picture followed its hand; none: too little movement
    std::optional<double> imagesPerS;  // how often the picture changed; none: it never did
};

// The two intervals of the trial on screen, told by the screen's phase text ("Interval 1 of 2",
// "Interval 2 of 2"), and the answer to the question after them. A new first interval begins a
// new trial and forgets the last one's.
class IntervalJudge {
public:
    // `delayNoiseMs` and `rateNoise`: ParticipantParams::delayJudgementNoiseMs and
    // ::smoothnessJudgementNoise. `seed`: the stream those noises and its guesses are drawn from.
    IntervalJudge(std::uint64_t seed, double delayNoiseMs, double rateNoise);
    // Every frame, first: the phase text ("" on a question screen) opens and closes intervals;
    // the hand is logged.
    void follow(const std::string& phaseText, double time, glm::dvec2 hand);
    // Each frame of play in an interval: whether its image is new, and if so and it shows the
    // scene in play, the pointer it shows (the cursor, or the view as seen in the pictures).
    void see(double time, bool newImage, std::optional<glm::dvec2> pointer);
    bool inInterval() const { return open_ != 0; }
    // The interval (1 or 2) the question names, if it asks which interval was the more (or
    // less) responsive, laggy or smooth and this trial has shown an interval; else none.
    std::optional<int> answer(const std::string& prompt);

private:
    struct Seen {
        TimedLog pointer;
        double from = -1.0, to = -1.0;  // the first and last frame of play seen in it
        int changes = 0;  // new images after the first
    };
    void close();

    game::Random random_;
    double delayNoiseMs_, rateNoise_;
    TimedLog hand_;
    int open_ = 0;  // the interval on screen (1 or 2), 0 for none
    double openedAt_ = 0.0;
    std::array<Seen, 2> seen_;
    std::array<std::optional<IntervalJudgement>, 2> judged_;
};

}  // namespace warplab::participants
