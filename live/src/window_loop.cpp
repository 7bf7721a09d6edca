#include "window_loop.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>

#include "game/registry.h"
#include "image/image.h"
#include "refresh_rule.h"
#include "runner/session_runner.h"

namespace warplab::live {
namespace {

constexpr double kPi = 3.14159265358979323846;

Polled poll(renderer::Window& window, double countScale, bool invertY) {
    return readInput(window.pollInput(), countScale, invertY);
}

// A participant's sensitivity as the protocol's counts: cm per full turn at the mouse's DPI.
double countScaleFor(const LiveRun& run, const game::Study& study) {
    if (!(run.cmPer360 > 0.0) || !(study.mouseRadiansPerCount() > 0.0)) return 1.0;
    const double countsPerTurn = run.cmPer360 / 2.54 * run.mouseDpi;
    return (2.0 * kPi / countsPerTurn) / study.mouseRadiansPerCount();
}

// The run's --photon-marker, else the protocol's display.photon_marker.
protocol::PhotonMarker photonMarkerFor(const LiveRun& run, const game::Study& study) {
    if (run.photonMarker.empty()) return study.rendering().photonMarker;
    if (const auto corner = protocol::valueNamed<protocol::PhotonMarker>(run.photonMarker)) return *corner;
    throw std::invalid_argument("LiveRun::photonMarker '" + run.photonMarker + "' is no display.photon_marker");
}

}  // namespace

Polled readInput(const renderer::WindowInput& in, double countScale, bool invertY) {
    Polled p;
    p.closed = in.closed;
    p.closeAsked = in.closeAsked;
    p.focusLost = in.focusLost;
    p.keys = in.keysPressed;
    p.input.mouseDx = in.mouseDx * countScale;
    p.input.mouseDy = in.mouseDy * countScale * (invertY ? -1.0 : 1.0);
    p.input.buttons = in.leftHeld ? game::kButtonLeft : 0u;
    static_assert(renderer::kTypedBackspace == game::kTextBackspace, "the window's Backspace is the game's");
    p.input.text = in.text;
    for (const char c : in.keysPressed) {
        if (c == '\r') p.input.keys |= game::kKeyEnter;
        if (c >= '1' && c <= '9') p.input.keys |= game::digitKey(c - '0');
        if (c == 27) p.escape = true;
    }
    return p;
}

DisplayClock::DisplayClock(renderer::Window& window, double refreshHz, bool byVsync)
    : window_(window), period_(1.0 / refreshHz), byVsync_(byVsync), last_(Clock::now()), deadline_(last_) {}

DisplayClock::Presented DisplayClock::present() {
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_));
    if (!byVsync_) {
        deadline_ += period;
        std::this_thread::sleep_until(deadline_);
    }
    window_.swapBuffers();
    const auto now = Clock::now();
    const double frameS = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    const bool first = std::exchange(first_, false);
    if (first) {
        deadline_ = now;
        return {frameS, 0};
    }
    if (!byVsync_) {
        // Whole ticks past the deadline are display frames this one took: the deadline moves
        // past them, as the game does, rather than the clock falling behind for good.
        const int missed = now > deadline_ ? static_cast<int>((now - deadline_) / period) : 0;
        deadline_ += missed * period;
        return {frameS, missed};
    }
    return {frameS, std::max(0, static_cast<int>(std::lround(frameS / period_)) - 1)};
}

void DisplayClock::restart() {
    deadline_ = last_ = Clock::now();
    first_ = true;
}

WindowLoop::Opened WindowLoop::open(const LiveRun& run, const game::Study& study, std::ostream& progress) {
    renderer::ContextOptions options;
    options.width = run.width;
    options.height = run.height;
    options.fullscreen = run.fullscreen;
    options.display = run.display;
    options.title = "warplab: " + study.name();
    Opened w;
    w.window = renderer::createWindow(options);
    w.display = {w.window->drawableWidth(), w.window->drawableHeight()};
    const double refresh = study.refreshHz();
    w.measuredHz = w.window->refreshHz();
    w.byVsync = w.window->vsyncOn() && w.measuredHz > 0.0 && std::abs(w.measuredHz - refresh) < 0.5;
    if (refusesRefresh(w.measuredHz, study, run.allowRefreshMismatch))
        throw std::runtime_error(refreshText(w.measuredHz, refresh, run.protocolPath, true));
    if (w.measuredHz > 0.0 && std::abs(w.measuredHz - refresh) >= 0.5) {
        progress << "warning: " << refreshText(w.measuredHz, refresh, run.protocolPath, false)
                 << "; frames are paced by a timer, not by vsync\n";
    } else if (!w.byVsync) {
        progress << "note: " << (w.measuredHz > 0.0 ? "vsync could not be set" : "the display reports no refresh rate")
                 << "; frames are paced by a timer at " << refresh << " Hz\n";
    }
    return w;
}

WindowLoop::WindowLoop(const LiveRun& run, const renderer::DataPaths& paths, std::ostream& progress)
    : run_(run),
      progress_(progress),
      study_(runner::loadRunStudy(run.protocolPath, run.protocolText)),
      script_(run.inputScript.empty() ? InputScript() : InputScript(run.inputScript)),
      opened_(open(run, *study_, progress)),
      window_(*opened_.window),
      display_(opened_.display),
      countScale_(countScaleFor(run, *study_)),
      player_(run.player == "human" ? nullptr : runner::makePlayer(run.player, run.seed, *study_, display_)),
      maker_(paths, display_.width, display_.height, study_->rendering()),
      hud_(paths),
      screen_(display_.width, display_.height),
      clock_(window_, study_->refreshHz(), opened_.byVsync),
      photonCorner_(photonMarkerFor(run, *study_)),
      photonMarker_(present::hudPhotonMarker(photonCorner_)) {
    if (!sounds_.available()) progress << "note: " << sounds_.why() << "; feedback sounds are off\n";
    maker_.prepareFor(*study_);
}

WindowLoop::~WindowLoop() = default;

double WindowLoop::shownRefreshHz() const { return opened_.byVsync ? opened_.measuredHz : study_->refreshHz(); }

void WindowLoop::captureMouse(bool on) { window_.setRelativeMouse(on && human()); }

void WindowLoop::showScreen(const std::string& banner, const std::string& status) {
    renderer::HudContent content;
    content.backdrop = true;
    content.reticle = false;
    content.banner = banner;
    content.bannerGood = true;
    content.status = status;
    content.photonMarker = photonMarker_;  // black: a sensor sees no press answered
    hud_.draw(content, screen_.buffer());
    renderer::blitToDefaultFramebuffer(screen_.buffer(), window_.drawableWidth(), window_.drawableHeight());
    window_.swapBuffers();
}

char WindowLoop::waitFor(const std::string& banner, const std::string& status, const std::string& keys,
                         const std::string& pending, std::string* rest) {
    // The first of `keys` in `read`, and what follows it into *rest.
    auto first = [&](const std::string& read) -> char {
        const std::size_t at = read.find_first_of(keys);
        if (at == std::string::npos) return 0;
        const char c = read[at];
        if (rest) *rest = read.substr(at + 1);  // `read` may be *rest
        return c;
    };
    if (const char c = first(pending)) return c;
    for (;;) {
        showScreen(banner, status);
        const renderer::WindowInput in = window_.pollInput();
        if (in.closed || in.closeAsked) {
            quit_ = in.closed;
            return 0;
        }
        if (const char c = first(in.keysPressed)) return c;
        if (!window_.vsyncOn()) std::this_thread::sleep_for(std::chrono::milliseconds(16));
    }
}

void WindowLoop::playSoundCheck(std::ostream& progress) {
    progress << "sound check:";
    for (const std::string& name : FeedbackSounds::names()) progress << " " << name;
    if (!sounds_.available()) progress << " (not played: " << sounds_.why() << ")";
    progress << "\n";
    sounds_.playEach();
}

void WindowLoop::screenshot(const std::string& name) {
    image::writePng(run_.screenshotDir + "/" + name + ".png", renderer::readBack(screen_).colour);
}

void WindowLoop::inject(const std::string& when) { script_.inject(window_, when); }

void WindowLoop::sawBeforeResume(const game::ShownFrame& shown) {
    if (player_) {
        if (!std::exchange(playerStarted_, true)) player_->first();
        resumedInput_ = player_->next(shown);
    }
    // A frame is made from sources at most a few renders old (a hold, a warp of the last one,
    // bidirectional reprojection's two around it, whose flow needs the one before).
    constexpr std::size_t kSourcesKept = 3;
    if (shown.rendersNow) keptSources_.push_back(shown);
    if (keptSources_.size() > kSourcesKept) keptSources_.pop_front();
    firstFrame_ = shown.frame + 1;
}

WindowLoop::End WindowLoop::run(LoopPolicy& policy) {
    game::Game& game = policy.game();
    game::FrameInput input = !player_ ? game::FrameInput{} : playerStarted_ ? resumedInput_ : player_->first();
    for (const game::ShownFrame& source : keptSources_) maker_.keepSource(source);
    keptSources_.clear();
    End end;
    std::int64_t frame = firstFrame_, injectedFor = firstFrame_ - 1;  // frame: the display frame to show next
    clock_.restart();
    while (!game.finished() && (!player_ || player_->hasMore())) {
        // Each frame's scripted input once, also across a pause; a skipped frame's reaches the
        // next frame shown, as a participant's input does.
        while (injectedFor < frame) inject(std::to_string(++injectedFor));
        const Polled polled = poll(window_, countScale_, run_.invertY);
        if (human()) input = polled.input;
        const Stop stop = stopFor(polled);
        if (polled.closed || (stop != Stop::None && !pause(polled.keys, stop, frame, policy))) {
            end.aborted = true;
            break;
        }
        if (stop != Stop::None) continue;  // resumed: the frame is polled again

        policy.beforeStep(polled.keys, frame, input);
        const game::ShownFrame shown = game.step(input);
        policy.stepped(shown, input);
        const FrameTiming timing = show(shown, frame, policy, photonTiming_.step(shown, input, true));
        policy.presented(shown, timing);
        if (std::find(run_.screenshotFrames.begin(), run_.screenshotFrames.end(), frame) != run_.screenshotFrames.end())
            screenshot(policy.screenshotName(frame));
        end.lastFrame = shown.frame;
        ++frame;
        // The display frames this one took from the next: the game steps through them, so a
        // trial's seconds stay the protocol's, and they are recorded as skipped. The participant
        // holds what they held (what the mouse did meanwhile reaches the next frame shown); a
        // player gives its input frame by frame, as if each was shown.
        const game::FrameInput held{0.0, 0.0, input.buttons, input.keys};
        if (player_) input = player_->next(shown);
        const int skips = run_.everyFrame ? 0 : timing.missedVsyncs;
        for (int i = 0; i < skips && !game.finished() && (!player_ || player_->hasMore()); ++i) {
            const game::FrameInput passedInput = player_ ? input : held;
            const game::ShownFrame passed = game.step(passedInput);
            policy.stepped(passed, passedInput);
            photonTiming_.step(passed, passedInput, false);  // never seen: the next frame shown answers
            maker_.keepSource(passed);  // a later frame may be made from its render
            FrameTiming skipped;
            skipped.skipped = true;
            policy.presented(passed, skipped);
            end.lastFrame = passed.frame;
            ++frame;
            if (player_) input = player_->next(passed);
        }
    }
    return end;
}

WindowLoop::Stop WindowLoop::stopFor(const Polled& polled) const {
    if (polled.closeAsked) return Stop::Close;
    if (polled.escape) return Stop::Escape;
    // A bot or a recorded player plays on: it does not look at the window.
    if (polled.focusLost && human()) return Stop::Away;
    return Stop::None;
}

bool WindowLoop::pause(const std::string& keys, Stop stop, std::int64_t frame, const LoopPolicy& policy) {
    // Nothing is recorded while paused, and ending needs a second key. The keys read with the
    // Esc after it, or with the window manager's close, are the supervisor's answer; those read
    // with a focus loss were the participant's.
    window_.setRelativeMouse(false);
    std::string pending = stop == Stop::Escape ? keys.substr(keys.find('\x1b') + 1) : stop == Stop::Close ? keys : "";
    if (stop != Stop::Escape)
        progress_ << "paused at frame " << frame << ": "
                  << (stop == Stop::Close ? "the window was asked to close" : "the window lost the focus") << "\n";
    for (;;) {
        const bool closing = stop == Stop::Close;
        const std::string text = closing ? policy.closeText()
            : stop == Stop::Away ? "The window went to the background, so the session paused. " + policy.pauseText()
                                 : policy.pauseText();
        const char c = waitFor(closing ? "Close the session?" : "Paused", text, "\rq", pending);
        if (c == 'q') return false;
        if (c == '\r') break;
        // Closed: a second close (or a quit) ends it; a first one asks.
        if (closing || quit_) return false;
        stop = Stop::Close;
        pending.clear();
        progress_ << "paused at frame " << frame << ": the window was asked to close\n";
    }
    captureMouse(true);
    clock_.restart();
    return true;
}

FrameTiming WindowLoop::show(const game::ShownFrame& shown, std::int64_t frame, LoopPolicy& policy,
                             const PhotonMarkerTiming::Answer& marker) {
    // Making the frame, timed to glFinish: what must fit in one refresh. (The glFinish only
    // waits for what the swap would wait for anyway.)
    timer_.begin();
    maker_.keepSource(shown);
    if (!shown.blank) maker_.make(shown, screen_);
    for (const std::string& note : maker_.takeNotes()) progress_ << "note: " << note << "\n";
    renderer::HudContent content = present::hudFor(shown, 1.0, 1.0);
    policy.decorate(shown, frame, content);
    content.photonMarker = photonMarker_;
    if (content.photonMarker) content.photonMarker->lit = marker.lit;
    hud_.draw(content, screen_.buffer());
    renderer::blitToDefaultFramebuffer(screen_.buffer(), display_.width, display_.height);
    if (run_.slowEvery > 0 && frame % run_.slowEvery == 0)
        std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(run_.slowMs));
    const double renderMs = timer_.end().wallMs;
    const DisplayClock::Presented presented = clock_.present();
    if (!shown.feedback.empty()) sounds_.play(shown.feedback);
    FrameTiming timing{presented.frameS * 1000.0, renderMs, presented.missedVsyncs};
    timing.photonMarker = photonMarker_ && marker.lit;
    timing.photonPress = timing.photonMarker ? marker.press : -1;
    return timing;
}

}  // namespace warplab::live
