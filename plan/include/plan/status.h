// Where a study stands: for each participant of a plan and each of their protocols, what the
// sessions in the plan's results folder hold (docs/study-plan.md, "Running the study").
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "game/game.h"
#include "plan/study_plan.h"
#include "session/results_lock.h"
#include "session/session_store.h"

namespace warplab::plan {

// The results folder of a plan: where run --study writes its sessions. A rig (a booth, a
// machine) has a folder of its own inside it, DIR/results/RIG, so that its lock never blocks
// another rig's run; "" is DIR/results itself. Status, run --resume and export read them all.
std::string resultsFolder(const std::string& planDir, const std::string& rig = "");

// Why `rig` cannot name a rig's folder ("" when it can): one path component of letters, digits,
// '-', '_' and '.', not starting with '.', at most 64 bytes.
std::string rigNameProblem(const std::string& rig);

// The plan's results folders: DIR/results ("") and each rig folder inside it, by name.
std::vector<std::string> rigsOf(const std::string& planDir);

// "rig booth-a" or "the results folder itself": where a session lies, for a sentence.
std::string rigText(const std::string& rig);

// From best to worst: what counts when a participant has several sessions of one protocol.
enum class SessionState { Done, Flagged, Incomplete, Damaged, NotStarted };
const char* stateName(SessionState state);  // "done", "flagged", "incomplete", "damaged", "not started"

struct ProtocolStatus;
// The state as the supervisor reads it: the name, and for an incomplete or damaged session how
// far it got, e.g. "incomplete (17 of 675 test trials)".
std::string stateText(const ProtocolStatus& status);

struct ProtocolStatus {
    int protocolIndex = 0;  // into StudyPlan::protocols
    SessionState state = SessionState::NotStarted;
    std::string detail;  // the best session's file name and, when not done, why (its note or flags)
    int sessions = 0;  // of this participant and protocol, in the results folder
    // How far the best session got, as its game counts (Study::progress): `done` of `planned`
    // `unit` ("test trials", "matches"); all 0 and "" when not started.
    std::size_t done = 0, planned = 0;
    std::string unit;
    // The last (by file name) incomplete session that is not damaged: what run --resume carries
    // on; "" when there is none.
    std::string resumable;
    // Who played the best session: session::playerKind of its player ("human", "bot",
    // "simulated", "replay"); "" when not started.
    std::string playerKind;
    // The rigs holding a complete session (done or flagged), by name: more than one means the
    // participant played the protocol on two rigs, which the status reports.
    std::vector<std::string> completeRigs;
    // A run holding a rig's lock for this participant and protocol (holderMayRun): its
    // session is being written, not to be resumed.
    std::optional<session::LockHolder> running;
    std::string runningRig;
};

struct ParticipantStatus {
    std::string id;
    std::vector<ProtocolStatus> protocols;  // in the participant's protocol order
};

// The kind of player of a participant's sessions: the one kind all their started protocols
// have, "mixed" when they differ, "" when none is started.
std::string participantKind(const ParticipantStatus& participant);

// Whether the participant is in the default export's analysis for every protocol: each has a
// complete session without flags (export leaves flagged ones out unless --include-flagged).
bool inAnalysis(const ParticipantStatus& participant);

// The state, and for a running session who runs it: "running (pid 4242 on booth-a, since
// ...; rig booth-a)".
std::string stateLine(const ProtocolStatus& status);

// What the status needs of one session file: its header, how it ended, how far it got.
struct SessionFacts {
    std::string path;
    session::SessionHeader header;
    bool completed = false, damaged = false;
    std::map<std::string, std::string> flags;
    std::string note;
    game::Progress progress;  // Study::progress of its events
    std::string rig;  // the rig folder it lies in ("" for DIR/results itself)
};
// The facts of a session read whole, with its stored protocol's study.
SessionFacts factsOf(const std::string& path, const session::SessionData& data, const game::Study& study);
// The same from its outline (session::readSessionOutline): what studyStatus reads.
SessionFacts factsOf(const std::string& path, const session::SessionOutline& outline, const game::Study& study);

// A lock found in one of the plan's results folders whose run may still be going.
struct RunningSession {
    std::string rig;
    session::LockHolder holder;
};

// Where the plan's participants stand, from the given sessions (those whose plan_id is not the
// plan's are passed over): by participant and by the stored protocol's name; a session that a
// resumed session carries on is part of that one, and copies of one session (one session id,
// e.g. a rig's folder copied twice) count once. `running` marks the participant and protocol
// each lock names. Participants in plan order.
std::vector<ParticipantStatus> studyStatus(const StudyPlan& plan, std::vector<SessionFacts> sessions,
                                           const std::vector<RunningSession>& running = {});

// Reads every session of the plan (header plan_id = the plan's id) in its results folders (every
// rig's) and their locks: by
// participant and by the stored protocol's name. Unreadable files are not the plan's and are
// skipped; so is a session that a resumed session carries on (it is part of that one).
// Participants in plan order. Each session is read as far as its outline (its header, last
// commit and events), so the time taken does not grow with the sessions' lengths; damage
// within a session's input or frame rows shows where the session is read whole (replay,
// export, run --resume).
std::vector<ParticipantStatus> studyStatus(const std::string& planDir, const StudyPlan& plan);

// Index into participant.protocols of the first one not done (flagged counts as done: the
// session is whole, its flag is for the analysts), or -1 when every one is.
int nextProtocol(const ParticipantStatus& participant);

// The first participant with a protocol to do that no rig is running, or nullptr.
const ParticipantStatus* nextParticipant(const std::vector<ParticipantStatus>& status);

}  // namespace warplab::plan
