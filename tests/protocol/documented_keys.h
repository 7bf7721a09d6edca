// The keys a protocol page documents, as JSON paths, for the tests that hold a game's parser
// to its page: every "| key |" table's rows under the game's part, in order.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace warplab::protocol {

// The rows of the first "| key |" table under the heading `heading` of the page at `path`.
inline std::vector<std::string> keyTableUnder(const std::string& path, const std::string& heading) {
    std::ifstream doc(path);
    EXPECT_TRUE(doc.good());
    std::vector<std::string> keys;
    std::string line;
    bool under = false, inTable = false;
    while (std::getline(doc, line)) {
        if (line.rfind("# ", 0) == 0 || line.rfind("## ", 0) == 0) {
            if (under) break;
            under = line == heading;
        }
        if (!under) continue;
        if (line.rfind("| key |", 0) == 0)
            inTable = true;
        else if (line.rfind("|", 0) != 0 && inTable)
            break;
        if (inTable && line.rfind("| `", 0) == 0) keys.push_back(line.substr(3, line.find('`', 3) - 3));
    }
    return keys;
}

// A protocol page's keys (docs/protocol.md, a game module's own page) for the game whose part
// starts at the heading `part` ("# The
// falling-sphere click game"), as JSON paths: each "| key |" table's rows, under "## Top
// level" (no prefix), "## `section`" ("section.") or "Each element of `array`:"
// ("section.array[]."). A question list's elements are documented once for every game, under
// "## Questions": "Each element of `questions`: ... [Questions](#questions)" stands for its rows.
inline std::vector<std::string> documentedKeys(const std::string& path, const std::string& part) {
    std::ifstream doc(path);
    EXPECT_TRUE(doc.good());
    std::vector<std::string> keys;
    std::string line, section, prefix;
    bool inPart = false, inTable = false;
    while (std::getline(doc, line)) {
        if (line.rfind("# ", 0) == 0) {
            if (inPart) break;
            inPart = line == part;
            continue;
        }
        if (!inPart) continue;
        if (line.rfind("## ", 0) == 0) {
            const auto open = line.find('`');
            section = open == std::string::npos ? "" : line.substr(open + 1, line.find('`', open + 1) - open - 1);
            prefix = line == "## Top level" ? "" : section.empty() ? "-" : section + ".";
        } else if (line.rfind("Each element of `", 0) == 0) {
            prefix = section + "." + line.substr(17, line.find('`', 17) - 17) + "[].";
            if (line.find("[Questions](#questions)") != std::string::npos)
                for (const std::string& key :
                     keyTableUnder(std::string(WARPLAB_SOURCE_DIR) + "/docs/protocol.md", "## Questions"))
                    keys.push_back(prefix + key);
        }
        if (line.rfind("| key |", 0) == 0)
            inTable = prefix != "-";
        else if (line.rfind("|", 0) != 0)
            inTable = false;
        if (inTable && line.rfind("| `", 0) == 0) keys.push_back(prefix + line.substr(3, line.find('`', 3) - 3));
    }
    return keys;
}

}  // namespace warplab::protocol
