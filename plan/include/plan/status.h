// Where a study stands: for each participant of a plan and each of their protocols, what the
// sessions in the plan's results folder hold (docs/study-plan.md, "Running the study").
#pragma once

#include <map>
#include <string>
#include <vector>

#include "game/game.h"
#include "plan/study_plan.h"
#include "session/session_store.h"

namespace warplab::plan {

// The results folder of a plan: where run --study writes its sessions.
std::string resultsFolder(const std::string& planDir);

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
};

struct ParticipantStatus {
    std::string id;
    std::vector<ProtocolStatus> protocols;  // in the participant's protocol order
};

// What the status needs of one session file: its header, how it ended, how far it got.
struct SessionFacts {
    std::string path;
    session::SessionHeader header;
    bool completed = false, damaged = false;
    std::map<std::string, std::string> flags;
    std::string note;
    game::Progress progress;  // Study::progress of its events
};
// The facts of a session read whole, with its stored protocol's study.
SessionFacts factsOf(const std::string& path, const session::SessionData& data, const game::Study& study);
// The same from its outline (session::readSessionOutline): what studyStatus reads.
SessionFacts factsOf(const std::string& path, const session::SessionOutline& outline, const game::Study& study);

// Where the plan's participants stand, from the given sessions (those whose plan_id is not the
// plan's are passed over): by participant and by the stored protocol's name; a session that a
// resumed session carries on is part of that one. Participants in plan order.
std::vector<ParticipantStatus> studyStatus(const StudyPlan& plan, std::vector<SessionFacts> sessions);

// Reads every session of the plan (header plan_id = the plan's id) in its results folder: by
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

}  // namespace warplab::plan
