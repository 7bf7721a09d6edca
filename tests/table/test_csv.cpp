// The column-table CSV writer on its own, with no module but table/ linked: a formatted number
// is written as its caller spelled it, and a cell that would split the row is refused.
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "table/columns.h"
#include "table/csv.h"

namespace warplab::table {
namespace {

struct Point {
    std::string name;
    double x = 0.0;
};

const std::vector<Column<Point>>& pointColumns() {
    static const std::vector<Column<Point>> columns = {
        {"name", [](table::CellWriter& f, const Point& p) { f.text(p.name); }},
        {"x", [](table::CellWriter& f, const Point& p) { f.formatted(std::to_string(p.x)); }},
    };
    return columns;
}

TEST(TableCsv, WritesTheHeaderAndRowsThroughOneTable) {
    std::ostringstream out;
    CsvFile csv(out, headerOf(pointColumns()), "points.csv");
    for (const Point& p : {Point{"a", -0.5}, Point{"-b", 2.0}}) {
        writeCells(csv, pointColumns(), p);
        csv.endRow();
    }
    // A formatted number keeps its sign; a text beginning with '-' is escaped for spreadsheets.
    EXPECT_EQ(out.str(), "name,x\na,-0.500000\n'-b,2.000000\n");
    EXPECT_EQ(csv.rows(), 2);
    EXPECT_EQ(csv.path(), "points.csv");
}

TEST(TableCsv, AFormattedCellThatWouldSplitTheRowIsRefused) {
    std::ostringstream out;
    CsvFile csv(out, {"x"}, "points.csv");
    for (const std::string bad : {"1,5", "\"1\"", "1\n", "1\r"})
        EXPECT_THROW(csv.formatted(bad), std::logic_error) << bad;
    EXPECT_NO_THROW(csv.formatted("-1.5e-3"));
}

}  // namespace
}  // namespace warplab::table
