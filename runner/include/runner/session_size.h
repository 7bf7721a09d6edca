// How much disk a session of a protocol takes, known before it starts: `warplab check`
// compares it with the results folder's free space, and a live `run` refuses a folder
// without room for it before its window opens. No GL.
#pragma once

#include <cstdint>
#include <string>

#include "game/game.h"

namespace warplab::runner {

struct SessionSize {
    // The protocol's frames as its bot plays it to the end, seed 1 (no store, no rendering).
    std::int64_t botFrames = 0;
    // A session file's bytes per frame, measured: the first kSampleFrames of that play (every
    // row a session writes: input, frame, events, commits) written to a session store in the
    // system's temporary folder, and removed. And the file with its header alone.
    double bytesPerFrame = 0.0;
    std::uint64_t headerBytes = 0;

    // A participant's session: the bot's frames times kSlowerParticipant.
    std::uint64_t sessionBytes() const;
    // The free space it needs: kFinishCopies times that, since finishing a session (or
    // rescuing one whose file was replaced) may write it again beside itself before the old
    // one goes (docs/session-format.md, "Crash safety").
    std::uint64_t neededBytes() const;

    static constexpr std::int64_t kSampleFrames = 2400;  // 20 s at 120 Hz: rows and commits both
    // The bot shoots within a second or two and answers every question at once; a participant
    // may take a trial to its timeout and a rating screen as long as they like. shooter-thesis
    // at every trial's timeout is 1.8 times the bot's 2070 s of display, click-yang with 20 s
    // per rating screen 1.4 times its 999 s.
    static constexpr double kSlowerParticipant = 2.0;
    static constexpr double kFinishCopies = 2.0;
};

// Plays the study with its bot and measures a sample of what the store writes. Throws
// session::SessionError when the sample cannot be written (no temporary folder).
SessionSize estimateSessionSize(const game::Study& study, const game::DisplaySize& display);

// The bytes an unprivileged process may still write to the file system holding `folder`;
// throws std::runtime_error naming the folder when it cannot be read.
std::uint64_t freeBytes(const std::string& folder);

// "512 kB", "43.0 MB", "1.2 GB" (powers of 1000, as disks are sold and `df -H` shows them).
std::string bytesText(std::uint64_t bytes);

// Throws std::runtime_error naming the folder, its free space and what a session of `protocol`
// needs, when the folder has less room than that (a sentence the caller ends with its advice).
void requireDiskSpace(const std::string& folder, const SessionSize& size, const std::string& protocol);

}  // namespace warplab::runner
