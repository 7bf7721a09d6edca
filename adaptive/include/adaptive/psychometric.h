// A psychometric function: the probability of a correct answer at a stimulus level, as the
// adaptive procedures (quest_plus.h, staircase.h) and the fits of a discrimination task model
// it. In a forced choice among m alternatives a guess is right with probability 1/m (the
// "guess rate", ½ for two intervals), and a lapse -- an answer given without looking -- caps
// the rate below 1 (Wichmann and Hill 2001):
//     p(x) = guess + (1 - guess - lapse) F(β (u(x) - u(t)))
// with t the threshold (the location, a stimulus level), β the slope and u the scale the
// function is formed on: the stimulus itself or its natural log.
//   Logistic: F(z) = 1 / (1 + e^-z).
//   Weibull:  F(z) = 1 - exp(-e^z). On the log scale this is the classic Weibull of the stimulus,
//             1 - exp(-(x / t)^β); on the linear scale it is the Weibull of a stimulus already in
//             log units, as QUEST+ forms it over decibels (Watson 2017, eq. 11).
// No GL, no game: plain functions of numbers.
#pragma once

namespace warplab::adaptive {

enum class Shape { Logistic, Weibull };
enum class Scale { Linear, Log };

struct PsychometricFunction {
    Shape shape = Shape::Weibull;
    Scale scale = Scale::Log;
    double guess = 0.5;  // two-interval forced choice

    // p(x); on the log scale a stimulus or threshold at or below 0 is refused (std::domain_error).
    double probability(double x, double threshold, double slope, double lapse) const;
    // The stimulus at which p(x) = percentCorrect / 100: "the threshold at 75 % correct". Throws
    // std::domain_error where the function never reaches it (at or below the guess rate, or at
    // or above 1 - lapse).
    double stimulusAt(double percentCorrect, double threshold, double slope, double lapse) const;
};

}  // namespace warplab::adaptive
