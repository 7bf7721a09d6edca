// Private to app/: playing a protocol headlessly (bot or recorded input) into a session store,
// and replaying a stored session to check every logged outcome.
#pragma once

#include <cstdint>
#include <memory>
#include <ostream>
#include <string>

#include "game/game.h"
#include "protocol/session_store.h"

namespace warplab::app {

struct HeadlessRun {
    std::string protocolPath;
    std::string participant;
    std::string resultsDir;
    std::string player;        // "bot", "bot:SEED" or "replay:SESSION"
    std::uint64_t seed = 1;    // the session seed: trial order and target spawns
    int displayWidth = 1920;   // the display the session stands for (fits the target plane)
    int displayHeight = 1080;
};

// What headless and live runs share.
std::unique_ptr<game::Player> makePlayer(const std::string& player, std::uint64_t sessionSeed,
                                         const game::Study& study, const game::DisplaySize& display);
protocol::SessionHeader sessionHeader(const game::Study& study, const std::string& participant, std::uint64_t seed,
                                      const std::string& player, const game::DisplaySize& display);
protocol::InputRecord toRecord(std::int64_t frame, double time, const game::FrameInput& in);

// Plays the whole protocol; returns the session file's path.
std::string runHeadless(const HeadlessRun& run, std::ostream& progress);

struct ReplayResult {
    std::size_t outcomes = 0;      // scored outcomes logged (shots and timeouts, clicks)
    std::size_t reproduced = 0;    // ... and replayed identically
    std::size_t events = 0;        // all events compared
    std::string difference;        // first difference, "" when none
    std::string note;              // why the session ends early, "" when complete
    bool completed = false;        // the session finished and nothing was lost
    bool damaged = false;          // committed data was lost or altered (SessionData::damaged)
    double seconds = 0.0;          // wall time of the replay itself
    double displaySeconds = 0.0;   // display time the session covers
};

// What `warplab replay` exits with, so that a script can tell a session worth keeping from one
// that is not (README "Exit codes"): 0 only for an intact session whose every outcome replayed.
enum ReplayExit : int {
    kReplayReproduced = 0,
    kReplayDiffers = 1,     // a logged record differs from the replayed one
    kReplayIncomplete = 3,  // the session never finished (killed, ended early, still running); all it holds replays
    kReplayDamaged = 4,     // committed data was lost or altered, or the file is unreadable
};
int replayExitCode(const ReplayResult& result);

// Re-runs the session from its store without a window and without rendering.
ReplayResult replaySession(const std::string& sessionPath);

}  // namespace warplab::app
