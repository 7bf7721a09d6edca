#include "adaptive/staircase.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "physics/splitmix.h"

namespace warplab::adaptive {

Staircase::Staircase(StaircaseSettings settings) : settings_(std::move(settings)), level_(settings_.start) {
    const StaircaseSettings& s = settings_;
    if (s.stimuli.empty()) throw std::invalid_argument("a staircase needs at least one level");
    if (s.start >= s.stimuli.size())
        throw std::invalid_argument("a staircase's start is level " + std::to_string(s.start) + " of " +
                                    std::to_string(s.stimuli.size()));
    if (s.up < 1 || s.down < 1) throw std::invalid_argument("a staircase's up and down must be 1 or more");
    if (s.steps.empty()) throw std::invalid_argument("a staircase needs a step size");
    for (const int step : s.steps)
        if (step < 1) throw std::invalid_argument("a staircase's steps must be 1 level or more");
}

void Staircase::update(bool correct) {
    ++trials_;
    int move = 0;  // +1 easier, -1 harder
    if (correct) {
        wrongRun_ = 0;
        if (++correctRun_ >= settings_.down) move = -1, correctRun_ = 0;
    } else {
        correctRun_ = 0;
        if (++wrongRun_ >= settings_.up) move = +1, wrongRun_ = 0;
    }
    if (move == 0) return;
    if (direction_ != 0 && move != direction_) reversals_.push_back(level_);
    direction_ = move;
    const std::size_t k = std::min(reversals_.size(), settings_.steps.size() - 1);
    const auto step = static_cast<std::ptrdiff_t>(settings_.steps[k]);
    // Easier is a higher index when higher levels are easier.
    const std::ptrdiff_t signedStep = (move > 0) == settings_.higherIsEasier ? step : -step;
    const auto last = static_cast<std::ptrdiff_t>(settings_.stimuli.size()) - 1;
    level_ =
        static_cast<std::size_t>(std::clamp(static_cast<std::ptrdiff_t>(level_) + signedStep, std::ptrdiff_t{0}, last));
}

double Staircase::threshold(std::size_t count) const {
    if (count == 0 || reversals_.size() < count) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0.0;
    for (std::size_t i = reversals_.size() - count; i < reversals_.size(); ++i) sum += settings_.stimuli[reversals_[i]];
    return sum / static_cast<double>(count);
}

std::vector<std::size_t> constantStimuliOrder(std::size_t levels, int repeats, std::uint64_t seed) {
    if (repeats < 1) throw std::invalid_argument("constant stimuli need each level once or more");
    std::vector<std::size_t> order;
    for (int r = 0; r < repeats; ++r)
        for (std::size_t level = 0; level < levels; ++level) order.push_back(level);
    std::uint64_t state = seed;
    for (std::size_t i = order.size(); i > 1; --i) {
        const auto j = static_cast<std::size_t>(physics::uniform01(state) * static_cast<double>(i));
        std::swap(order[i - 1], order[std::min(j, i - 1)]);
    }
    return order;
}

}  // namespace warplab::adaptive
