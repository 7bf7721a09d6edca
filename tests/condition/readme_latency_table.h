// The README's latency table ("## Conditions and their latency"), read as the tests that check it
// need it: each row's condition and its view and scene latency cells, and the display refreshes the
// section says the table holds at. Read in one place, so every test that holds the table to
// the schedule or to a real run reads the same cells.
#pragma once

#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace warplab::readme {

struct ReadmeLatencyRow {
    std::string id;
    double viewMinMs = -1, viewMaxMs = -1, sceneMinMs = -1, sceneMaxMs = -1;
};

struct ReadmeLatencyTable {
    std::vector<ReadmeLatencyRow> rows;
    // Every "N Hz display" the section names: the table's own (120) and the click game's (60),
    // which "runs the same schedules".
    std::set<double> displayRatesHz;
};

inline ReadmeLatencyTable readmeLatencyTable() {
    std::ifstream doc(std::string(WARPLAB_SOURCE_DIR) + "/README.md");
    EXPECT_TRUE(doc.good());
    ReadmeLatencyTable table;
    bool inSection = false;
    for (std::string line; std::getline(doc, line);) {
        if (line.rfind("## ", 0) == 0) inSection = line == "## Conditions and their latency";
        if (!inSection) continue;
        for (std::size_t at = line.find(" Hz display"); at != std::string::npos;
             at = line.find(" Hz display", at + 1)) {
            const std::size_t start = line.find_last_not_of("0123456789", at - 1) + 1;
            if (start < at) table.displayRatesHz.insert(std::stod(line.substr(start, at - start)));
        }
        if (line.rfind("| `", 0) != 0) continue;
        std::vector<std::string> cells;
        for (std::size_t at = 1, next; (next = line.find(" |", at)) != std::string::npos; at = next + 2)
            cells.push_back(line.substr(at + 1, next - at - 1));
        EXPECT_GE(cells.size(), 6u) << line;
        if (cells.size() < 6) continue;
        ReadmeLatencyRow row;
        row.id = cells[0].substr(1, cells[0].find('`', 1) - 1);
        // "A – B ms ..." -> A, B
        auto range = [&](const std::string& cell, double& a, double& b) {
            const std::size_t dash = cell.find(" – ");
            EXPECT_NE(dash, std::string::npos) << row.id << ": " << cell;
            if (dash == std::string::npos) return;
            a = std::stod(cell.substr(0, dash));
            b = std::stod(cell.substr(dash + 5));  // " – " is 5 bytes in UTF-8
        };
        range(cells[4], row.viewMinMs, row.viewMaxMs);
        if (cells[5] == "same as view") {
            row.sceneMinMs = row.viewMinMs;
            row.sceneMaxMs = row.viewMaxMs;
        } else {
            range(cells[5], row.sceneMinMs, row.sceneMaxMs);
        }
        table.rows.push_back(row);
    }
    EXPECT_FALSE(table.rows.empty()) << "README.md has no latency table";
    return table;
}

}  // namespace warplab::readme
