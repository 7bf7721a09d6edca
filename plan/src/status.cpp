#include "plan/status.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

#include "game/registry.h"
#include "session/session_store.h"

namespace warplab::plan {

namespace fs = std::filesystem;

std::string resultsFolder(const std::string& planDir) { return (fs::path(planDir) / "results").string(); }

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

}  // namespace

SessionFacts factsOf(const std::string& path, const session::SessionData& data, const game::Study& study) {
    return {path, data.header, data.completed, data.damaged, data.flags, data.note, study.progress(data.events)};
}

SessionFacts factsOf(const std::string& path, const session::SessionOutline& outline, const game::Study& study) {
    return {path,
            outline.header,
            outline.completed,
            outline.damaged,
            outline.flags,
            outline.note,
            study.progress(outline.events)};
}

std::vector<ParticipantStatus> studyStatus(const std::string& planDir, const StudyPlan& plan) {
    std::vector<SessionFacts> sessions;
    std::error_code ec;
    const std::string results = resultsFolder(planDir);
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
        } catch (const std::exception&) {
            continue;  // not a session of this plan that can be told, or its stored protocol does not parse
        }
    }
    return studyStatus(plan, std::move(sessions));
}

std::vector<ParticipantStatus> studyStatus(const StudyPlan& plan, std::vector<SessionFacts> sessions) {
    sessions.erase(std::remove_if(sessions.begin(), sessions.end(),
                                  [&](const SessionFacts& s) { return s.header.planId != plan.id; }),
                   sessions.end());
    std::set<std::string> carriedOn;  // session ids a resumed session carries on
    for (const SessionFacts& s : sessions)
        for (const auto& r : s.header.resumed) carriedOn.insert(r.sessionId);
    // Directory order is the file system's; by name (participant, then start time) the last
    // incomplete session of a protocol is the latest.
    std::sort(sessions.begin(), sessions.end(), [](const SessionFacts& a, const SessionFacts& b) {
        return fs::path(a.path).filename() < fs::path(b.path).filename();
    });

    // (participant, protocol name) -> the status so far
    std::map<std::pair<std::string, std::string>, ProtocolStatus> seen;
    for (const SessionFacts& found : sessions) {
        // A session carried on by a resumed one is part of it, not a session of its own.
        if (carriedOn.count(found.header.sessionId)) continue;
        const std::string name = fs::path(found.path).filename().string();
        ProtocolStatus& s = seen[{found.header.participant, protocolName(found.header.protocolJson)}];
        ++s.sessions;
        const SessionState state = stateOf(found);
        if (state == SessionState::Incomplete) s.resumable = found.path;
        if (s.sessions == 1 || state < s.state) {
            s.state = state;
            s.done = found.progress.done;
            s.planned = found.progress.planned;
            s.unit = found.progress.unit;
            s.detail = name;
            if (state == SessionState::Flagged)
                s.detail += ": flagged " + found.flags.begin()->first + ": " + found.flags.begin()->second;
            else if (state != SessionState::Done)
                s.detail += ": " + found.note;
        }
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

int nextProtocol(const ParticipantStatus& participant) {
    for (std::size_t i = 0; i < participant.protocols.size(); ++i)
        if (participant.protocols[i].state != SessionState::Done &&
            participant.protocols[i].state != SessionState::Flagged)
            return static_cast<int>(i);
    return -1;
}

}  // namespace warplab::plan
