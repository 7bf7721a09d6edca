#include "adaptive/psychometric.h"

#include <cmath>
#include <stdexcept>

namespace warplab::adaptive {
namespace {

double onScale(Scale scale, double x, const char* what) {
    if (scale == Scale::Linear) return x;
    if (!(x > 0.0))
        throw std::domain_error(std::string("a psychometric function on the log scale needs a ") + what + " above 0");
    return std::log(x);
}

double fromScale(Scale scale, double u) { return scale == Scale::Linear ? u : std::exp(u); }

}  // namespace

double PsychometricFunction::probability(double x, double threshold, double slope, double lapse) const {
    const double z = slope * (onScale(scale, x, "stimulus") - onScale(scale, threshold, "threshold"));
    // Both written so that no large exponent overflows: e^-z for a very negative z is huge, but
    // 1 / (1 + huge) is 0 all the same; exp(-e^z) of a huge e^z is 0.
    const double f = shape == Shape::Logistic ? 1.0 / (1.0 + std::exp(-z)) : -std::expm1(-std::exp(z));
    return guess + (1.0 - guess - lapse) * f;
}

double PsychometricFunction::stimulusAt(double percentCorrect, double threshold, double slope, double lapse) const {
    const double q = (percentCorrect / 100.0 - guess) / (1.0 - guess - lapse);
    if (!(q > 0.0 && q < 1.0))
        throw std::domain_error("the psychometric function never reaches " + std::to_string(percentCorrect) +
                                " % correct (guess rate " + std::to_string(guess) + ", lapse " + std::to_string(lapse) +
                                ")");
    const double z = shape == Shape::Logistic ? std::log(q / (1.0 - q)) : std::log(-std::log1p(-q));
    return fromScale(scale, onScale(scale, threshold, "threshold") + z / slope);
}

}  // namespace warplab::adaptive
