#include "strict/number.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace warplab::strict {

bool NumberRange::contains(double v) const {
    return (lowOpen ? v > low : v >= low) && (highOpen ? v < high : v <= high);
}

std::string NumberRange::text() const {
    const std::string lo = formatNumber(low), hi = formatNumber(high);
    if (!lowOpen && !highOpen) return "between " + lo + " and " + hi;
    return (lowOpen ? "greater than " : "at least ") + lo + (highOpen ? " and less than " : " and at most ") + hi;
}

std::string formatNumber(double value) {
    char buffer[32];
    if (value == std::floor(value) && std::abs(value) < 1e15) {
        std::snprintf(buffer, sizeof buffer, "%.0f", value);
        return buffer;
    }
    for (int precision = 1; precision <= 17; ++precision) {
        std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
        if (std::strtod(buffer, nullptr) == value) break;
    }
    return buffer;
}

// from_chars: no locale, no leading space or '+', and the whole text or nothing.
std::optional<std::uint64_t> wholeNumber(const std::string& text, std::uint64_t high) {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value > high) return std::nullopt;
    return value;
}

std::optional<double> decimalNumber(const std::string& text, const NumberRange& range) {
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
        !range.contains(value))
        return std::nullopt;
    return value;
}

}  // namespace warplab::strict
