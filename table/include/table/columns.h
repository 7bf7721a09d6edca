// A CSV file's columns as one table: export's files and bench.csv.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "table/csv.h"

namespace warplab::table {

// One column of a CSV: its header name and how a row's cell is written. Each file's columns
// are one table, which its header and every row walk, so the two cannot drift apart (and
// docs/export.md is checked against export's tables).
template <class Row>
struct Column {
    const char* name;
    std::function<void(CellWriter&, const Row&)> write;  // into a file or a kept row
};

template <class Row>
std::vector<std::string> headerOf(const std::vector<Column<Row>>& columns) {
    std::vector<std::string> names;
    for (const auto& c : columns) names.emplace_back(c.name);
    return names;
}

template <class Row>
void writeCells(CellWriter& file, const std::vector<Column<Row>>& columns, const Row& row) {
    for (const auto& c : columns) c.write(file, row);
}

}  // namespace warplab::table
