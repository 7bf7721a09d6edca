// Balanced Latin squares (Williams 1949, "Experimental designs balanced for the estimation of
// residual effects of treatments"): orders of conditions in which every condition comes first,
// second, ... equally often and follows every other condition equally often, so neither
// practice nor carry-over from the previous condition favours one. docs/study-plan.md.
#pragma once

#include <vector>

namespace warplab::plan {

// Larger squares are refused: no study compares that many conditions, and the rows grow as n².
inline constexpr int kMaxLatinSquareSize = 256;

// Rows, each an order of 0..n-1. Even n: n rows; each condition is in each position once and
// each ordered pair (a then b, a != b) is adjacent in exactly one row. Odd n: 2n rows, the
// square and then its rows reversed; each condition is in each position twice and each ordered
// adjacent pair occurs twice. n = 1 is {{0}}. Throws std::invalid_argument for n < 1 or
// n > kMaxLatinSquareSize.
std::vector<std::vector<int>> balancedLatinSquare(int n);

}  // namespace warplab::plan
