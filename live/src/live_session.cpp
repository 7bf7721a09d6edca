#include "live/live_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>

#include "present/frame_maker.h"
#include "study/session_runner.h"
#include "sound.h"
#include "game/registry.h"
#include "session/session_store.h"
#include "renderer/hud.h"
#include "image/image.h"
#include "renderer/timing.h"
#include "renderer/window.h"

namespace warplab::live {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kPi = 3.14159265358979323846;

// What the window's input means to the game (Enter, digits, the left button) and to the
// supervisor (Esc, and the answers on the pause screen).
struct Polled {
    game::FrameInput input;
    bool escape = false, closed = false;
    std::string keys;
};

Polled poll(renderer::Window& window, double countScale, bool invertY) {
    const renderer::WindowInput in = window.pollInput();
    Polled p;
    p.closed = in.closed;
    p.keys = in.keysPressed;
    p.input.mouseDx = in.mouseDx * countScale;
    p.input.mouseDy = in.mouseDy * countScale * (invertY ? -1.0 : 1.0);
    p.input.buttons = in.leftHeld ? game::kButtonLeft : 0u;
    for (const char c : in.keysPressed) {
        if (c == '\r') p.input.keys |= game::kKeyEnter;
        if (c >= '1' && c <= '9') p.input.keys |= game::digitKey(c - '0');
        if (c == 27) p.escape = true;
    }
    return p;
}

// A screen of the supervisor's flow (not part of the session): a dark backdrop and text.
void showScreen(renderer::HudRenderer& hud, renderer::DisplayFrame& frame, renderer::Window& window,
                const std::string& banner, const std::string& status) {
    renderer::HudContent content;
    content.backdrop = true;
    content.reticle = false;
    content.banner = banner;
    content.bannerGood = true;
    content.status = status;
    hud.draw(content, frame.buffer());
    renderer::blitToDefaultFramebuffer(frame.buffer(), window.drawableWidth(), window.drawableHeight());
    window.swapBuffers();
}

// Waits on a screen until one of `keys` is pressed (or the window closes: returns 0).
// `pending`: keys already read with the one that opened the screen (a fast typist, a script).
char waitFor(renderer::HudRenderer& hud, renderer::DisplayFrame& frame, renderer::Window& window,
             const std::string& banner, const std::string& status, const std::string& keys,
             const std::string& pending = "") {
    for (const char c : pending)
        if (keys.find(c) != std::string::npos) return c;
    for (;;) {
        showScreen(hud, frame, window, banner, status);
        const renderer::WindowInput in = window.pollInput();
        if (in.closed) return 0;
        for (const char c : in.keysPressed)
            if (keys.find(c) != std::string::npos) return c;
        if (!window.vsyncOn()) std::this_thread::sleep_for(std::chrono::milliseconds(16));
    }
}

// The --input-script: what the window receives at each moment, as if from the participant.
class InputScript {
public:
    InputScript() = default;
    explicit InputScript(const std::string& path) {
        std::ifstream file(path);
        if (!file) throw std::runtime_error("cannot read input script '" + path + "'");
        std::string line;
        for (int number = 1; std::getline(file, line); ++number) {
            std::istringstream words(line);
            std::string when, action;
            if (!(words >> when) || when[0] == '#') continue;
            auto bad = [&](const std::string& why) {
                return std::runtime_error("input script '" + path + "' line " + std::to_string(number) + ": " + why);
            };
            if (!(words >> action)) throw bad("no action after '" + when + "'");
            if (when != "start" && when != "end" && when.find_first_not_of("0123456789") != std::string::npos)
                throw bad("'" + when + "' is not a frame number, start or end");
            renderer::WindowInput& in = at_[when];
            if (action == "click") {
                in.leftHeld = true;
            } else if (action == "move") {
                if (!(words >> in.mouseDx >> in.mouseDy)) throw bad("move needs DX DY");
            } else if (action == "key") {
                std::string key;
                words >> key;
                if (key == "enter") in.keysPressed += '\r';
                else if (key == "esc") in.keysPressed += '\x1b';
                else if (key.size() == 1 && std::isalnum(static_cast<unsigned char>(key[0])))
                    in.keysPressed += static_cast<char>(std::tolower(static_cast<unsigned char>(key[0])));
                else throw bad("unknown key '" + key + "' (enter, esc, a letter or a digit)");
            } else {
                throw bad("unknown action '" + action + "' (key, move or click)");
            }
        }
    }
    void inject(renderer::Window& window, const std::string& when) const {
        const auto it = at_.find(when);
        if (it != at_.end()) window.injectInput(it->second);
    }

private:
    std::map<std::string, renderer::WindowInput> at_;
};

void screenshot(const LiveRun& run, const renderer::DisplayFrame& frame, const std::string& name) {
    image::writePng(run.screenshotDir + "/" + name + ".png", renderer::readBack(frame).colour);
}

// One present per vsync, or per timer tick where vsync cannot keep the protocol's rate.
class DisplayClock {
public:
    DisplayClock(renderer::Window& window, double refreshHz, bool byVsync)
        : window_(window), period_(1.0 / refreshHz), byVsync_(byVsync), last_(Clock::now()), deadline_(last_) {}

    struct Presented {
        double frameS;     // since the previous present
        int missedVsyncs;  // a frame that took n periods to reach the screen missed n - 1
    };
    Presented present() {
        if (!byVsync_) {
            deadline_ += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_));
            std::this_thread::sleep_until(deadline_);
        }
        window_.swapBuffers();
        const auto now = Clock::now();
        const double frameS = std::chrono::duration<double>(now - last_).count();
        last_ = now;
        if (!byVsync_ && now > deadline_ + std::chrono::milliseconds(100)) deadline_ = now;  // fell far behind
        const bool first = std::exchange(first_, false);
        return {frameS, first ? 0 : std::max(0, static_cast<int>(std::lround(frameS / period_)) - 1)};
    }
    // After a pause: the next frame is not late.
    void restart() {
        deadline_ = last_ = Clock::now();
        first_ = true;
    }

private:
    renderer::Window& window_;
    double period_;
    bool byVsync_;
    Clock::time_point last_, deadline_;
    bool first_ = true;
};

struct OpenedWindow {
    std::unique_ptr<renderer::WindowContext> context;
    game::DisplaySize display;
    bool byVsync = false;
    double measuredHz = 0.0;
};

// Opens the window and decides the display clock: vsync at the protocol's refresh, else a
// timer at it; a known refresh that differs refuses unless allowed.
OpenedWindow openWindow(const LiveRun& run, const game::Study& study, std::ostream& progress) {
    renderer::ContextOptions options;
    options.width = run.width;
    options.height = run.height;
    options.fullscreen = run.fullscreen;
    options.display = run.display;
    options.title = "warplab: " + study.name();
    OpenedWindow w;
    w.context = renderer::createWindow(options);
    w.display = {w.context->drawableWidth(), w.context->drawableHeight()};
    const double refresh = study.refreshHz();
    w.measuredHz = w.context->refreshHz();
    w.byVsync = w.context->vsyncOn() && w.measuredHz > 0.0 && std::abs(w.measuredHz - refresh) < 0.5;
    if (w.measuredHz > 0.0 && std::abs(w.measuredHz - refresh) >= 0.5) {
        std::ostringstream why;
        why << "the display runs at " << w.measuredHz << " Hz but protocol '" << run.protocolPath << "' needs "
            << refresh << " Hz";
        if (!run.allowRefreshMismatch && !study.warnsOnRefreshMismatch())
            throw std::runtime_error(why.str() + "; set the display to " + std::to_string(std::lround(refresh)) +
                                     " Hz (or pass --allow-refresh-mismatch for a pilot)");
        progress << "warning: " << why.str() << "; frames are paced by a timer, not by vsync\n";
    } else if (!w.byVsync) {
        progress << "note: " << (w.measuredHz > 0.0 ? "vsync could not be set" : "the display reports no refresh rate")
                 << "; frames are paced by a timer at " << refresh << " Hz\n";
    }
    return w;
}

// A participant's sensitivity as the protocol's counts: cm per full turn at the mouse's DPI.
double countScaleFor(const LiveRun& run, const game::Study& study) {
    if (!(run.cmPer360 > 0.0) || !(study.mouseRadiansPerCount() > 0.0)) return 1.0;
    const double countsPerTurn = run.cmPer360 / 2.54 * run.mouseDpi;
    return (2.0 * kPi / countsPerTurn) / study.mouseRadiansPerCount();
}

}  // namespace

std::string runLive(const LiveRun& run, const renderer::DataPaths& paths, std::ostream& progress) {
    const auto study = game::loadStudy(run.protocolPath);
    OpenedWindow opened = openWindow(run, *study, progress);
    renderer::WindowContext* const window = opened.context.get();
    const game::DisplaySize display = opened.display;
    const int width = display.width, height = display.height;
    const double countScale = countScaleFor(run, *study);
    std::ostringstream playerText;
    playerText << run.player;
    if (run.player == "human")
        playerText << " (cm_per_360=" << run.cmPer360 << ", dpi=" << run.mouseDpi
                   << ", invert_y=" << (run.invertY ? 1 : 0) << ")";
    const bool human = run.player == "human";
    const auto player = human ? nullptr : study::makePlayer(run.player, run.seed, *study, display);

    present::FrameMaker maker(paths, width, height, study->rendering());
    renderer::HudRenderer hud(paths);
    renderer::DisplayFrame frame(width, height);
    FeedbackSounds sounds;
    if (!sounds.available()) progress << "note: " << sounds.why() << "; feedback sounds are off\n";

    // Start screen (Appendix B: the supervisor checks the participant and the protocol).
    const std::string who = "Participant " + run.participant + ", protocol " + study->name();
    if (run.screenshotStartScreen) {
        showScreen(hud, frame, *window, "warplab", who + ". Press Enter to start.");
        screenshot(run, frame, "start");
    }
    const InputScript script = run.inputScript.empty() ? InputScript() : InputScript(run.inputScript);
    script.inject(*window, "start");
    if (human && waitFor(hud, frame, *window, "warplab", who + ". Press Enter to start, Esc to leave.", "\r\x1b") != '\r')
        return "";

    auto header = study::sessionHeader(*study, run.participant, run.seed, playerText.str(), display);
    header.glRenderer = window->info().renderer;
    header.glVersion = window->info().version;
    header.refreshHz = opened.byVsync ? opened.measuredHz : study->refreshHz();
    auto writer = session::SessionWriter::create(run.resultsDir, header);
    progress << "session " << writer.path() << "\n";
    if (human) window->setRelativeMouse(true);

    const auto game = study->newGame(run.seed, display);
    study::SessionCommits commits(writer, study->refreshHz(), progress);
    std::map<std::string, std::pair<long, long>> missedPerMode;  // mode -> missed vsyncs, frames
    std::map<std::string, long> lateFramesPerMode;               // mode -> frames that missed one
    game::ShownFrame shown;
    game::FrameInput input = player ? player->first() : game::FrameInput{};
    DisplayClock clock(*window, study->refreshHz(), opened.byVsync);
    renderer::PassTimer timer;
    bool aborted = false;
    std::int64_t nextFrame = 0, injectedFor = -1;
    while (!game->finished() && (!player || player->hasMore())) {
        if (injectedFor != nextFrame) script.inject(*window, std::to_string(nextFrame));  // once, also across a pause
        injectedFor = nextFrame;
        const Polled polled = poll(*window, countScale, run.invertY);
        if (human) input = polled.input;
        if (polled.closed) {
            aborted = true;
            break;
        }
        if (polled.escape) {
            // Esc pauses: the display clock stops, nothing is recorded; ending needs a second key.
            window->setRelativeMouse(false);
            const std::string after = polled.keys.substr(polled.keys.find('\x1b') + 1);
            const char c = waitFor(hud, frame, *window, "Paused",
                                   "Enter resumes. Q ends the session: everything recorded so far is kept.", "\rq",
                                   after);
            if (c != '\r') {
                aborted = true;
                break;
            }
            if (human) window->setRelativeMouse(true);
            clock.restart();
            continue;
        }

        shown = game->step(input);
        nextFrame = shown.frame + 1;
        writer.addInput(study::toRecord(shown.frame, shown.time, input));
        for (auto& e : game->takeEvents()) writer.addEvent(e);

        // Making the frame, timed to glFinish: what must fit in one refresh. (The glFinish
        // only waits for what the swap would wait for anyway.)
        timer.begin();
        maker.keepSource(shown);
        if (!shown.blank) maker.make(shown, frame);
        renderer::HudContent content = present::hudFor(shown, 1.0, 1.0);
        const std::string waiting = commits.waitingText();  // the supervisor must see it
        if (!waiting.empty()) content.status = waiting;
        hud.draw(content, frame.buffer());
        renderer::blitToDefaultFramebuffer(frame.buffer(), width, height);
        const double renderMs = timer.end().wallMs;
        const DisplayClock::Presented presented = clock.present();
        if (!shown.feedback.empty()) sounds.play(shown.feedback);

        session::FrameRecord record = game->frameRecord(shown);
        record.frameMs = presented.frameS * 1000.0;
        record.renderMs = renderMs;
        record.missedVsyncs = presented.missedVsyncs;
        const std::string mode = shown.mode.empty() ? "(screens)" : shown.mode;
        auto& tally = missedPerMode[mode];
        tally.first += record.missedVsyncs;
        ++tally.second;
        lateFramesPerMode[mode] += record.missedVsyncs > 0;
        writer.addFrame(record);
        commits.afterFrame(shown.frame, game->atCommitPoint());

        if (std::find(run.screenshotFrames.begin(), run.screenshotFrames.end(), shown.frame) != run.screenshotFrames.end())
            screenshot(run, frame, "frame_" + std::to_string(shown.frame));
        if (player) input = player->next(shown);
    }
    window->setRelativeMouse(false);
    // More than 1 % of frames late is more than a study can call "at the protocol's rate":
    // the store says so, and export can leave such sessions out.
    long missed = 0, frames = 0, lateFrames = 0;
    for (const auto& [mode, tally] : missedPerMode) {
        missed += tally.first;
        frames += tally.second;
        lateFrames += lateFramesPerMode[mode];
    }
    if (frames > 0 && lateFrames * 100 > frames) {
        std::ostringstream text;
        text << lateFrames << " of " << frames << " frames missed their vsync (" << missed << " vsyncs in all)";
        writer.flag("missed_frames", text.str());
        progress << "warning: " << text.str() << "; the session is flagged\n";
    }
    commits.end(game->finished(), [&](const std::string& line) {
        showScreen(hud, frame, *window, "Saving", line);
        window->pollInput();  // keeps the window responsive while it waits
    });

    progress << "missed vsyncs per mode (missed / frames):";
    for (const auto& [mode, tally] : missedPerMode)
        progress << " " << mode << " " << tally.first << "/" << tally.second;
    progress << "\n";
    if (aborted) {
        progress << "session ended by the supervisor at frame " << shown.frame << "; everything recorded is kept\n";
        return writer.path();
    }
    if (run.screenshotStartScreen) {
        showScreen(hud, frame, *window, "Thank you", "The experiment has ended.");
        screenshot(run, frame, "end");
    }
    script.inject(*window, "end");
    if (human) waitFor(hud, frame, *window, "Thank you", "The experiment has ended. Press Enter or Esc to close.", "\r\x1b");
    return writer.path();
}

void runFreePlay(const LiveRun& run, const renderer::DataPaths& paths, std::ostream& progress) {
    const auto study = game::loadStudy(run.protocolPath);
    OpenedWindow opened = openWindow(run, *study, progress);
    renderer::Window& window = *opened.context;
    const game::DisplaySize display = opened.display;
    const double countScale = countScaleFor(run, *study);
    const bool human = run.player == "human";
    const auto player = human ? nullptr : study::makePlayer(run.player, run.seed, *study, display);

    std::string mode = run.freePlayMode.empty() ? study->modes().front() : run.freePlayMode;
    int level = run.freePlayLevel;
    auto game = study->newFreePlay(run.seed, display, mode, level);
    present::FrameMaker maker(paths, display.width, display.height, study->rendering());
    renderer::HudRenderer hud(paths);
    renderer::DisplayFrame frame(display.width, display.height);
    FeedbackSounds sounds;
    DisplayClock clock(window, study->refreshHz(), opened.byVsync);
    const InputScript script = run.inputScript.empty() ? InputScript() : InputScript(run.inputScript);
    const std::vector<std::string> modes = game::modeIds();
    std::vector<double> recentMs;  // the last second's frame times, for the status line
    long late = 0;
    std::string said;              // why the last key was refused, shown for a while
    std::int64_t saidUntil = -1;
    if (human) window.setRelativeMouse(true);
    game::ShownFrame shown;
    game::FrameInput input = player ? player->first() : game::FrameInput{};
    for (std::int64_t n = 0;; ++n) {
        script.inject(window, std::to_string(n));
        const Polled polled = poll(window, countScale, run.invertY);
        if (human) input = polled.input;
        if (polled.closed) break;
        if (polled.escape) {
            window.setRelativeMouse(false);
            if (waitFor(hud, frame, window, "Paused", "Free play. Enter resumes, Q ends.", "\rq",
                        polled.keys.substr(polled.keys.find('\x1b') + 1)) != '\r')
                break;
            if (human) window.setRelativeMouse(true);
            clock.restart();
            continue;
        }
        // The supervisor's keys: digits pick a mode, U and D the difficulty.
        std::string nextMode = mode;
        int nextLevel = level;
        for (const char c : polled.keys) {
            if (c >= '1' && c <= '9' && static_cast<std::size_t>(c - '1') < modes.size()) nextMode = modes[c - '1'];
            if (c == 'u') ++nextLevel;
            if (c == 'd') nextLevel = std::max(0, nextLevel - 1);
        }
        if (nextMode != mode || nextLevel != level) {
            try {
                game->switchTo(nextMode, nextLevel);
                mode = nextMode;
                level = nextLevel;
                progress << "free play: " << mode << ", level " << level << "\n";
            } catch (const std::invalid_argument& e) {
                said = e.what();
                saidUntil = n + static_cast<std::int64_t>(2 * study->refreshHz());
            }
        }
        input.keys = 0;  // the keys were the supervisor's, not the game's
        shown = game->step(input);
        game->takeEvents();
        maker.keepSource(shown);
        if (!shown.blank) maker.make(shown, frame);
        renderer::HudContent content = present::hudFor(shown, 1.0, 1.0);
        std::vector<double> sorted = recentMs;
        std::sort(sorted.begin(), sorted.end());
        char stats[160];
        std::snprintf(stats, sizeof stats, " | %.1f ms median, %.1f max, %ld late | keys 1-9, U, D, Esc",
                      sorted.empty() ? 0.0 : sorted[sorted.size() / 2], sorted.empty() ? 0.0 : sorted.back(), late);
        content.status = (n < saidUntil ? said : shown.phaseText) + stats;
        hud.draw(content, frame.buffer());
        renderer::blitToDefaultFramebuffer(frame.buffer(), display.width, display.height);
        const DisplayClock::Presented presented = clock.present();
        if (!shown.feedback.empty()) sounds.play(shown.feedback);
        late += presented.missedVsyncs > 0;
        recentMs.push_back(presented.frameS * 1000.0);
        if (recentMs.size() > static_cast<std::size_t>(study->refreshHz())) recentMs.erase(recentMs.begin());
        if (std::find(run.screenshotFrames.begin(), run.screenshotFrames.end(), n) != run.screenshotFrames.end())
            screenshot(run, frame, "free_" + std::to_string(n));
        if (player) input = player->next(shown);
        if (player && !player->hasMore()) break;
    }
    window.setRelativeMouse(false);
    progress << "free play ended: " << late << " late frames\n";
}

}  // namespace warplab::live
