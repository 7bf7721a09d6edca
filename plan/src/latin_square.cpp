#include "plan/latin_square.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace warplab::plan {

std::vector<std::vector<int>> balancedLatinSquare(int n) {
    if (n < 1 || n > kMaxLatinSquareSize)
        throw std::invalid_argument("balancedLatinSquare: n must be between 1 and " +
                                    std::to_string(kMaxLatinSquareSize) + ", got " + std::to_string(n));
    // Williams' first row zig-zags from both ends, 0, 1, n-1, 2, n-2, ...: its successive
    // differences are 1, -2, 3, -4, ... (mod n), all distinct for even n, so adding r to every
    // element gives n rows in which each difference, and hence each ordered pair, occurs once.
    std::vector<int> first(n);
    for (int j = 1, low = 1, high = n - 1; j < n; ++j) first[j] = (j % 2 == 1) ? low++ : high--;
    std::vector<std::vector<int>> rows;
    for (int r = 0; r < n; ++r) {
        std::vector<int> row(n);
        for (int j = 0; j < n; ++j) row[j] = (first[j] + r) % n;
        rows.push_back(std::move(row));
    }
    // For odd n a difference and its negative coincide pairwise, so each unordered pair is
    // adjacent twice in one direction; the reversed rows supply the other direction.
    if (n % 2 == 1 && n > 1)
        for (int r = 0; r < n; ++r) rows.push_back(std::vector<int>(rows[r].rbegin(), rows[r].rend()));
    return rows;
}

}  // namespace warplab::plan
