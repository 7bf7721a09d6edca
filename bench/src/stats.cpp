#include "stats.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace warplab::bench {

double median(std::vector<double> values) {
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }), values.end());
    if (values.empty()) return kNaN;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double psnrOfMeanMse(const std::vector<double>& psnrs) {
    double sum = 0.0;
    int n = 0;
    for (double p : psnrs) {
        if (std::isnan(p)) continue;
        sum += 255.0 * 255.0 / std::pow(10.0, p / 10.0);
        ++n;
    }
    if (n == 0) return kNaN;
    return sum == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / (sum / n));
}

double mean(const std::vector<double>& values) {
    double sum = 0.0;
    int n = 0;
    for (double v : values)
        if (!std::isnan(v)) sum += v, ++n;
    return n ? sum / n : kNaN;
}

std::string field(double v, int precision) {
    if (std::isnan(v)) return "";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s << std::setprecision(precision) << std::fixed << v;
    return s.str();
}

}  // namespace warplab::bench
