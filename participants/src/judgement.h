// How late the picture follows the simulated participant's hand, judged from what it sees: the
// fit over a log of the pointer as new images showed it against the log of its hand. Private
// to the participant.
#pragma once

#include <deque>
#include <optional>
#include <utility>

#include <glm/glm.hpp>

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

}  // namespace warplab::participants
