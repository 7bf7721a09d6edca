// The columns a page documents for a CSV file: export's own files in docs/export.md, a game's
// own tables on its page. The pages analysts read are the contract, so tests hold each file's
// columns to them.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace warplab::testing_docs {

namespace fs = std::filesystem;

// A page's column list for `file` ("### sessions.csv -- ..."): the backticked names
// in the first cell of its table's rows, or, for a file described in a sentence, the names of
// the backticked list that opens it ("`a, b (unit), c`"). "x_1 ... x_N" is given as "x_" in
// `numbered`.
struct DocumentedColumns {
    std::vector<std::string> columns;
    std::string numbered;
};

// The pages that list a section "### FILE -- ...": export.md for its own files, a game's page
// (docs/NAME.md, or a test game's README.md) for the game's own tables.
inline std::vector<std::string> pagesDocumenting(const std::string& file) {
    std::vector<fs::path> pages;
    for (const auto& e : fs::directory_iterator(std::string(WARPLAB_SOURCE_DIR) + "/docs"))
        if (e.path().extension() == ".md") pages.push_back(e.path());
    for (const auto& e : fs::directory_iterator(std::string(WARPLAB_SOURCE_DIR) + "/tests/games"))
        if (fs::exists(e.path() / "README.md")) pages.push_back(e.path() / "README.md");
    std::vector<std::string> out;
    for (const fs::path& page : pages) {
        std::ifstream doc(page);
        for (std::string line; std::getline(doc, line);)
            if (line.rfind("### " + file + " ", 0) == 0) {
                out.push_back(page.string());
                break;
            }
    }
    return out;
}

inline DocumentedColumns documentedColumns(const std::string& file, const std::string& page) {
    std::ifstream doc(page);
    EXPECT_TRUE(doc.good()) << page;
    DocumentedColumns out;
    std::string line, list;
    bool inSection = false, inList = false, listDone = false;
    while (std::getline(doc, line)) {
        if (line.rfind("#", 0) == 0) {
            if (inSection) break;
            inSection = line.rfind("### " + file + " ", 0) == 0;
            continue;
        }
        if (!inSection) continue;
        if (line.rfind("| `", 0) == 0) {
            const std::string cell = line.substr(1, line.find('|', 1) - 1);
            for (std::size_t open = cell.find('`'); open != std::string::npos;) {
                const std::size_t close = cell.find('`', open + 1);
                out.columns.push_back(cell.substr(open + 1, close - open - 1));
                open = cell.find('`', close + 1);
            }
        } else if (!listDone && (inList || line.rfind("`", 0) == 0)) {
            const std::size_t from = inList ? 0 : 1;
            const std::size_t close = line.find('`', from);
            list += " " + line.substr(from, close == std::string::npos ? std::string::npos : close - from);
            inList = close == std::string::npos;
            listDone = !inList;
        }
    }
    std::stringstream items(list);
    for (std::string item; std::getline(items, item, ',');) {
        if (const auto paren = item.find('('); paren != std::string::npos) item.erase(paren);
        item.erase(0, item.find_first_not_of(' '));
        item.erase(item.find_last_not_of(' ') + 1);
        if (const auto dots = item.find(" ... "); dots != std::string::npos) {
            out.numbered = item.substr(0, item.find('1'));
            EXPECT_EQ(item, out.numbered + "1 ... " + out.numbered + "N");
        } else if (!item.empty()) {
            out.columns.push_back(item);
        }
    }
    return out;
}

}  // namespace warplab::testing_docs
