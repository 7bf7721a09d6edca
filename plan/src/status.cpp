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

SessionState stateOf(const session::SessionData& data) {
    if (data.damaged) return SessionState::Damaged;
    if (!data.completed) return SessionState::Incomplete;
    return data.flags.empty() ? SessionState::Done : SessionState::Flagged;
}

std::string protocolName(const std::string& protocolJson) {
    const auto json = nlohmann::json::parse(protocolJson, nullptr, false);
    return json.is_object() && json.contains("name") && json["name"].is_string() ? json["name"].get<std::string>() : "";
}

}  // namespace

std::vector<ParticipantStatus> studyStatus(const std::string& planDir, const StudyPlan& plan) {
    struct Found {
        fs::path path;
        session::SessionData data;
        game::Progress progress;
    };
    std::vector<Found> sessions;
    std::set<std::string> carriedOn;  // session ids a resumed session carries on
    std::error_code ec;
    const std::string results = resultsFolder(planDir);
    for (fs::directory_iterator it(results, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path& path = it->path();
        const std::string name = path.filename().string();
        if (path.extension() != ".warplab-session" || name.front() == '.' || !it->is_regular_file(ec)) continue;
        Found found{path, {}, {}};
        try {
            // The header first: another plan's session (or one without a plan) is not read whole.
            if (session::readSessionHeader(path.string()).planId != plan.id) continue;
            found.data = session::readSession(path.string());
        } catch (const session::SessionError&) {
            continue;  // not a session of this plan that can be told
        }
        if (found.data.header.planId != plan.id) continue;
        try {
            found.progress =
                game::parseStudy(found.data.header.protocolJson, path.string())->progress(found.data.events);
        } catch (const std::exception&) {
            continue;  // its stored protocol does not parse: export says so
        }
        // Only the headers are needed from here on.
        found.data.inputs.clear();
        found.data.frames.clear();
        found.data.events.clear();
        for (const auto& r : found.data.header.resumed) carriedOn.insert(r.sessionId);
        sessions.push_back(std::move(found));
    }
    // Directory order is the file system's; by name (participant, then start time) the last
    // incomplete session of a protocol is the latest.
    std::sort(sessions.begin(), sessions.end(), [](const Found& a, const Found& b) { return a.path < b.path; });

    // (participant, protocol name) -> the status so far
    std::map<std::pair<std::string, std::string>, ProtocolStatus> seen;
    for (const Found& found : sessions) {
        const session::SessionData& data = found.data;
        // A session carried on by a resumed one is part of it, not a session of its own.
        if (carriedOn.count(data.header.sessionId)) continue;
        const std::string name = found.path.filename().string();
        ProtocolStatus& s = seen[{data.header.participant, protocolName(data.header.protocolJson)}];
        ++s.sessions;
        const SessionState state = stateOf(data);
        if (state == SessionState::Incomplete) s.resumable = found.path.string();
        if (s.sessions == 1 || state < s.state) {
            s.state = state;
            s.done = found.progress.done;
            s.planned = found.progress.planned;
            s.unit = found.progress.unit;
            s.detail = name;
            if (state == SessionState::Flagged)
                s.detail += ": flagged " + data.flags.begin()->first + ": " + data.flags.begin()->second;
            else if (state != SessionState::Done)
                s.detail += ": " + data.note;
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
