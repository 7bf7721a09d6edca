#include "runner/resume.h"

#include <filesystem>
#include <memory>
#include <sstream>
#include <type_traits>

#include "game/registry.h"
#include "rerun.h"

namespace warplab::runner {

ResumePoint findResumePoint(const std::string& sessionPath) {
    ResumePoint point;
    point.path = sessionPath;
    point.stored = session::readSession(sessionPath);
    const session::SessionData& data = point.stored;
    const std::string what = "session '" + sessionPath + "' ";
    if (data.damaged)
        throw ResumeError(what + "is damaged (" + data.note +
                          "), so it cannot be played again exactly: it cannot be resumed; record a new session");
    if (data.completed) throw ResumeError(what + "is complete: there is nothing to resume");
    if (data.header.formatVersion < session::kSessionIdSince)
        throw ResumeError(what + "is session format version " + std::to_string(data.header.formatVersion) +
                          ", written before sessions had ids: it cannot be resumed; record a new session");

    const auto study = game::parseStudy(data.header.protocolJson, sessionPath);
    const auto game = study->newGame(data.header.seed, {data.header.displayWidth, data.header.displayHeight});
    const Rerun r = rerun(data, *game, [&](std::size_t index, const game::ShownFrame& shown, std::size_t events) {
        if (!game->atCommitPoint()) return;
        point.keptInputs = index + 1;
        point.keptEvents = events;
        point.resumeFrame = shown.frame + 1;
    });
    if (!r.difference.empty())
        throw ResumeError(what + "does not replay as it was recorded (" + r.difference +
                          "), so it cannot be resumed; record a new session");
    for (const auto& frame : data.frames) point.keptFrames += frame.frame < point.resumeFrame;
    for (std::size_t i = 0; i < data.events.size(); ++i)
        (i < point.keptEvents ? point.keptOutcomes : point.droppedOutcomes) += game->isOutcome(data.events[i]);
    point.kept = study->progress(std::vector<session::EventRecord>(
        data.events.begin(), data.events.begin() + static_cast<std::ptrdiff_t>(point.keptEvents)));
    return point;
}

session::SessionHeader resumedHeader(const ResumePoint& point, const session::SessionHeader& now) {
    const session::SessionHeader& was = point.stored.header;
    session::SessionHeader header = now;
    header.protocolJson = was.protocolJson;
    header.seed = was.seed;
    header.participant = was.participant;
    header.displayWidth = was.displayWidth;
    header.displayHeight = was.displayHeight;
    header.planId = was.planId;
    header.resumed = was.resumed;
    session::Resumption r;
    r.sessionId = was.sessionId;
    r.file = std::filesystem::path(point.path).filename().string();
    r.startedAt = was.startedAt;
    r.player = was.player;
    r.frame = point.resumeFrame;
    r.resumedAt = session::utcNow();
    header.resumed.push_back(r);
    return header;
}

session::SessionWriter::FirstCommit keptRows(const ResumePoint& point) {
    const session::SessionData& data = point.stored;
    const auto first = [](const auto& rows, std::size_t count) {
        return std::decay_t<decltype(rows)>(rows.begin(), rows.begin() + static_cast<std::ptrdiff_t>(count));
    };
    return {first(data.inputs, point.keptInputs), first(data.frames, point.keptFrames),
            first(data.events, point.keptEvents)};
}

void replayKeptFrames(const ResumePoint& point, game::Game& game,
                      const std::function<void(const game::ShownFrame&)>& seen) {
    for (std::size_t i = 0; i < point.keptInputs; ++i) {
        const session::InputRecord& in = point.stored.inputs[i];
        if (game::resumedBefore(point.stored.header, in.frame)) game.resumeHere();  // an earlier resume of it
        const game::ShownFrame shown = game.step({in.mouseDx, in.mouseDy, in.buttons, in.keys, in.text});
        game.takeEvents();  // the stored ones, checked equal by findResumePoint, are in keptRows
        if (seen) seen(shown);
    }
    game.resumeHere();  // the next frame is the resumed session's first (its header's resumed.frame)
}

std::string resumeSummary(const ResumePoint& point) {
    std::ostringstream text;
    // Counted as the plan counts (test trials, matches); a shot of training is an outcome kept
    // but no test trial, and said apart, so "0 of 20 test trials" is not "3 kept".
    text << "resuming " << point.path << " at frame " << point.resumeFrame << ": " << point.kept.done;
    if (point.kept.planned > 0) text << " of " << point.kept.planned;
    text << " " << point.kept.unit << " kept (" << point.keptOutcomes
         << " scored outcome(s) in all, those of practice and training included)";
    if (point.droppedOutcomes > 0)
        text << ", " << point.droppedOutcomes << " of the trial or match it was in the middle of played again";
    if (point.keptInputs < point.stored.inputs.size())
        text << " (" << point.stored.inputs.size() - point.keptInputs
             << " frame(s) after its last completed one dropped)";
    return text.str();
}

}  // namespace warplab::runner
