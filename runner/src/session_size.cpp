#include "runner/session_size.h"

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "runner/session_runner.h"

namespace warplab::runner {
namespace {

namespace fs = std::filesystem;

// A scratch folder of this process's own, removed with everything in it.
class ScratchFolder {
public:
    ScratchFolder() {
        static std::atomic<int> counter{0};
        path_ = fs::temp_directory_path() /
            ("warplab-size-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::create_directories(path_);
    }
    ~ScratchFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    std::string path() const { return path_.string(); }

private:
    fs::path path_;
};

// Longer than any protocol plays: a bot that never finished would otherwise hold the check.
constexpr double kMaxDisplaySeconds = 24 * 3600.0;

}  // namespace

std::uint64_t SessionSize::sessionBytes() const {
    return headerBytes + static_cast<std::uint64_t>(std::ceil(bytesPerFrame * botFrames * kSlowerParticipant));
}

std::uint64_t SessionSize::neededBytes() const {
    return static_cast<std::uint64_t>(std::ceil(sessionBytes() * kFinishCopies));
}

SessionSize estimateSessionSize(const game::Study& study, const game::DisplaySize& display) {
    constexpr std::uint64_t kSeed = 1;
    const auto game = study.newGame(kSeed, display);
    const auto bot = makePlayer("bot", kSeed, study, display);
    const auto maxFrames = static_cast<std::int64_t>(kMaxDisplaySeconds * study.refreshHz());

    SessionSize size;
    ScratchFolder scratch;
    std::optional<session::SessionWriter> sample =
        session::SessionWriter::create(scratch.path(), sessionHeader(study, "size", kSeed, "bot", display));
    size.headerBytes = fs::file_size(sample->path());
    auto measure = [&] {
        sample->commit();
        size.bytesPerFrame = static_cast<double>(fs::file_size(sample->path()) - size.headerBytes) /
            static_cast<double>(std::max<std::int64_t>(1, size.botFrames));
        sample.reset();
    };
    game::FrameInput input = bot->first();
    while (!game->finished() && bot->hasMore() && size.botFrames < maxFrames) {
        const game::ShownFrame shown = game->step(input);
        if (sample) {
            sample->addInput(toRecord(shown.frame, shown.time, input));
            sample->addFrame(game->frameRecord(shown));
            for (auto& e : game->takeEvents()) sample->addEvent(e);
            if (game->atCommitPoint()) sample->commit();
        } else {
            game->takeEvents();
        }
        ++size.botFrames;
        if (sample && size.botFrames == SessionSize::kSampleFrames) measure();
        input = bot->next(shown);
    }
    if (sample) measure();
    return size;
}

std::uint64_t freeBytes(const std::string& folder) {
    std::error_code error;
    const fs::space_info space = fs::space(folder, error);
    if (error)
        throw std::runtime_error("cannot read the free space of results folder '" + folder + "': " + error.message());
    return space.available;
}

std::string bytesText(std::uint64_t bytes) {
    char text[32];
    if (bytes < 1000 * 1000)
        std::snprintf(text, sizeof text, "%.0f kB", std::ceil(bytes / 1e3));
    else if (bytes < 1000ull * 1000 * 1000)
        std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
    else
        std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
    return text;
}

void requireDiskSpace(const std::string& folder, const SessionSize& size, const std::string& protocol) {
    const std::uint64_t free = freeBytes(folder);
    if (free >= size.neededBytes()) return;
    throw std::runtime_error("Results folder '" + folder + "' has " + bytesText(free) + " free but a session of " +
                             protocol + " needs " + bytesText(size.neededBytes()) + " (its file, about " +
                             bytesText(size.sessionBytes()) + ", may be written twice as it finishes)");
}

}  // namespace warplab::runner
