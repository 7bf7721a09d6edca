// Numbers as warplab's files may hold them: finite, in a stated range, whole where whole is
// meant, and said back in a message as the user wrote them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace warplab::strict {

struct NumberRange {
    double low;
    bool lowOpen;
    double high;
    bool highOpen;

    bool contains(double v) const;  // false for NaN
    std::string text() const;  // "between 1 and 2", "greater than 0 and at most 3", ...
};

// Shortest text that reads back as the same double; integers without a decimal point.
std::string formatNumber(double value);

// The whole number `text` spells in decimal digits alone (no sign, no space, no exponent), if
// it is at most `high`; nothing otherwise, 2^64 included.
std::optional<std::uint64_t> wholeNumber(const std::string& text, std::uint64_t high);
// The number `text` spells ("-12", "0.5", "1e3"), if it is finite and in `range`; nothing for
// "nan", "inf", "1e999", "12px" or "".
std::optional<double> decimalNumber(const std::string& text, const NumberRange& range);

}  // namespace warplab::strict
