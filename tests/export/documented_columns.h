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

// The page analysts read is the contract: each CSV's documented columns are exactly the
// columns its table writes, in the same order.
// Who played every row (a person, a bot), and where each condition came in the participant's order,
// so that a model can keep people apart and fit order effects without deriving them from `trial`.
TEST(Export, EveryRowSaysWhoPlayedAndWhereItsConditionCameInTheOrder) {
    const std::string source = scratch("kinds/source"), results = scratch("kinds/results");
    auto protocol = nlohmann::json::parse(slurp(std::string(WARPLAB_SOURCE_DIR) + "/protocol/shooter-quick.json"));
    protocol["test"]["conditions"] = {"warp15to120", "conv120"};  // conv15: training's low mode only
    protocol["test"]["interleave"] = false;
    const std::string file = source + "/blocked.json";
    std::ofstream(file) << protocol.dump(2);
    runner::HeadlessRun run;
    run.protocolPath = file;
    run.participant = "P02";
    run.resultsDir = results;
    run.player = "bot:4";
    run.seed = 4;
    std::ostringstream quiet;
    const std::string bot = runner::runHeadless(run, quiet);
    replayedAs(bot, results, "P01", "human (cm_per_360=0, dpi=800, invert_y=0)");

    const std::string out = scratch("kinds/out");
    exporter::ExportOptions all;
    all.allPhases = true;
    exportQuietly(results, out, all);
    const std::map<std::string, std::string> kindOf{{"P01", "human"}, {"P02", "bot"}};
    int test = 0, training = 0;
    for (const auto& r : readCsv(out + "/shots.csv")) {
        EXPECT_EQ(r.at("player_kind"), kindOf.at(r.at("participant")));
        if (r.at("scored_phase") == "true") {
            // Blocked: the protocol's order, which a plan's condition_order writes into it.
            EXPECT_EQ(r.at("condition_position"), r.at("mode") == "warp15to120" ? "1" : "2") << r.at("trial");
            ++test;
        } else {
            EXPECT_EQ(r.at("condition_position"), "") << r.at("phase");
            ++training;
        }
    }
    EXPECT_GT(test, 0);
    EXPECT_GT(training, 0);
    for (const char* name : {"/hitrates.csv", "/pacing.csv", "/sessions.csv"})
        for (const auto& r : readCsv(out + name))
            EXPECT_EQ(r.at("player_kind"), kindOf.at(r.at("participant"))) << name;
    // The human's turn as it played: cm_per_360=0 is the protocol's own 0.0022 rad per count at
    // 800 counts per inch, 2 pi / 0.0022 / 800 inches.
    for (const auto& r : readCsv(out + "/sessions.csv")) {
        if (r.at("participant") == "P01")
            EXPECT_NEAR(std::stod(r.at("cm_per_360")), 2 * M_PI / 0.0022 / 800 * 2.54, 1e-9);
        else
            EXPECT_EQ(r.at("cm_per_360"), "");
    }
    std::map<std::string, std::string> usedIn;
    for (const auto& r : readCsv(out + "/conditions.csv")) usedIn[r.at("condition")] = r.at("used_in");
    EXPECT_EQ(
        usedIn,
        (std::map<std::string, std::string>{{"conv120", "test"}, {"conv15", "training"}, {"warp15to120", "test"}}));
}

TEST(Export, AnOutputFolderThatCannotBeMadeSaysWhy) {
    // The folder first: scratch() empties what it names, so the results inside come after.
    const std::string inTheWay = scratch("no-out") + "/a-file";
    const std::string results = scratch("no-out/results");
    headless("shooter-quick.json", "P01", results, 1);
    std::ofstream(inTheWay) << "not a folder\n";
    try {
        exportQuietly(results, inTheWay + "/out");
        FAIL() << "exported under a file";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot create the output folder '" + inTheWay + "/out': Not a directory"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace warplab::testing_docs
