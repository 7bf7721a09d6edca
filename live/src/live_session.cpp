// A recorded live session: the window loop with a session store, its commits and the
// supervisor's start and end screens.
#include "live/live_session.h"

#include <map>
#include <optional>
#include <stdexcept>
#include <sstream>
#include <utility>

#include "game/game.h"
#include "session/session_store.h"
#include "study/resume.h"
#include "study/session_runner.h"
#include "window_loop.h"

namespace warplab::live {
namespace {

// Every frame's input, events and frame record go to the store, committed at the game's
// commit points; the missed vsyncs are tallied per mode.
class SessionPolicy final : public LoopPolicy {
public:
    SessionPolicy(const WindowLoop& loop, std::uint64_t seed, session::SessionWriter& writer, std::ostream& progress)
        : game_(loop.study().newGame(seed, loop.display())),
          writer_(writer),
          commits_(writer, loop.study().refreshHz(), progress) {}

    game::Game& game() override { return *game_; }
    std::string pauseText() const override {
        return "Enter resumes. Q ends the session: everything recorded so far is kept.";
    }
    void beforeStep(const std::string&, std::int64_t, game::FrameInput&) override {}
    void stepped(const game::ShownFrame& shown, const game::FrameInput& input) override {
        writer_.addInput(study::toRecord(shown.frame, shown.time, input));
        for (auto& e : game_->takeEvents()) writer_.addEvent(e);
    }
    void decorate(const game::ShownFrame&, std::int64_t, renderer::HudContent& hud) override {
        const std::string waiting = commits_.waitingText();  // the supervisor must see it
        if (!waiting.empty()) hud.status = waiting;
    }
    void presented(const game::ShownFrame& shown, const FrameTiming& timing) override {
        session::FrameRecord record = game_->frameRecord(shown);
        record.frameMs = timing.frameMs;
        record.renderMs = timing.renderMs;
        record.missedVsyncs = timing.missedVsyncs;
        count(record);
        writer_.addFrame(record);
        commits_.afterFrame(shown.frame, game_->atCommitPoint());
    }
    std::string screenshotName(std::int64_t frame) const override { return "frame_" + std::to_string(frame); }
    // A resumed session's kept frames count towards its late frames like the ones shown now.
    void kept(const session::FrameRecord& record) { count(record); }

    // Flags a session with too many late frames, writes what waits (showing the supervisor
    // why it takes long) and prints the missed vsyncs per mode.
    void finish(WindowLoop& loop, std::ostream& progress);

private:
    struct Tally {
        long missed = 0, frames = 0, late = 0;  // missed vsyncs, frames, frames that missed one
    };
    void count(const session::FrameRecord& record) {
        Tally& tally = perMode_[record.mode.empty() ? "(screens)" : record.mode];
        tally.missed += record.missedVsyncs;
        ++tally.frames;
        tally.late += record.missedVsyncs > 0;
    }
    std::unique_ptr<game::Game> game_;
    session::SessionWriter& writer_;
    study::SessionCommits commits_;
    std::map<std::string, Tally> perMode_;
};

void SessionPolicy::finish(WindowLoop& loop, std::ostream& progress) {
    // More than 1 % of frames late is more than a study can call "at the protocol's rate":
    // the store says so, and export can leave such sessions out.
    Tally all;
    for (const auto& [mode, tally] : perMode_) {
        all.missed += tally.missed;
        all.frames += tally.frames;
        all.late += tally.late;
    }
    if (all.frames > 0 && all.late * 100 > all.frames) {
        std::ostringstream text;
        text << all.late << " of " << all.frames << " frames missed their vsync (" << all.missed << " vsyncs in all)";
        writer_.flag("missed_frames", text.str());
        progress << "warning: " << text.str() << "; the session is flagged\n";
    }
    commits_.end(game_->finished(), [&](const std::string& line) {
        loop.showScreen("Saving", line);
        loop.drainInput();  // keeps the window responsive while it waits
    });
    progress << "missed vsyncs per mode (missed / frames):";
    for (const auto& [mode, tally] : perMode_) progress << " " << mode << " " << tally.missed << "/" << tally.frames;
    progress << "\n";
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
LiveRun carryingOn(const LiveRun& given, const study::ResumePoint& resume) {
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

std::string runLive(const LiveRun& given, const renderer::DataPaths& paths, std::ostream& progress) {
    std::optional<study::ResumePoint> resume;
    if (!given.resumeFrom.empty()) resume = study::findResumePoint(given.resumeFrom);
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
        progress << study::resumeSummary(*resume) << "\n";
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
            if (c != 's') return "";
            loop.playSoundCheck(progress);
        }
    }

    auto header = study::sessionHeader(study, run.participant, run.seed, playerText(run), loop.display());
    header.planId = run.planId;
    header.glRenderer = loop.glInfo().renderer;
    header.glVersion = loop.glInfo().version;
    header.refreshHz = loop.shownRefreshHz();
    if (resume) header = study::resumedHeader(*resume, header);
    auto writer = session::SessionWriter::create(
        run.resultsDir, header, resume ? study::keptRows(*resume) : session::SessionWriter::FirstCommit{});
    progress << "session " << writer.path() << "\n";

    SessionPolicy policy(loop, run.seed, writer, progress);
    if (resume) {
        study::replayKeptFrames(*resume, policy.game(),
                                [&](const game::ShownFrame& shown) { loop.sawBeforeResume(shown); });
        for (std::size_t i = 0; i < resume->keptFrames; ++i) policy.kept(resume->stored.frames[i]);
    }
    loop.captureMouse(true);
    const WindowLoop::End end = loop.run(policy);
    loop.captureMouse(false);
    policy.finish(loop, progress);
    if (end.aborted) {
        progress << "session ended by the supervisor at frame " << end.lastFrame << "; everything recorded is kept\n";
        return writer.path();
    }
    if (run.screenshotStartScreen) {
        loop.showScreen("Thank you", "The experiment has ended.");
        loop.screenshot("end");
    }
    loop.inject("end");
    if (loop.human()) loop.waitFor("Thank you", "The experiment has ended. Press Enter or Esc to close.", "\r\x1b");
    return writer.path();
}

}  // namespace warplab::live
