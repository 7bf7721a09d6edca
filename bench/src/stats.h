// Numbers over a run's repeats and frames, and how the CSV and the summary print them.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace warplab::bench {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Of the values that are not NaN; NaN when none is.
double median(std::vector<double> values);

// PSNR of the mean squared error over frames, each frame's MSE recovered from its PSNR (an
// identical frame, PSNR = inf, has MSE 0): averaging dB would let exact frames dominate.
double psnrOfMeanMse(const std::vector<double>& psnrs);

// Of the values that are not NaN; NaN when none is.
double mean(const std::vector<double>& values);

// Empty for "does not apply", "inf" for identical images' PSNR.
std::string field(double v, int precision = 4);

}  // namespace warplab::bench
