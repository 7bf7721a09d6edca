// QUEST+ (Watson 2017): a Bayesian adaptive procedure over a grid. The unknowns -- threshold,
// slope and lapse of a stated psychometric function -- each take values on a stated grid; a
// prior over their combinations becomes the posterior after each answer (Bayes' rule with the
// function's likelihood), and each next stimulus is the one of the stated levels whose answer is
// expected to leave the posterior with the least entropy. Everything is a function of the
// settings and the answers so far, so a session replays, and resumes, by feeding the recorded
// answers again.
#pragma once

#include <cstddef>
#include <vector>

#include "adaptive/psychometric.h"

namespace warplab::adaptive {

struct QuestPlusSettings {
    PsychometricFunction function;
    std::vector<double> stimuli;  // the levels it may present, as the display can show them; rising
    std::vector<double> thresholds, slopes, lapses;  // the grids of the unknowns, each rising
    // Over every (threshold, slope, lapse), threshold outermost, lapse innermost; any positive
    // weights (normalised here); empty for a uniform prior.
    std::vector<double> prior;
};

// A parameter's marginal posterior: its mean and the 95 % credible interval between the 2.5 %
// and 97.5 % quantiles of its distribution on the grid (the lowest grid value whose cumulative
// probability reaches each).
struct Estimate {
    double mean = 0.0, low = 0.0, high = 0.0;
};

class QuestPlus {
public:
    // Throws std::invalid_argument for an empty or unordered grid or level list, a prior of the
    // wrong size or with a negative or no weight, and std::domain_error for a grid the function
    // cannot take.
    explicit QuestPlus(QuestPlusSettings settings);

    // The index into stimuli of the next level: the least expected entropy, the first of equals.
    std::size_t next() const;
    // The expected entropy (nats) of the posterior after an answer at stimuli[level].
    double expectedEntropy(std::size_t level) const;
    void update(std::size_t level, bool correct);

    // The posterior over every (threshold, slope, lapse), ordered as the prior.
    const std::vector<double>& posterior() const { return posterior_; }
    Estimate threshold() const;
    Estimate slope() const;
    Estimate lapse() const;
    std::size_t trials() const { return trials_; }
    const QuestPlusSettings& settings() const { return settings_; }

private:
    double likelihood(std::size_t level, std::size_t parameters, bool correct) const;
    Estimate marginal(const std::vector<double>& grid, std::size_t stride, std::size_t count) const;

    QuestPlusSettings settings_;
    std::vector<double> correct_;  // p(correct | level, parameters), level outermost
    std::vector<double> posterior_;
    std::size_t trials_ = 0;
};

}  // namespace warplab::adaptive
