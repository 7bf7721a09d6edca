// Balanced Latin squares against their definition (Williams 1949), counted directly: every row
// an order of 0..n-1, each condition in each position equally often, each ordered adjacent pair
// equally often. The counts are the oracle, not the construction.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "plan/latin_square.h"

namespace warplab::plan {
namespace {

TEST(LatinSquare, IsBalancedForPositionsAndAdjacentPairs) {
    for (int n = 1; n <= 9; ++n) {
        SCOPED_TRACE("n = " + std::to_string(n));
        const auto rows = balancedLatinSquare(n);
        // Odd n needs the reversed rows for balance; one condition has no pairs to balance.
        const int copies = (n % 2 == 1 && n > 1) ? 2 : 1;
        ASSERT_EQ(rows.size(), static_cast<std::size_t>(n * copies));

        std::vector<int> identity(n);
        std::iota(identity.begin(), identity.end(), 0);
        std::vector<std::vector<int>> atPosition(n, std::vector<int>(n, 0));
        std::vector<std::vector<int>> followedBy(n, std::vector<int>(n, 0));
        for (const auto& row : rows) {
            std::vector<int> sorted = row;
            std::sort(sorted.begin(), sorted.end());
            ASSERT_EQ(sorted, identity) << "a row is not an order of 0..n-1";
            for (int j = 0; j < n; ++j) ++atPosition[row[j]][j];
            for (int j = 0; j + 1 < n; ++j) ++followedBy[row[j]][row[j + 1]];
        }
        for (int c = 0; c < n; ++c)
            for (int j = 0; j < n; ++j) EXPECT_EQ(atPosition[c][j], copies) << c << " at position " << j;
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) EXPECT_EQ(followedBy[a][b], a == b ? 0 : copies) << a << " then " << b;
    }
}

TEST(LatinSquare, OneConditionIsOneRow) { EXPECT_EQ(balancedLatinSquare(1), (std::vector<std::vector<int>>{{0}})); }

TEST(LatinSquare, RefusesSizesOutsideItsRange) {
    EXPECT_THROW(balancedLatinSquare(0), std::invalid_argument);
    EXPECT_THROW(balancedLatinSquare(-3), std::invalid_argument);
    EXPECT_THROW(balancedLatinSquare(kMaxLatinSquareSize + 1), std::invalid_argument);
    EXPECT_THROW(balancedLatinSquare(1 << 30), std::invalid_argument);
    EXPECT_NO_THROW(balancedLatinSquare(kMaxLatinSquareSize));
}

}  // namespace
}  // namespace warplab::plan
