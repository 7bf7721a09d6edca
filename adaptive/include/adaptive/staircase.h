// The two classic procedures beside QUEST+ (quest_plus.h), as labs run them: a transformed
// up-down staircase (Levitt 1971) and the method of constant stimuli. Like QUEST+ each is a
// function of its settings, its seed and the answers so far, so a session replays, and resumes,
// by feeding the recorded answers again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace warplab::adaptive {

struct StaircaseSettings {
    std::vector<double> stimuli;  // the levels, rising
    bool higherIsEasier = true;  // more added lag, a lower frame rate: easier to tell apart
    std::size_t start = 0;  // index of the first level
    // After `down` correct answers in a row one step harder, after `up` wrong ones in a row one
    // step easier: 1-up-2-down settles where p(correct) = 0.5^(1/2), about 70.7 % (Levitt 1971).
    int up = 1, down = 2;
    // Levels per step: steps[k] after k reversals, the last one from then on.
    std::vector<int> steps{1};
};

class Staircase {
public:
    // Throws std::invalid_argument for no levels, a start outside them, up or down below 1, or a
    // step below 1.
    explicit Staircase(StaircaseSettings settings);

    std::size_t next() const { return level_; }  // index into stimuli
    // The answer at the level next() gave.
    void update(bool correct);
    // The levels (indices) at which the staircase turned, in order.
    const std::vector<std::size_t>& reversals() const { return reversals_; }
    // The mean stimulus at the last `count` reversals, the staircase's estimate of the level it
    // settles at; NaN with fewer reversals than that.
    double threshold(std::size_t count) const;
    std::size_t trials() const { return trials_; }

private:
    StaircaseSettings settings_;
    std::size_t level_;
    int correctRun_ = 0, wrongRun_ = 0;
    int direction_ = 0;  // of the last move: +1 easier, -1 harder, 0 none yet
    std::vector<std::size_t> reversals_;
    std::size_t trials_ = 0;
};

// The method of constant stimuli: each of `levels` levels `repeats` times, in an order drawn
// from `seed` (a Fisher-Yates shuffle over splitmix64, the same on every machine).
std::vector<std::size_t> constantStimuliOrder(std::size_t levels, int repeats, std::uint64_t seed);

}  // namespace warplab::adaptive
