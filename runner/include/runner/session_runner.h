// Playing a protocol headlessly (bot or recorded input) into a session store,
// and replaying a stored session to check every logged outcome.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include "game/game.h"
#include "session/session_store.h"

namespace warplab::runner {

struct HeadlessRun {
    std::string protocolPath;
    // A study plan's run (run --study): the participant's own protocol text, which protocolPath
    // then only names in messages, and the plan's id for the session header. Both empty
    // otherwise: the file is the protocol.
    std::string protocolText, planId;
    std::string participant;
    std::string resultsDir;
    // An interrupted session to carry on (runner/resume.h): its protocol, seed, participant,
    // display and plan replace the run's own.
    std::string resumeFrom;
    std::string player;  // "bot", "bot:SEED", "sim", "sim:SEED" or "replay:SESSION"
    std::uint64_t seed = 1;  // the session seed: trial order and target spawns
    int displayWidth = 1920;  // the display the session stands for (fits the target plane)
    int displayHeight = 1080;
    // Makes the "sim" players, which draw what they see; unset: "sim" is refused.
    game::SeeingPlayerMaker seeingPlayer;
};

// True for the player specs of the perceptual simulated participant ("sim", "sim:SEED").
bool isSimulatedParticipant(const std::string& player);
// Throws std::invalid_argument, in the words makePlayer would use, when `player` is not a form
// run --player takes (human, bot[:SEED], sim[:SEED], replay:SESSION); reads no file.
void checkPlayer(const std::string& player);
// The SESSION of "replay:SESSION", the recorded session whose input the player plays; "" for
// the other players.
std::string replaySource(const std::string& player);

// What headless and live runs share. `seeing` makes the "sim" players, which only run headless
// (unset: "sim" is refused with a sentence saying so).
std::unique_ptr<game::Player> makePlayer(const std::string& player, std::uint64_t sessionSeed, const game::Study& study,
                                         const game::DisplaySize& display, const game::SeeingPlayerMaker& seeing = {});
// The study a run plays: `protocolText` when given (named by `protocolPath`), else the file.
std::unique_ptr<game::Study> loadRunStudy(const std::string& protocolPath, const std::string& protocolText);
session::SessionHeader sessionHeader(const game::Study& study, const std::string& participant, std::uint64_t seed,
                                     const std::string& player, const game::DisplaySize& display);
session::InputRecord toRecord(std::int64_t frame, double time, const game::FrameInput& in);

// When a running session commits, and what the supervisor hears about its file. Shared by
// the headless and the live loop.
class SessionCommits {
public:
    // The longest stretch of display time whose rows wait in memory without a commit: a
    // long phase (acclimation, a slow trial) is committed in parts, so a kill loses at most
    // this much and the rows held stay small.
    static constexpr double kMaxSecondsBetweenCommits = 10.0;

    SessionCommits(session::SessionWriter& writer, double refreshHz, std::ostream& progress);

    // After each frame's rows are added: commits at the game's commit points (each trial's
    // end, each phase change), at least every kMaxSecondsBetweenCommits, and about once a
    // second while commits wait for another program's write lock. Never waits.
    void afterFrame(std::int64_t frame, bool commitPoint);
    // While commits wait for the write lock: one line for the supervisor; "" otherwise.
    std::string waitingText() const;
    // The end: finish() when the protocol ran to its end, else a commit; either way waits as
    // long as another program holds the write lock, calling `show(line)` about once a second
    // (and saying so on `progress` every few seconds) until everything is written.
    void end(bool completed, const std::function<void(const std::string&)>& show = {});

private:
    void tell();
    session::SessionWriter& writer_;
    std::ostream& progress_;
    std::int64_t maxFrames_, retryFrames_;
    std::int64_t lastCommit_ = 0, lastTry_ = 0;
    bool waiting_ = false;  // said that commits wait, not yet that they are written
};

// Plays the whole protocol; returns the session file's path.
std::string runHeadless(const HeadlessRun& run, std::ostream& progress);

struct ReplayResult {
    std::size_t outcomes = 0;  // scored outcomes logged (shots and timeouts, clicks)
    std::size_t reproduced = 0;  // ... and replayed identically
    std::size_t events = 0;  // all events compared
    std::string difference;  // first difference, "" when none
    std::string note;  // why the session ends early, "" when complete
    bool completed = false;  // the session finished and nothing was lost
    bool damaged = false;  // committed data was lost or altered (SessionData::damaged)
    double seconds = 0.0;  // wall time of the replay itself
    double displaySeconds = 0.0;  // display time the session covers
    std::int64_t frames = 0;  // display frames replayed
};

// What `warplab replay` exits with, so that a script can tell a session worth keeping from one
// that is not (README "Exit codes"): 0 only for an intact session whose every outcome replayed.
// A difference has a code of its own: it says the game no longer plays as it was recorded,
// where any other error (exit 1) says nothing about the session.
enum ReplayExit : int {
    kReplayReproduced = 0,
    kReplayFailed = 1,  // an error that is not the session's: as for every command (2 is a bad command line)
    kReplayIncomplete = 3,  // the session never finished (killed, ended early, still running); all it holds replays
    kReplayDamaged = 4,  // committed data was lost or altered, or the file is unreadable
    kReplayDiffers = 5,  // a logged record differs from the replayed one
};
int replayExitCode(const ReplayResult& result);

// Re-runs the session from its store without a window and without rendering.
ReplayResult replaySession(const std::string& sessionPath);

}  // namespace warplab::runner
