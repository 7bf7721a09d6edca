// Resuming an interrupted session (warplab run --resume, docs/live-sessions.md "Resuming"). A
// session is a pure function of its protocol, seed and input, so its recorded input can be
// played again exactly: up to the end of its last completed trial or match (the game's last
// commit point), every stored event checked on the way. A new session starts from those
// frames, copied with their stored rows, and plays on from there; it replays as a whole and
// its header names the session it carries on (SessionHeader::resumed).
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include "game/game.h"
#include "session/session_store.h"

namespace warplab::runner {

// A session that cannot be resumed: one sentence naming its file and why (exit 1).
class ResumeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ResumePoint {
    std::string path;  // the interrupted session
    session::SessionData stored;  // what it holds
    // Its first keptInputs input rows (frames 0 .. resumeFrame - 1) are kept, through the end of
    // its last completed trial or match, with the frame and event rows of those frames.
    std::size_t keptInputs = 0, keptFrames = 0, keptEvents = 0;
    std::int64_t resumeFrame = 0;  // the first frame played after resuming
    std::size_t keptOutcomes = 0;  // scored outcomes (shots and timeouts, clicks) kept, of every phase
    game::Progress kept;  // what of the protocol's plan is kept, as a supervisor counts it (test trials, matches)
    std::size_t droppedOutcomes = 0;  // ... recorded after the last commit point, to be played again
};

// Reads `sessionPath` and plays its recorded input again, checking every stored event. Throws
// ResumeError when it is complete (nothing to resume), damaged, older than session format 3
// (no session id to name it by), or does not replay as it was recorded (naming the first
// difference); session::SessionError when it cannot be read at all.
ResumePoint findResumePoint(const std::string& sessionPath);

// The header of the session that carries `point` on: `now` (what runs it: player, app, GL,
// refresh) with the interrupted session's protocol, seed, participant, display and plan, and
// its `resumed` list extended by it. create() draws the session id and start time.
session::SessionHeader resumedHeader(const ResumePoint& point, const session::SessionHeader& now);

// The kept frames' stored rows (frames with the timings measured when they were shown): the
// first commit of the session that carries `point` on (SessionWriter::create).
session::SessionWriter::FirstCommit keptRows(const ResumePoint& point);

// Steps `game` (new, from the stored protocol and seed) through the kept frames, calling
// seen(shown) after each, so that a player or a frame maker learns what was on screen. The
// game then stands where the interrupted session's last completed trial or match left it, told
// that play goes on from here (Game::resumeHere), as each replay of the resumed file tells it.
void replayKeptFrames(const ResumePoint& point, game::Game& game,
                      const std::function<void(const game::ShownFrame&)>& seen);

// One line for the supervisor: what is kept and what is played again.
std::string resumeSummary(const ResumePoint& point);

}  // namespace warplab::runner
