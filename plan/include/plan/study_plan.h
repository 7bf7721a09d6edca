// The study plan a lab prepares once for a whole study (docs/study-plan.md): the protocols the
// study runs, copied beside the plan so they cannot change under it, and for every participant
// a seed, the order of the protocols and, per protocol, the order of its conditions, both
// counterbalanced by balanced Latin squares (latin_square.h), and the participant's mouse.
// Plain structs and functions; the command line (`warplab study`, `run --study`) sits on top.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace warplab::plan {

// The format of study.json this build writes and the newest it reads.
inline constexpr int kPlanFormatVersion = 1;
// Sanity bounds: a lab's study has some tens of participants.
inline constexpr int kMaxParticipants = 10000;
// Participants' seeds stay below 2^53, so that every JSON reader (JavaScript's, R's, which
// hold numbers as doubles) reads study.json's seeds exactly and `warplab run --seed` takes them.
inline constexpr std::uint64_t kMaxParticipantSeed = (std::uint64_t{1} << 53) - 1;

// A plan that cannot be made or a study.json that does not hold: one sentence naming the file
// and the field or participant row.
class PlanError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// How a participant's mouse is set up. Unset means the protocol's own.
struct ParticipantSettings {
    std::optional<double> cmPer360;  // hand travel for one full turn; empty: the protocol's turn rate
    double mouseDpi = 800;  // the mouse's counts per inch
    bool invertY = false;
};

// A protocol the study runs, as copied into the plan folder.
struct ProtocolEntry {
    std::string file;  // relative to the plan folder, e.g. protocols/shooter-quick.json
    std::string name, game;  // the protocol's "name" and "game"
    std::string hash;  // FNV-1a 64 of the file's bytes, 16 lower-case hex digits
    // The list that is counterbalanced (shooter test.conditions, click matches.conditions), in the
    // file's order.
    std::vector<std::string> conditions;
    // The game plays the list in the given order (shooter test.interleave false, click
    // matches.shuffle false), so the plan's order is the order played; otherwise the session
    // seed shuffles it and the plan's order only records which row the participant had.
    bool blocked = false;
};

struct ParticipantPlan {
    std::string id;
    std::uint64_t seed = 0;  // the session seed: 1..kMaxParticipantSeed, distinct within the plan
    std::vector<int> protocolOrder;  // indices into StudyPlan::protocols, in the order run
    // Per protocol index (not per position in protocolOrder): a permutation of its conditions.
    std::vector<std::vector<std::string>> conditionOrder;
    ParticipantSettings settings;
};

struct StudyPlan {
    int formatVersion = kPlanFormatVersion;
    std::string id;  // 32 hex digits, random when the plan is made: tells plans apart
    std::string createdAt;  // UTC, ISO 8601 (2024-05-01T09:30:00Z)
    std::uint64_t seed = 0;  // the seed the participants' seeds were drawn from
    std::vector<ProtocolEntry> protocols;
    std::vector<ParticipantPlan> participants;
};

// Makes the plan for `participants` participants over the protocol files (each parsed by its
// game's loader; a file that does not parse is refused with the loader's message), copying
// each into planDir/protocols/ (created; two files of the same name are refused, and so is a
// planDir that already holds a study.json). `ids` names the participants; empty means P01..PNN,
// zero-padded to the width of N. The same arguments give the same plan but for id and createdAt.
// Nothing is written but the copies: writePlan writes study.json.
StudyPlan makePlan(const std::string& planDir, const std::vector<std::string>& protocolPaths, int participants,
                   const std::vector<std::string>& ids, std::uint64_t seed);

// The plan grown by `participants` rows at its end, the rows a plan made for all of them at
// once would have had there: the next seeds of the plan's stream (passing over any seed a row
// already has) and the next rows of its squares. Rows already there are kept as they are, and
// so is everything else. `ids` names the new participants; empty means the next default ids,
// P<row number> zero-padded to the new total's width (as makePlan numbers them); an id the
// plan already has is refused. Nothing is written: writePlan does that.
StudyPlan extendPlan(const std::string& planDir, const StudyPlan& plan, int participants,
                     const std::vector<std::string>& ids);

// planDir/study.json, written whole beside it and renamed into place, so a reader never sees
// half a plan.
void writePlan(const std::string& planDir, const StudyPlan& plan);

// Reads planDir/study.json and checks it against itself and the protocol copies (every rule of
// docs/study-plan.md); a PlanError names the file and the field or participant row.
StudyPlan readPlan(const std::string& planDir);

// The participant of that id, or nullptr.
const ParticipantPlan* findParticipant(const StudyPlan& plan, const std::string& id);

// The text of protocol `protocolIndex`'s file with its counterbalanced list replaced by the
// participant's order and everything else as in the file: the protocol the participant's session
// runs and stores. A PlanError when the file is missing or changed since the plan was made.
std::string participantProtocolJson(const std::string& planDir, const StudyPlan& plan,
                                    const ParticipantPlan& participant, int protocolIndex);

}  // namespace warplab::plan
