#include "live/check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <thread>

#include "cadence_check.h"
#include "game/game.h"
#include "present/frame_maker.h"
#include "photon_marker.h"
#include "refresh_rule.h"
#include "renderer/hud.h"
#include "renderer/timing.h"
#include "renderer/window.h"
#include "session/results_lock.h"
#include "sound.h"
#include "runner/session_runner.h"
#include "runner/session_size.h"

namespace warplab::live {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string number(double value, int decimals) {
    char text[48];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

// Hz as the system reports it (a whole number on most) or as measured.
std::string hertz(double value) { return number(value, std::abs(value - std::round(value)) < 0.005 ? 0 : 2) + " Hz"; }

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

// The nearest-rank 95th percentile, as the session's pacing summary takes it.
double p95(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(values.size()))) - 1;
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
    return values[rank];
}

bool softwareRenderer(const std::string& renderer) {
    for (const char* name : {"llvmpipe", "softpipe", "Software Rasterizer", "SWR"})
        if (renderer.find(name) != std::string::npos) return true;
    return false;
}

class Lines {
public:
    explicit Lines(std::ostream& out) : out_(out) {}
    void add(Verdict verdict, const std::string& name, const std::string& detail) {
        lines_.push_back({verdict, name, detail});
        out_ << formatCheckLine(lines_.back()) << "\n" << std::flush;
    }
    std::vector<CheckLine> take() { return std::move(lines_); }

private:
    std::ostream& out_;
    std::vector<CheckLine> lines_;
};

// The checks that need the window: what `warplab run` would open, and what it would show.
class WindowChecks {
public:
    WindowChecks(const CheckRun& run, const game::Study* study, const renderer::DataPaths& paths, Lines& lines)
        : run_(run), study_(study), paths_(paths), lines_(lines) {}

    void all() {
        renderer::ContextOptions options;  // as WindowLoop::open asks for a session's
        options.width = run_.width;
        options.height = run_.height;
        options.fullscreen = run_.fullscreen;
        options.display = run_.display;
        options.title = "warplab check" + (study_ ? ": " + study_->name() : std::string());
        window_ = renderer::createWindow(options);
        display_ = {window_->drawableWidth(), window_->drawableHeight()};
        hud_.emplace(paths_);
        screen_.emplace(display_.width, display_.height);
        timer_.emplace();

        const renderer::GlInfo& info = window_->info();
        const bool software = softwareRenderer(info.renderer);
        lines_.add(software ? Verdict::Warn : Verdict::Ok, "gl",
                   info.renderer + ", OpenGL " + info.version +
                       (software ? ": a software renderer, for tests and replays, not for participants" : ""));
        reported();
        lines_.add(window_->vsyncOn() ? Verdict::Ok : Verdict::Warn, "vsync",
                   window_->vsyncOn()
                       ? "on: each swap waits for the display"
                       : "off: the driver refused a swap interval of 1; a session would pace its frames by a timer");
        measured();
        if (!run_.photonCorner.empty()) photonPattern();
        if (!study_) return;
        std::vector<std::string> conditions;  // each once, in the protocol's order (phases repeat them)
        for (const std::string& condition : study_->conditionNames())
            if (std::find(conditions.begin(), conditions.end(), condition) == conditions.end())
                conditions.push_back(condition);
        for (const std::string& condition : conditions) frameTime(condition);
    }

private:
    void reported() {
        reportedHz_ = window_->refreshHz();
        if (!study_) {
            if (reportedHz_ > 0.0)
                lines_.add(Verdict::Ok, "refresh", hertz(reportedHz_) + ", as the system reports it");
            else
                lines_.add(Verdict::Warn, "refresh", "the display reports no refresh rate");
            return;
        }
        const double wanted = study_->refreshHz();
        if (!refreshMismatch(reportedHz_, wanted)) {
            lines_.add(Verdict::Ok, "refresh", hertz(reportedHz_) + ", as protocol '" + run_.protocolPath + "' needs");
            return;
        }
        const bool refused = refusesRefresh(reportedHz_, *study_, run_.allowRefreshMismatch);
        lines_.add(refused ? Verdict::Fail : Verdict::Warn, "refresh",
                   refreshText(reportedHz_, wanted, run_.protocolPath, refused) +
                       (refused ? "" : "; a session would pace its frames by a timer"));
    }

    // The display's rate as swaps meet it: the median interval of ~2 s of swaps, so a late
    // swap or two (the check's own start) do not move it.
    void measured() {
        screen("measuring the display's refresh");
        std::vector<double> intervals;
        const auto start = Clock::now();
        auto last = start;
        for (int swap = 0; secondsSince(start) < run_.refreshSeconds; ++swap) {
            renderer::blitToDefaultFramebuffer(screen_->buffer(), display_.width, display_.height);
            window_->swapBuffers();
            poll();
            const auto now = Clock::now();
            if (swap >= 10) intervals.push_back(std::chrono::duration<double>(now - last).count());
            last = now;
        }
        const double measuredHz = intervals.empty() ? 0.0 : 1.0 / median(intervals);
        measuredHz_ = window_->vsyncOn() ? measuredHz : 0.0;  // unpaced swaps measure nothing
        const std::string seen = hertz(measuredHz) + " over " + number(secondsSince(start), 1) + " s of swaps";
        if (!window_->vsyncOn()) {
            lines_.add(Verdict::Warn, "measured refresh",
                       seen + ": without vsync that is the machine's speed, not the display's");
            return;
        }
        const double wanted = study_ ? study_->refreshHz() : reportedHz_;
        if (!(wanted > 0.0)) {
            // Nothing to hold it against: a display runs at 24 to 500 Hz; more is swaps vsync does not pace.
            const bool plausible = measuredHz >= 24.0 && measuredHz <= 500.0;
            lines_.add(plausible ? Verdict::Ok : Verdict::Warn, "measured refresh",
                       seen + (plausible ? "" : ": swaps are not paced by the display"));
            return;
        }
        // 1 %: a 59.94 Hz display is a 60 Hz one; a compositor halving the rate is not.
        if (std::abs(measuredHz - wanted) <= std::max(0.5, 0.01 * wanted)) {
            lines_.add(Verdict::Ok, "measured refresh",
                       seen + (study_ ? ", as the protocol needs" : ", as the system reports"));
            return;
        }
        const bool refused = study_ && refusesRefresh(measuredHz, *study_, run_.allowRefreshMismatch);
        lines_.add(refused ? Verdict::Fail : Verdict::Warn, "measured refresh",
                   seen + ", not the " + hertz(wanted) + (study_ ? " the protocol needs" : " the system reports") +
                       ": vsynced frames would reach the screen at the measured rate");
    }

    // The frames of one condition as a session makes them (present/frame_maker.h: the condition's
    // renders, warps or blends, and the HUD, timed to glFinish as the window loop times them),
    // played by the study's bot in free play, against one refresh.
    void frameTime(const std::string& condition) {
        screen("making frames of " + condition);
        if (!maker_) {
            maker_.emplace(paths_, display_.width, display_.height, study_->rendering());
            game_ = study_->newFreePlay(1, display_, condition, 0);
            bot_ = runner::makePlayer("bot", 1, *study_, display_);
            input_ = bot_->first();
        } else {
            game_->switchTo(condition, 0);
        }
        // Its first renders give the condition's method its sources and compile its shaders: not
        // timed. Then at least conditionSeconds, and at least two more renders, so that
        // rendered frames and the frames made between them are both in the count.
        int renders = 0;
        std::vector<double> ms, drawingMs;  // every frame made; those of them that drew a render
        std::vector<double> newImageMs;  // those of them that put a new image on the display
        const auto start = Clock::now();
        Clock::time_point timedFrom{};
        while (renders < 4 || secondsSince(timedFrom) < run_.conditionSeconds) {
            const game::ShownFrame shown = game_->step(input_);
            game_->takeEvents();
            timer_->begin();
            const std::int64_t rendersBefore = maker_->rendersDrawn();
            maker_->keepSource(shown);
            if (!shown.blank) maker_->make(shown, *screen_);
            hud_->draw(present::hudFor(shown, 1.0, 1.0), screen_->buffer());
            renderer::blitToDefaultFramebuffer(screen_->buffer(), display_.width, display_.height);
            const double made = timer_->end().wallMs;
            window_->swapBuffers();
            poll();
            input_ = bot_->next(shown);
            renders += shown.rendersNow;
            if (renders == 2 && shown.rendersNow) timedFrom = Clock::now();
            if (renders >= 2) ms.push_back(made);
            if (renders >= 2 && maker_->rendersDrawn() > rendersBefore) drawingMs.push_back(made);
            if (renders >= 2 && shown.schedule.kind != condition::FrameKind::Held) newImageMs.push_back(made);
            if (secondsSince(start) > kMaxConditionSeconds) break;  // a renderer this slow fails anyway
        }
        const double budget = 1000.0 / study_->refreshHz();
        const auto late = std::count_if(ms.begin(), ms.end(), [&](double m) { return m > budget; });
        const double lateShare = ms.empty() ? 0.0 : static_cast<double>(late) / static_cast<double>(ms.size());
        // A session with more of its frames late than its protocol allows is flagged in its store
        // (missed_frames, SessionPolicy::finish in live_session.cpp): a machine that would be fails.
        const double allowed = study_->rendering().maxLateShare;
        const Verdict verdict = lateShare > allowed ? Verdict::Fail : late > 0 ? Verdict::Warn : Verdict::Ok;
        std::string detail = "median " + number(median(ms), 1) + " ms, p95 " + number(p95(ms), 1) + " ms, max " +
            number(ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end()), 1) + " ms over " +
            std::to_string(ms.size()) + " frames at " + std::to_string(display_.width) + "x" +
            std::to_string(display_.height) + "; " + std::to_string(late) + " longer than one refresh (" +
            number(budget, 2) + " ms at " + hertz(study_->refreshHz()) + ")";
        if (verdict == Verdict::Fail) {
            detail += ": more than " + number(100.0 * allowed, allowed < 0.01 ? 2 : 0) +
                " % of a session's frames would miss their vsync, and it would be flagged";
            detail += shortfall(ms, drawingMs, budget);
        } else if (verdict == Verdict::Warn)
            detail += ": those would miss their vsync";
        lines_.add(verdict, "frame time " + condition, detail);
        const CheckLine cadence =
            cadenceLine(condition, cadenceNeed(study_->conditions().at(condition), study_->refreshHz()),
                        study_->refreshHz(), p95(newImageMs), newImageMs.size());
        lines_.add(cadence.verdict, cadence.name, cadence.detail);
    }

    // How far short a session would fall: a frame m ms in the making holds the screen for the
    // whole refreshes it spans, and the game steps through the rest unseen (window_loop.cpp).
    // Once frames are that late, nearly every frame shown is made from a render the frames
    // before it did not draw, so the frames that draw one decide, not the cheap held frames
    // between them that the median of all is made of.
    std::string shortfall(const std::vector<double>& ms, const std::vector<double>& drawingMs, double budget) const {
        const double typical = std::max(median(ms), median(drawingMs));
        const double spans = std::max(1.0, std::ceil(typical / budget - 1e-9));
        return "; its frames that draw a render take a median " + number(median(drawingMs), 1) +
            " ms, so a session would show about " + number(study_->refreshHz() / spans, 1) +
            " frames a second of the display's " + number(study_->refreshHz(), 0);
    }

    // The marker's square wave, frame by frame at the measured refresh (or a timer at 60 Hz
    // where there is none), as a session would draw it: on the backdrop, nothing else moving.
    void photonPattern() {
        std::optional<renderer::HudPhotonMarker> marker = present::hudPhotonMarker(
            protocol::valueNamed<protocol::PhotonMarker>(run_.photonCorner).value_or(protocol::PhotonMarker::Off));
        if (!marker) {
            lines_.add(Verdict::Fail, "photon", "'" + run_.photonCorner + "' is no corner for the marker");
            return;
        }
        const double hz = measuredHz_ > 0.0 ? measuredHz_ : 60.0;
        const int half = std::max(1, static_cast<int>(std::lround(run_.photonOnS * hz)));
        renderer::HudContent content;
        content.backdrop = true;
        content.reticle = false;
        content.status = "photodiode test pattern";
        const auto start = Clock::now();
        for (int frame = 0; frame < 2 * half * run_.photonCycles; ++frame) {
            marker->lit = frame % (2 * half) < half;
            content.photonMarker = marker;
            hud_->draw(content, screen_->buffer());
            renderer::blitToDefaultFramebuffer(screen_->buffer(), display_.width, display_.height);
            if (!window_->vsyncOn())
                std::this_thread::sleep_until(
                    start +
                    std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>((frame + 1) / hz)));
            window_->swapBuffers();
            poll();
        }
        lines_.add(Verdict::Ok, "photon",
                   "the marker in the " + run_.photonCorner + " corner was white for " + std::to_string(half) +
                       " frames and black for " + std::to_string(half) + ", " + std::to_string(run_.photonCycles) +
                       " times (" + number(2.0 * half / hz * run_.photonCycles, 1) + " s): a meter over it reads a " +
                       number(hz / (2.0 * half), 2) + " Hz square wave");
    }

    void screen(const std::string& doing) {
        renderer::HudContent content;
        content.backdrop = true;
        content.reticle = false;
        content.banner = "warplab check";
        content.bannerGood = true;
        content.status = doing;
        hud_->draw(content, screen_->buffer());
        renderer::blitToDefaultFramebuffer(screen_->buffer(), display_.width, display_.height);
        window_->swapBuffers();
    }

    void poll() {
        const renderer::WindowInput in = window_->pollInput();
        if (in.closed || in.closeAsked) throw renderer::WindowLost("the check's window was closed before it finished");
    }

    static constexpr double kMaxConditionSeconds = 20.0;
    const CheckRun& run_;
    const game::Study* study_;
    const renderer::DataPaths& paths_;
    Lines& lines_;
    std::unique_ptr<renderer::WindowContext> window_;
    game::DisplaySize display_;
    double reportedHz_ = 0.0;
    double measuredHz_ = 0.0;  // of vsynced swaps; 0 without vsync
    // What draws: made once the window gives a context, gone before it.
    std::optional<renderer::HudRenderer> hud_;
    std::optional<renderer::DisplayFrame> screen_;
    std::optional<renderer::PassTimer> timer_;
    std::optional<present::FrameMaker> maker_;
    std::unique_ptr<game::FreePlayGame> game_;
    std::unique_ptr<game::Player> bot_;
    game::FrameInput input_;
};

// Whether a session could start here: the folder there, writable and held by no session.
bool resultsFolder(const CheckRun& run, const game::Study* study, Lines& lines) {
    try {
        const session::ResultsFolderLock lock(run.resultsDir, "check", study ? study->name() : "");
    } catch (const session::SessionError& e) {
        lines.add(Verdict::Fail, "results folder", e.what());
        return false;
    }
    lines.add(Verdict::Ok, "results folder", "'" + run.resultsDir + "' is writable and no session holds it");
    return true;
}

void disk(const CheckRun& run, const game::Study* study, const game::DisplaySize& display, Lines& lines) {
    const std::uint64_t free = runner::freeBytes(run.resultsDir);
    if (!study) {
        lines.add(Verdict::Ok, "disk", runner::bytesText(free) + " free in '" + run.resultsDir + "'");
        return;
    }
    runner::SessionSize size;
    try {
        size = runner::estimateSessionSize(*study, display);
    } catch (const std::exception& e) {
        lines.add(Verdict::Warn, "disk",
                  runner::bytesText(free) + " free in '" + run.resultsDir +
                      "'; a session's size was not measured: " + e.what());
        return;
    }
    const bool room = free >= size.neededBytes();
    lines.add(room ? Verdict::Ok : Verdict::Fail, "disk",
              runner::bytesText(free) + " free in '" + run.resultsDir + "'; a session of " + study->name() +
                  " writes about " + runner::bytesText(size.sessionBytes()) + " and needs " +
                  runner::bytesText(size.neededBytes()) + " free (" + std::to_string(size.botFrames) +
                  " frames by its bot at " + number(size.bytesPerFrame, 0) +
                  " bytes each, doubled for a participant, doubled again as it finishes)");
}

void audio(Lines& lines) {
    const FeedbackSounds sounds;
    if (!sounds.available())
        lines.add(Verdict::Warn, "audio", sounds.why() + "; a session's feedback sounds would be off");
    else if (sounds.driver() == "dummy" || sounds.driver() == "disk")
        lines.add(Verdict::Warn, "audio", "SDL's " + sounds.driver() + " audio driver plays nowhere (SDL_AUDIODRIVER)");
    else
        lines.add(Verdict::Ok, "audio", "a device is open through " + sounds.driver());
}

}  // namespace

std::string formatCheckLine(const CheckLine& line) {
    std::string verdict = line.verdict == Verdict::Ok ? "ok" : line.verdict == Verdict::Warn ? "warn" : "FAIL";
    verdict.resize(6, ' ');
    return verdict + line.name + ": " + line.detail;
}

std::vector<CheckLine> checkMachine(const CheckRun& run, const renderer::DataPaths& paths, std::ostream& out) {
    const std::unique_ptr<game::Study> study =
        run.protocolPath.empty() ? nullptr : runner::loadRunStudy(run.protocolPath, "");
    Lines lines(out);
    game::DisplaySize display{run.width, run.height};
    {
        WindowChecks window(run, study.get(), paths, lines);
        try {
            window.all();
        } catch (const renderer::ContextError& e) {  // no display, no GL 4.1, the window taken away
            lines.add(Verdict::Fail, "window", e.what());
        }
    }
    if (resultsFolder(run, study.get(), lines)) disk(run, study.get(), display, lines);
    audio(lines);
    return lines.take();
}

}  // namespace warplab::live
