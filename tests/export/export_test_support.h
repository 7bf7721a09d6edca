// What the export tests share: a scratch folder, a headless session, an export, and a CSV
// reader written independently of the exporter's.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "export/export.h"
#include "runner/session_runner.h"

namespace warplab::app::exporttest {

namespace fs = std::filesystem;
using Row = std::map<std::string, std::string>;

inline std::string scratch(const std::string& name) {
    const fs::path dir = fs::path(WARPLAB_BINARY_DIR) / "test-output" / "export" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// RFC 4180, written independently of the exporter: quoted cells, doubled quotes, line breaks
// inside quotes. Every row must have as many cells as the header.
inline std::vector<Row> readCsv(const std::string& path) {
    const std::string text = slurp(path);
    std::vector<std::vector<std::string>> rows(1);
    std::string cell;
    bool quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"')
                cell += '"', ++i;
            else if (c == '"')
                quoted = false;
            else
                cell += c;
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            rows.back().push_back(cell);
            cell.clear();
        } else if (c == '\n') {
            rows.back().push_back(cell);
            cell.clear();
            rows.emplace_back();
        } else {
            cell += c;
        }
    }
    EXPECT_TRUE(rows.back().empty() && cell.empty()) << path << " does not end with a line break";
    rows.pop_back();
    std::vector<Row> out;
    if (rows.empty()) {
        ADD_FAILURE() << path << " has no header";
        return out;
    }
    for (std::size_t r = 1; r < rows.size(); ++r) {
        EXPECT_EQ(rows[r].size(), rows[0].size()) << path << " row " << r;
        Row row;
        for (std::size_t k = 0; k < rows[0].size() && k < rows[r].size(); ++k) row[rows[0][k]] = rows[r][k];
        out.push_back(row);
    }
    return out;
}

// The header row's names.
inline std::vector<std::string> headerOf(const std::string& path) {
    std::string line = slurp(path);
    line = line.substr(0, line.find('\n'));
    std::vector<std::string> names;
    std::stringstream s(line);
    for (std::string name; std::getline(s, name, ',');) names.push_back(name);
    return names;
}

inline std::string headless(const std::string& protocol, const std::string& participant, const std::string& dir,
                            std::uint64_t seed) {
    runner::HeadlessRun run;
    run.protocolPath = std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + protocol;
    run.participant = participant;
    run.resultsDir = dir;
    run.player = "bot:" + std::to_string(seed);
    run.seed = seed;
    std::ostringstream quiet;
    return runner::runHeadless(run, quiet);
}

inline exporter::ExportSummary exportQuietly(const std::string& results, const std::string& out,
                                             const exporter::ExportOptions& options = {}, std::string* log = nullptr) {
    std::ostringstream lines;
    exporter::ExportSummary summary = exporter::exportResults(results, out, options, lines);
    if (log != nullptr) *log = lines.str();
    return summary;
}

}  // namespace warplab::app::exporttest
