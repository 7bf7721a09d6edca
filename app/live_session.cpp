#include "app/live_session.h"

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

#include "app/frame_maker.h"
#include "app/session_runner.h"
#include "app/sound.h"
#include "game/registry.h"
#include "protocol/session_store.h"
#include "renderer/hud.h"
#include "renderer/image.h"

namespace warplab::app {
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

Polled poll(renderer::GlContext& window, double countScale, bool invertY) {
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
void showScreen(renderer::HudRenderer& hud, renderer::DisplayFrame& frame, renderer::GlContext& window,
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
char waitFor(renderer::HudRenderer& hud, renderer::DisplayFrame& frame, renderer::GlContext& window,
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
    void inject(renderer::GlContext& window, const std::string& when) const {
        const auto it = at_.find(when);
        if (it != at_.end()) window.injectInput(it->second);
    }

private:
    std::map<std::string, renderer::WindowInput> at_;
};

void screenshot(const LiveRun& run, const renderer::DisplayFrame& frame, const std::string& name) {
    renderer::writePng(run.screenshotDir + "/" + name + ".png", renderer::readBack(frame).colour);
}

}  // namespace

std::string runLive(const LiveRun& run, const renderer::DataPaths& paths, std::ostream& progress) {
    const auto study = game::loadStudy(run.protocolPath);
    renderer::ContextOptions options;
    options.backend = renderer::GlBackend::Window;
    options.width = run.width;
    options.height = run.height;
    options.fullscreen = run.fullscreen;
    options.display = run.display;
    options.title = "warplab: " + study->name();
    const auto window = renderer::createContext(options);
    const int width = window->drawableWidth(), height = window->drawableHeight();
    const game::DisplaySize display{width, height};

    // The display clock: vsync at the protocol's refresh, else a timer at it.
    const double refresh = study->refreshHz(), measured = window->refreshHz();
    const bool byVsync = window->vsyncOn() && measured > 0.0 && std::abs(measured - refresh) < 0.5;
    if (measured > 0.0 && std::abs(measured - refresh) >= 0.5) {
        std::ostringstream why;
        why << "the display runs at " << measured << " Hz but protocol '" << run.protocolPath << "' needs " << refresh
            << " Hz";
        if (!run.allowRefreshMismatch)
            throw std::runtime_error(why.str() + "; set the display to " + std::to_string(std::lround(refresh)) +
                                     " Hz (or pass --allow-refresh-mismatch for a pilot)");
        progress << "warning: " << why.str() << "; frames are paced by a timer, not by vsync\n";
    } else if (!byVsync) {
        progress << "note: " << (measured > 0.0 ? "vsync could not be set" : "the display reports no refresh rate")
                 << "; frames are paced by a timer at " << refresh << " Hz\n";
    }

    // A participant's sensitivity as the protocol's counts: cm per full turn at the mouse's DPI.
    double countScale = 1.0;
    if (run.cmPer360 > 0.0 && study->mouseRadiansPerCount() > 0.0) {
        const double countsPerTurn = run.cmPer360 / 2.54 * run.mouseDpi;
        countScale = (2.0 * kPi / countsPerTurn) / study->mouseRadiansPerCount();
    }
    std::ostringstream playerText;
    playerText << run.player;
    if (run.player == "human")
        playerText << " (cm_per_360=" << run.cmPer360 << ", dpi=" << run.mouseDpi
                   << ", invert_y=" << (run.invertY ? 1 : 0) << ")";
    const bool human = run.player == "human";
    const auto player = human ? nullptr : makePlayer(run.player, run.seed, *study, display);

    FrameMaker maker(paths, width, height, progress);
    renderer::HudRenderer hud(paths);
    renderer::DisplayFrame frame(width, height);
    FeedbackSounds sounds;
    if (!sounds.available()) progress << "note: " << sounds.why() << "; feedback sounds are off\n";
    sayStandIns(*study, progress);

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

    auto header = sessionHeader(*study, run.participant, run.seed, playerText.str(), display);
    header.glRenderer = window->info().renderer;
    header.glVersion = window->info().version;
    header.refreshHz = byVsync ? measured : refresh;
    auto writer = protocol::SessionWriter::create(run.resultsDir, header);
    progress << "session " << writer.path() << "\n";
    if (human) window->setRelativeMouse(true);

    const auto game = study->newGame(run.seed, display);
    const double period = 1.0 / refresh;
    std::map<std::string, std::pair<long, long>> missedPerMode;  // mode -> missed vsyncs, frames
    std::map<std::string, long> lateFramesPerMode;               // mode -> frames that missed one
    game::ShownFrame shown;
    game::FrameInput input = player ? player->first() : game::FrameInput{};
    auto lastPresent = Clock::now();
    auto deadline = lastPresent;
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
            deadline = lastPresent = Clock::now();
            continue;
        }

        shown = game->step(input);
        nextFrame = shown.frame + 1;
        writer.addInput(toRecord(shown.frame, shown.time, input));
        for (auto& e : game->takeEvents()) writer.addEvent(e);

        maker.keepSource(shown);
        if (!shown.blank) maker.make(shown, frame);
        hud.draw(hudFor(shown, 1.0, 1.0), frame.buffer());
        renderer::blitToDefaultFramebuffer(frame.buffer(), width, height);
        if (!byVsync) {
            deadline += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period));
            std::this_thread::sleep_until(deadline);
        }
        window->swapBuffers();
        const auto presented = Clock::now();
        const double frameS = std::chrono::duration<double>(presented - lastPresent).count();
        lastPresent = presented;
        if (!byVsync && presented > deadline + std::chrono::milliseconds(100)) deadline = presented;  // fell far behind
        if (!shown.feedback.empty()) sounds.play(shown.feedback);

        protocol::FrameRecord record = game->frameRecord(shown);
        record.frameMs = frameS * 1000.0;
        // A frame that took n refresh periods to reach the screen missed n - 1 vsyncs.
        record.missedVsyncs = shown.frame == 0 ? 0 : std::max(0, static_cast<int>(std::lround(frameS / period)) - 1);
        const std::string mode = shown.mode.empty() ? "(screens)" : shown.mode;
        auto& tally = missedPerMode[mode];
        tally.first += record.missedVsyncs;
        ++tally.second;
        lateFramesPerMode[mode] += record.missedVsyncs > 0;
        writer.addFrame(record);
        if (game->atCommitPoint()) writer.commit();

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
    if (game->finished()) writer.finish();
    else writer.commit();

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

}  // namespace warplab::app
