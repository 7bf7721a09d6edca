// A recorded live session: the window loop with a session store, its commits and the
// supervisor's start and end screens.
#include "live/live_session.h"

#include <algorithm>
#include <cstdio>
#include <deque>
#include <map>
#include <optional>
#include <stdexcept>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "game/game.h"
#include "session/pacing.h"
#include "session/session_store.h"
#include "runner/resume.h"
#include "runner/session_runner.h"
#include "window_loop.h"

namespace warplab::live {
namespace {

// Every frame's input, events and frame record go to the store, committed at the game's
// commit points; the missed vsyncs are tallied per condition.
class SessionPolicy final : public LoopPolicy {
public:
    SessionPolicy(const WindowLoop& loop, std::uint64_t seed, session::SessionWriter& writer, std::ostream& progress)
        : game_(loop.study().newGame(seed, loop.display())),
          writer_(writer),
          commits_(writer, loop.study().refreshHz(), progress),
          refreshHz_(loop.shownRefreshHz()),
          progress_(progress) {}

    game::Game& game() override { return *game_; }
    std::string pauseText() const override {
        return "Enter resumes. Q ends the session: everything recorded so far is kept.";
    }
    void beforeStep(const std::string&, std::int64_t, game::FrameInput&) override {}
    void stepped(const game::ShownFrame& shown, const game::FrameInput& input) override {
        writer_.addInput(runner::toRecord(shown.frame, shown.time, input));
        for (auto& e : game_->takeEvents()) writer_.addEvent(e);
    }
    void decorate(const game::ShownFrame&, std::int64_t, renderer::HudContent& hud) override {
        const std::string waiting = commits_.waitingText();  // the supervisor must see it
        if (!waiting.empty()) hud.status = waiting;
    }
    void presented(const game::ShownFrame& shown, const FrameTiming& timing) override {
        session::FrameRecord record = game_->frameRecord(shown);
        // A skipped frame was never on screen: its kind says so, and it has no times. Pacing
        // still counts a new image the schedule made there as one the machine missed.
        const std::string scheduledKind = record.kind;
        if (timing.skipped) record.kind = session::kSkippedFrameKind;
        record.frameMs = timing.frameMs;
        record.renderMs = timing.renderMs;
        record.missedVsyncs = timing.missedVsyncs;
        if (timing.photonMarker) {
            // Beside the game's own keys: the frame a photodiode saw turn white, and the press
            // it answers, to join a meter's measurements with the schedule's latency.
            nlohmann::json detail =
                record.detailJson.empty() ? nlohmann::json::object() : nlohmann::json::parse(record.detailJson);
            detail["photon_marker"] = true;
            detail["photon_press"] = timing.photonPress;
            record.detailJson = detail.dump();
        }
        pacing_.add(record, scheduledKind);
        warnIfOverBudget(record);
        writer_.addFrame(record);
        commits_.afterFrame(shown.frame, game_->atCommitPoint());
    }
    std::string screenshotName(std::int64_t frame) const override { return "frame_" + std::to_string(frame); }
    // A resumed session's kept frames count towards its pacing like the ones shown now.
    void kept(const session::FrameRecord& record) { pacing_.add(record); }

    // Flags a session with too many late or skipped frames, stores and prints the pacing per
    // condition, and writes what waits (showing the supervisor why it takes long).
    void finish(WindowLoop& loop, std::ostream& progress);

private:
    // Says on the supervisor's terminal, at most every few seconds, when the condition on screen
    // did not keep its rate over the last second.
    void warnIfOverBudget(const session::FrameRecord& record);

    std::unique_ptr<game::Game> game_;
    session::SessionWriter& writer_;
    runner::SessionCommits commits_;
    double refreshHz_;
    std::ostream& progress_;
    session::PacingTally pacing_;
    std::deque<session::FrameRecord> lastSecond_;  // condition, kind, frame time: the last refresh's worth
    std::int64_t warnedAt_ = -1;
};

void SessionPolicy::warnIfOverBudget(const session::FrameRecord& record) {
    // What pacing reads of a frame, without the game's detail (copied every frame otherwise).
    session::FrameRecord brief;
    brief.frame = record.frame;
    brief.condition = record.condition;
    brief.kind = record.kind;
    brief.frameMs = record.frameMs;
    brief.missedVsyncs = record.missedVsyncs;
    lastSecond_.push_back(std::move(brief));
    const auto perSecond = static_cast<std::size_t>(std::max(1.0, refreshHz_));
    if (lastSecond_.size() > perSecond) lastSecond_.pop_front();
    const std::int64_t frame = record.frame;
    if (lastSecond_.size() < perSecond || record.condition.empty() ||
        frame % static_cast<std::int64_t>(perSecond) != 0 ||
        (warnedAt_ >= 0 && frame - warnedAt_ < 5 * static_cast<std::int64_t>(perSecond)))
        return;
    std::vector<session::FrameRecord> recent;
    for (const auto& f : lastSecond_)
        if (f.condition == record.condition) recent.push_back(f);
    const auto summary = session::summarizePacing(recent, refreshHz_);
    if (summary.empty()) return;
    const session::ConditionPacing& p = summary.front();
    if (p.skipped == 0 && p.overBudget * 10 <= p.shown) return;  // nine in ten on time: no need to say
    warnedAt_ = frame;
    char text[200];
    std::snprintf(text, sizeof text,
                  "warning: %s did not keep its rate in the last second: %lld of %lld display frames skipped, "
                  "frame time median %.1f ms, max %.1f ms against %.1f ms\n",
                  p.condition.c_str(), static_cast<long long>(p.skipped), static_cast<long long>(p.shown + p.skipped),
                  p.medianMs, p.maxMs, p.budgetMs);
    progress_ << text;
}

void SessionPolicy::finish(WindowLoop& loop, std::ostream& progress) {
    // More display frames late or skipped than the protocol allows (display.max_late_share, 1 %
    // unless it says otherwise) is more than a study can call "at the protocol's rate": the
    // store says so, and export can leave such sessions out.
    const std::vector<session::ConditionPacing> pacing = pacing_.summary(refreshHz_);
    std::int64_t displayFrames = 0, offTime = 0;
    for (const auto& p : pacing) {
        displayFrames += p.shown + p.skipped;
        offTime += p.late + p.skipped;
    }
    const double allowed = loop.study().rendering().maxLateShare;
    if (displayFrames > 0 && static_cast<double>(offTime) > allowed * static_cast<double>(displayFrames)) {
        std::ostringstream text;
        text << offTime << " of " << displayFrames << " display frames late or skipped (more than " << allowed * 100.0
             << " %)";
        writer_.flag("missed_frames", text.str());
        progress << "warning: " << text.str() << "; the session is flagged\n";
    }
    writer_.summarize("pacing", session::pacingText(pacing));
    commits_.end(game_->finished(), [&](const std::string& line) {
        loop.showScreen("Saving", line);
        loop.drainInput();  // keeps the window responsive while it waits
    });
    progress << session::pacingReport(pacing);
}

std::string playerText(const LiveRun& run) {
    std::ostringstream text;
    text << run.player;
    if (run.player == "human")
        text << " (cm_per_360=" << run.cmPer360 << ", dpi=" << run.mouseDpi << ", invert_y=" << (run.invertY ? 1 : 0)
             << ")";
    return text.str();
}

// A resumed session plays the interrupted one's protocol, seed, participant and plan, on a
// window of its size (the click game's cursor lives in its pixels).
LiveRun carryingOn(const LiveRun& given, const runner::ResumePoint& resume) {
    LiveRun run = given;
    const session::SessionHeader& was = resume.stored.header;
    run.protocolPath = resume.path;
    run.protocolText = was.protocolJson;
    run.seed = was.seed;
    run.participant = was.participant;
    run.planId = was.planId;
    if (!run.fullscreen) {
        run.width = was.displayWidth;
        run.height = was.displayHeight;
    }
    return run;
}

}  // namespace

LiveEnd runLive(const LiveRun& given, const renderer::DataPaths& paths, std::ostream& progress) {
    std::optional<runner::ResumePoint> resume;
    if (!given.resumeFrom.empty()) resume = runner::findResumePoint(given.resumeFrom);
    const LiveRun run = resume ? carryingOn(given, *resume) : given;
    WindowLoop loop(run, paths, progress);
    const game::Study& study = loop.study();
    std::string who = "Participant " + run.participant + ", protocol " + study.name();
    if (resume) {
        const session::SessionHeader& was = resume->stored.header;
        if (loop.display().width != was.displayWidth || loop.display().height != was.displayHeight)
            throw std::runtime_error("session '" + resume->path + "' was played on a " +
                                     std::to_string(was.displayWidth) + "x" + std::to_string(was.displayHeight) +
                                     " display but this window is " + std::to_string(loop.display().width) + "x" +
                                     std::to_string(loop.display().height) +
                                     ": resume it at the same size (without --fullscreen, or on that display)");
        progress << runner::resumeSummary(*resume) << "\n";
        who += ", resumed after its last completed trial or match";
    }

    // Start screen (Appendix B: the supervisor checks the participant and the protocol).
    if (run.screenshotStartScreen) {
        loop.showScreen("warplab", who + ". Press Enter to start.");
        loop.screenshot("start");
    }
    loop.inject("start");
    if (loop.human()) {
        // S plays the feedback sounds, as often as the supervisor likes, before Enter starts.
        const std::string text = who + ". Press Enter to start, S to hear the feedback sounds, Esc to leave.";
        std::string pending;
        for (char c; (c = loop.waitFor("warplab", text, "\rs\x1b", pending, &pending)) != '\r';) {
            if (c != 's') return {"", true};
            loop.playSoundCheck(progress);
        }
    }

    auto header = runner::sessionHeader(study, run.participant, run.seed, playerText(run), loop.display());
    header.planId = run.planId;
    header.glRenderer = loop.glInfo().renderer;
    header.glVersion = loop.glInfo().version;
    header.refreshHz = loop.shownRefreshHz();
    header.photonMarker = protocol::nameOf(loop.photonMarker());  // replay --render draws it
    if (resume) header = runner::resumedHeader(*resume, header);
    auto writer = session::SessionWriter::create(
        run.resultsDir, header, resume ? runner::keptRows(*resume) : session::SessionWriter::FirstCommit{});
    progress << "session " << writer.path() << "\n";

    SessionPolicy policy(loop, run.seed, writer, progress);
    if (resume) {
        runner::replayKeptFrames(*resume, policy.game(),
                                 [&](const game::ShownFrame& shown) { loop.sawBeforeResume(shown); });
        for (std::size_t i = 0; i < resume->keptFrames; ++i) policy.kept(resume->stored.frames[i]);
    }
    loop.captureMouse(true);
    const WindowLoop::End end = loop.run(policy);
    loop.captureMouse(false);
    policy.finish(loop, progress);
    if (end.aborted) {
        progress << "session ended by the supervisor at frame " << end.lastFrame
                 << "; everything recorded is kept (warplab run --resume carries it on)\n";
        return {writer.path(), true};
    }
    if (run.screenshotStartScreen) {
        loop.showScreen("Thank you", "The experiment has ended.");
        loop.screenshot("end");
    }
    loop.inject("end");
    if (loop.human()) loop.waitFor("Thank you", "The experiment has ended. Press Enter or Esc to close.", "\r\x1b");
    return {writer.path(), false};
}

}  // namespace warplab::live
