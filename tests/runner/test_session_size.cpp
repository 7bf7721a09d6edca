// A session's size known before it starts (runner/session_size.h), against the file a whole
// headless session of the same protocol and bot really writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "runner/session_runner.h"
#include "runner/session_size.h"

namespace warplab::runner {
namespace {

namespace fs = std::filesystem;

std::string scratch(const std::string& name) {
    const fs::path dir = fs::path(WARPLAB_BINARY_DIR) / "test-output" / "session-size" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

TEST(SessionSize, TheEstimateIsWhatTheBotsWholeSessionWrites) {
    for (const std::string protocol : {"shooter-quick", "click-quick"}) {
        const std::string path = std::string(WARPLAB_SOURCE_DIR) + "/protocol/" + protocol + ".json";
        const auto study = loadRunStudy(path, "");
        const game::DisplaySize display{1920, 1080};
        const SessionSize size = estimateSessionSize(*study, display);

        HeadlessRun run;
        run.protocolPath = path;
        run.participant = "size";
        run.resultsDir = scratch(protocol);
        run.player = "bot:1";  // the estimate's player and seed
        run.seed = 1;
        std::ostringstream progress;
        const std::string session = runHeadless(run, progress);
        const double written = static_cast<double>(fs::file_size(session));
        const double estimated = static_cast<double>(size.headerBytes) + size.bytesPerFrame * size.botFrames;
        // The sample is the session's first 20 s; later phases write rows of much the same size.
        EXPECT_NEAR(estimated / written, 1.0, 0.15)
            << protocol << ": " << size.botFrames << " frames at " << size.bytesPerFrame << " bytes, file " << written;
        EXPECT_GT(size.sessionBytes(), written) << "a participant's session is the bot's, longer";
        EXPECT_EQ(size.neededBytes(), static_cast<std::uint64_t>(std::ceil(size.sessionBytes() * 2.0)));
    }
}

TEST(SessionSize, AFolderWithoutRoomIsRefusedNamingWhatIsFreeAndWhatIsNeeded) {
    const std::string dir = scratch("no-room");
    SessionSize huge;
    huge.botFrames = 1'000'000'000'000;  // far more than any disk: 1e12 frames at 100 bytes
    huge.bytesPerFrame = 100.0;
    try {
        requireDiskSpace(dir, huge, "shooter-thesis");
        FAIL() << "no refusal";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("Results folder '" + dir + "' has ", 0), 0u) << what;
        EXPECT_NE(what.find(" free but a session of shooter-thesis needs 400000.0 GB (its file, about 200000.0 GB, "
                            "may be written twice as it finishes)"),
                  std::string::npos)
            << what;
    }
    SessionSize small;
    small.botFrames = 10;
    small.bytesPerFrame = 100.0;
    EXPECT_NO_THROW(requireDiskSpace(dir, small, "shooter-quick"));
}

TEST(SessionSize, BytesAreSaidAsDisksAreSold) {
    EXPECT_EQ(bytesText(512), "1 kB");
    EXPECT_EQ(bytesText(43'024'384), "43.0 MB");
    EXPECT_EQ(bytesText(1'200'000'000), "1.2 GB");
}

}  // namespace
}  // namespace warplab::runner
