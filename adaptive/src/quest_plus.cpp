#include "adaptive/quest_plus.h"

#include <cmath>
#include <stdexcept>

namespace warplab::adaptive {
namespace {

// -Σ p ln p over the positive entries, of weights that sum to `total` (normalised here).
double entropy(const std::vector<double>& weights, double total) {
    double h = 0.0;
    for (const double w : weights)
        if (w > 0.0) {
            const double p = w / total;
            h -= p * std::log(p);
        }
    return h;
}

}  // namespace

QuestPlus::QuestPlus(QuestPlusSettings settings) : settings_(std::move(settings)) {
    const QuestPlusSettings& s = settings_;
    if (s.stimuli.empty() || s.thresholds.empty() || s.slopes.empty() || s.lapses.empty())
        throw std::invalid_argument("QUEST+ needs at least one stimulus level and one value of each parameter");
    for (const auto* grid : {&s.stimuli, &s.thresholds, &s.slopes, &s.lapses})
        for (std::size_t k = 1; k < grid->size(); ++k)
            if (!((*grid)[k] > (*grid)[k - 1]))
                throw std::invalid_argument("QUEST+'s levels and grids must each rise, without repeats");
    const std::size_t combinations = s.thresholds.size() * s.slopes.size() * s.lapses.size();
    if (!s.prior.empty() && s.prior.size() != combinations)
        throw std::invalid_argument("QUEST+'s prior has " + std::to_string(s.prior.size()) + " weights for " +
                                    std::to_string(combinations) + " combinations of the parameters");
    posterior_ = s.prior.empty() ? std::vector<double>(combinations, 1.0) : s.prior;
    double total = 0.0;
    for (const double w : posterior_) {
        if (!(w >= 0.0) || !std::isfinite(w)) throw std::invalid_argument("QUEST+'s prior weights must be 0 or more");
        total += w;
    }
    if (!(total > 0.0)) throw std::invalid_argument("QUEST+'s prior gives no combination any weight");
    for (double& w : posterior_) w /= total;
    correct_.reserve(s.stimuli.size() * combinations);
    for (const double x : s.stimuli)
        for (const double t : s.thresholds)
            for (const double b : s.slopes)
                for (const double l : s.lapses) correct_.push_back(s.function.probability(x, t, b, l));
}

double QuestPlus::likelihood(std::size_t level, std::size_t parameters, bool correct) const {
    const double p = correct_[level * posterior_.size() + parameters];
    return correct ? p : 1.0 - p;
}

double QuestPlus::expectedEntropy(std::size_t level) const {
    double expected = 0.0;
    std::vector<double> after(posterior_.size());
    for (const bool correct : {true, false}) {
        double total = 0.0;  // p(this answer | level): the normaliser of the posterior after it
        for (std::size_t i = 0; i < posterior_.size(); ++i) {
            after[i] = posterior_[i] * likelihood(level, i, correct);
            total += after[i];
        }
        if (total > 0.0) expected += total * entropy(after, total);
    }
    return expected;
}

std::size_t QuestPlus::next() const {
    std::size_t best = 0;
    double least = expectedEntropy(0);
    for (std::size_t level = 1; level < settings_.stimuli.size(); ++level)
        if (const double h = expectedEntropy(level); h < least) {
            least = h;
            best = level;
        }
    return best;
}

void QuestPlus::update(std::size_t level, bool correct) {
    if (level >= settings_.stimuli.size())
        throw std::out_of_range("QUEST+ level " + std::to_string(level) + " is not one of its " +
                                std::to_string(settings_.stimuli.size()));
    std::vector<double> after(posterior_.size());
    double total = 0.0;
    for (std::size_t i = 0; i < posterior_.size(); ++i) {
        after[i] = posterior_[i] * likelihood(level, i, correct);
        total += after[i];
    }
    // An answer every combination on the grid calls impossible (no lapse, a level far from every
    // threshold) would leave nothing: refused, the posterior as it was, rather than 0/0.
    if (!(total > 0.0))
        throw std::domain_error("QUEST+: the answer has probability 0 under every combination of the grid");
    for (std::size_t i = 0; i < after.size(); ++i) posterior_[i] = after[i] / total;
    ++trials_;
}

Estimate QuestPlus::marginal(const std::vector<double>& grid, std::size_t stride, std::size_t count) const {
    // The combination index is (threshold * slopes + slope) * lapses + lapse: the parameter's
    // index is (i / stride) % count.
    std::vector<double> mass(count, 0.0);
    for (std::size_t i = 0; i < posterior_.size(); ++i) mass[(i / stride) % count] += posterior_[i];
    Estimate e;
    for (std::size_t k = 0; k < count; ++k) e.mean += mass[k] * grid[k];
    double cumulative = 0.0;
    bool lowFound = false, highFound = false;
    for (std::size_t k = 0; k < count; ++k) {
        cumulative += mass[k];
        if (!lowFound && cumulative >= 0.025) e.low = grid[k], lowFound = true;
        if (!highFound && cumulative >= 0.975) e.high = grid[k], highFound = true;
    }
    if (!highFound) e.high = grid.back();  // rounding left the last few ulps short of 0.975
    if (!lowFound) e.low = grid.back();
    return e;
}

Estimate QuestPlus::threshold() const {
    const QuestPlusSettings& s = settings_;
    return marginal(s.thresholds, s.slopes.size() * s.lapses.size(), s.thresholds.size());
}
Estimate QuestPlus::slope() const {
    const QuestPlusSettings& s = settings_;
    return marginal(s.slopes, s.lapses.size(), s.slopes.size());
}
Estimate QuestPlus::lapse() const { return marginal(settings_.lapses, 1, settings_.lapses.size()); }

}  // namespace warplab::adaptive
