// The session format's version where the docs state it -- the README's summary and the title of
// docs/session-format.md -- against the constants the writer and reader use, so that a new
// version cannot leave the README promising an old one.
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "session/session_store.h"

namespace warplab::session {
namespace {

std::string sourceText(const std::string& relative) {
    std::ifstream in(std::string(WARPLAB_SOURCE_DIR) + "/" + relative);
    EXPECT_TRUE(in.good()) << relative;
    std::ostringstream text;
    text << in.rdbuf();
    // The README wraps its lines; a phrase may break anywhere.
    std::string flat = text.str();
    for (char& c : flat)
        if (c == '\n') c = ' ';
    return flat;
}

TEST(SessionFormatDocs, TheReadmeStatesTheVersionWrittenAndTheVersionsRead) {
    const std::string expected = "`docs/session-format.md`; format " + std::to_string(kSessionFormatVersion) +
        ", which also reads formats " + std::to_string(kOldestSessionFormatVersion) + " to " +
        std::to_string(kSessionFormatVersion - 1) + ")";
    EXPECT_NE(sourceText("README.md").find(expected), std::string::npos) << "README.md should say: " << expected;
}

TEST(SessionFormatDocs, TheFormatPageIsTitledWithTheVersionWritten) {
    const std::string title = "# Session file format (version " + std::to_string(kSessionFormatVersion) + ")";
    EXPECT_EQ(sourceText("docs/session-format.md").rfind(title, 0), 0u) << "its first line should be: " << title;
}

}  // namespace
}  // namespace warplab::session
