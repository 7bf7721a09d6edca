#include "plan/status.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

#include "game/registry.h"
#include "session/session_store.h"

namespace warplab::plan {

namespace fs = std::filesystem;

std::string resultsFolder(const std::string& planDir, const std::string& rig) {
    const fs::path results = fs::path(planDir) / "results";
    return (rig.empty() ? results : results / rig).string();
}

std::string rigNameProblem(const std::string& rig) {
    if (rig.empty()) return "must not be empty";
    if (rig.size() > 64) return "must be at most 64 bytes, got " + std::to_string(rig.size());
    if (rig.front() == '.') return "must not start with '.', got '" + rig + "'";
    for (const char c : rig)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
            return "may hold only letters, digits, '-', '_' and '.' (it names a folder), got '" + rig + "'";
    return "";
}

std::vector<std::string> rigsOf(const std::string& planDir) {
    std::vector<std::string> rigs{""};
    std::error_code ec;
    for (fs::directory_iterator it(resultsFolder(planDir), ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (rigNameProblem(name).empty() && it->is_directory(ec)) rigs.push_back(name);
    }
    std::sort(rigs.begin(), rigs.end());
    return rigs;
}

std::string rigText(const std::string& rig) { return rig.empty() ? "the results folder itself" : "rig " + rig; }

const char* stateName(SessionState state) {
    switch (state) {
        case SessionState::Done: return "done";
        case SessionState::Flagged: return "flagged";
        case SessionState::Incomplete: return "incomplete";
        case SessionState::Damaged: return "damaged";
        case SessionState::NotStarted: return "not started";
    }
    return "not started";
}

std::string stateText(const ProtocolStatus& status) {
    std::string text = stateName(status.state);
    if ((status.state == SessionState::Incomplete || status.state == SessionState::Damaged) && !status.unit.empty())
        text += " (" + std::to_string(status.done) + " of " + std::to_string(status.planned) + " " + status.unit + ")";
    return text;
}

namespace {

SessionState stateOf(const SessionFacts& s) {
    if (s.damaged) return SessionState::Damaged;
    if (!s.completed) return SessionState::Incomplete;
    return s.flags.empty() ? SessionState::Done : SessionState::Flagged;
}

std::string protocolName(const std::string& protocolJson) {
    const auto json = nlohmann::json::parse(protocolJson, nullptr, false);
    return json.is_object() && json.contains("name") && json["name"].is_string() ? json["name"].get<std::string>() : "";
}

void readRigSessions(const std::string& results, const std::string& rig, const StudyPlan& plan,
                     std::vector<SessionFacts>& sessions) {
    std::error_code ec;
    for (fs::directory_iterator it(results, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path& path = it->path();
        const std::string name = path.filename().string();
        if (path.extension() != ".warplab-session" || name.front() == '.' || !it->is_regular_file(ec)) continue;
        try {
            // The header first: another plan's session (or one without a plan) has its events
            // left unread. A session of the plan is read as far as its last commit, never its
            // input and frame rows: a participant waits for this at every start.
            if (session::readSessionHeader(path.string()).planId != plan.id) continue;
            const session::SessionOutline outline = session::readSessionOutline(path.string());
            sessions.push_back(
                factsOf(path.string(), outline, *game::parseStudy(outline.header.protocolJson, path.string())));
            sessions.back().rig = rig;
        } catch (const std::exception&) {
            continue;  // not a session of this plan that can be told, or its stored protocol does not parse
        }
    }
}

}  // namespace

SessionFacts factsOf(const std::string& path, const session::SessionData& data, const game::Study& study) {
    return {path, data.header, data.completed, data.damaged, data.flags, data.note, study.progress(data.events), ""};
}

SessionFacts factsOf(const std::string& path, const session::SessionOutline& outline, const game::Study& study) {
    return {path,
            outline.header,
            outline.completed,
            outline.damaged,
            outline.flags,
            outline.note,
            study.progress(outline.events),
            ""};
}

std::vector<ParticipantStatus> studyStatus(const std::string& planDir, const StudyPlan& plan) {
    std::vector<SessionFacts> sessions;
    std::vector<RunningSession> running;
    for (const std::string& rig : rigsOf(planDir)) {
        const std::string folder = resultsFolder(planDir, rig);
        if (const auto holder = session::readLockHolder(folder); holder && session::holderMayRun(*holder))
            running.push_back({rig, *holder});
        readRigSessions(folder, rig, plan, sessions);
    }
    return studyStatus(plan, std::move(sessions), running);
}

std::vector<ParticipantStatus> studyStatus(const StudyPlan& plan, std::vector<SessionFacts> sessions,
                                           const std::vector<RunningSession>& running) {
    sessions.erase(std::remove_if(sessions.begin(), sessions.end(),
                                  [&](const SessionFacts& s) { return s.header.planId != plan.id; }),
                   sessions.end());
    std::set<std::string> carriedOn;  // session ids a resumed session carries on
    for (const SessionFacts& s : sessions)
        for (const auto& r : s.header.resumed) carriedOn.insert(r.sessionId);
    // Directory order is the file system's; by name (participant, then start time) the last
    // incomplete session of a protocol is the latest. Rigs by name break ties between copies.
    std::sort(sessions.begin(), sessions.end(), [](const SessionFacts& a, const SessionFacts& b) {
        const auto nameA = fs::path(a.path).filename(), nameB = fs::path(b.path).filename();
        return nameA != nameB ? nameA < nameB : a.rig < b.rig;
    });

    // (participant, protocol name) -> the status so far
    std::map<std::pair<std::string, std::string>, ProtocolStatus> seen;
    std::set<std::string> counted;  // session ids: a copy of one (two rigs' folders merged) counts once
    for (const SessionFacts& found : sessions) {
        // A session carried on by a resumed one is part of it, not a session of its own.
        if (carriedOn.count(found.header.sessionId)) continue;
        if (!found.header.sessionId.empty() && !counted.insert(found.header.sessionId).second) continue;
        const std::string name = fs::path(found.path).filename().string();
        ProtocolStatus& s = seen[{found.header.participant, protocolName(found.header.protocolJson)}];
        ++s.sessions;
        const SessionState state = stateOf(found);
        if (state == SessionState::Incomplete) s.resumable = found.path;
        if ((state == SessionState::Done || state == SessionState::Flagged) &&
            std::find(s.completeRigs.begin(), s.completeRigs.end(), found.rig) == s.completeRigs.end())
            s.completeRigs.push_back(found.rig);
        if (s.sessions == 1 || state < s.state) {
            s.state = state;
            s.done = found.progress.done;
            s.planned = found.progress.planned;
            s.unit = found.progress.unit;
            s.playerKind = session::playerKind(found.header.player);
            s.detail = found.rig.empty() ? name : found.rig + "/" + name;
            if (state == SessionState::Flagged)
                s.detail += ": flagged " + found.flags.begin()->first + ": " + found.flags.begin()->second;
            else if (state != SessionState::Done)
                s.detail += ": " + found.note;
        }
    }
    for (const RunningSession& r : running) {
        ProtocolStatus& s = seen[{r.holder.participant, r.holder.protocol}];
        s.running = r.holder;
        s.runningRig = r.rig;
    }
    std::vector<ParticipantStatus> out;
    for (const ParticipantPlan& p : plan.participants) {
        ParticipantStatus status{p.id, {}};
        for (const int index : p.protocolOrder) {
            ProtocolStatus s;
            if (const auto found = seen.find({p.id, plan.protocols[static_cast<std::size_t>(index)].name});
                found != seen.end())
                s = found->second;
            s.protocolIndex = index;
            status.protocols.push_back(s);
        }
        out.push_back(std::move(status));
    }
    return out;
}

std::string participantKind(const ParticipantStatus& participant) {
    std::string kind;
    for (const ProtocolStatus& s : participant.protocols) {
        if (s.playerKind.empty()) continue;
        if (!kind.empty() && kind != s.playerKind) return "mixed";
        kind = s.playerKind;
    }
    return kind;
}

bool inAnalysis(const ParticipantStatus& participant) {
    return std::all_of(participant.protocols.begin(), participant.protocols.end(),
                       [](const ProtocolStatus& s) { return s.state == SessionState::Done; });
}

std::string stateLine(const ProtocolStatus& status) {
    if (!status.running) return stateText(status);
    return "running (" + session::holderText(*status.running) + "; " + rigText(status.runningRig) + ")";
}

const ParticipantStatus* nextParticipant(const std::vector<ParticipantStatus>& status) {
    for (const ParticipantStatus& p : status) {
        const int next = nextProtocol(p);
        if (next >= 0 && !p.protocols[static_cast<std::size_t>(next)].running) return &p;
    }
    return nullptr;
}

int nextProtocol(const ParticipantStatus& participant) {
    for (std::size_t i = 0; i < participant.protocols.size(); ++i)
        if (participant.protocols[i].state != SessionState::Done &&
            participant.protocols[i].state != SessionState::Flagged)
            return static_cast<int>(i);
    return -1;
}

}  // namespace warplab::plan
