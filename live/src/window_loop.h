// The one window loop of live sessions and free play: the display clock (vsync, or a timer at
// the protocol's rate), the participant's input (or a player's), making each frame as its condition
// makes it with the HUD over it, presenting it, feedback sounds, screenshots, scripted input
// and the supervisor's pause. What differs -- a session store and its commits, or free play's
// live switching and status line -- is a LoopPolicy's.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "game/game.h"
#include "input_script.h"
#include "live/live_session.h"
#include "photon_marker.h"
#include "present/frame_maker.h"
#include "renderer/hud.h"
#include "renderer/timing.h"
#include "renderer/window.h"
#include "sound.h"

namespace warplab::live {

// What the window's input means to the game (Enter, digits, the left button, typed text) and
// to the supervisor (Esc, and every key for the pause screen and free play). While a session
// runs only Esc is the supervisor's: the pause screen reads keys only after it, and a session
// reads no other key, so a participant typing an answer cannot reach a supervisor's action.
struct Polled {
    game::FrameInput input;
    bool escape = false, closed = false;
    bool closeAsked = false, focusLost = false;  // as renderer::WindowInput's
    std::string keys;
};
// Mouse counts scaled to the protocol's (and y inverted when asked for).
Polled readInput(const renderer::WindowInput& in, double countScale, bool invertY);

// One present per vsync, or per timer tick where vsync cannot keep the protocol's rate. A
// frame that reaches the screen late says how many display frames it missed; the loop steps
// the game past them, so that the session's display clock keeps up with the wall clock.
class DisplayClock {
public:
    DisplayClock(renderer::Window& window, double refreshHz, bool byVsync);

    struct Presented {
        double frameS;  // since the previous present
        int missedVsyncs;  // a frame that took n periods to reach the screen missed n - 1
    };
    Presented present();
    // Before the first frame and after a pause: the next frame is not late.
    void restart();

private:
    using Clock = std::chrono::steady_clock;
    renderer::Window& window_;
    double period_;
    bool byVsync_;
    Clock::time_point last_, deadline_;
    bool first_ = true;
};

// How one display frame reached the screen, or that it never did.
struct FrameTiming {
    double frameMs = 0.0;  // present to present
    double renderMs = 0.0;  // making it (render, warp or blend, HUD) to glFinish
    int missedVsyncs = 0;
    // The frame before took this frame's display slot: the game stepped through it (its
    // input is the held buttons and keys; what moved the mouse meanwhile goes to the next
    // frame shown), its renders were made, and nothing of it was shown.
    bool skipped = false;
    // The photodiode marker turned white on this frame, answering the press at photonPress.
    bool photonMarker = false;
    std::int64_t photonPress = -1;
};

// What makes the loop a recorded session or free play.
class LoopPolicy {
public:
    virtual ~LoopPolicy() = default;
    virtual game::Game& game() = 0;
    // The pause screen's line: what Enter and Q do.
    virtual std::string pauseText() const = 0;
    // The line of the screen that asks whether to end, when the window manager asked the
    // window to close (its close button, alt+F4).
    virtual std::string closeText() const {
        return "Enter: keep playing, Q: end it \xE2\x80\x94 everything recorded so far is kept";
    }
    // The keys polled for display frame `frame`, before the game steps with `input`; a policy
    // may act on them and change what the game is given.
    virtual void beforeStep(const std::string& keys, std::int64_t frame, game::FrameInput& input) = 0;
    // The game stepped with `input` and shows `shown`.
    virtual void stepped(const game::ShownFrame& shown, const game::FrameInput& input) = 0;
    // The HUD over display frame `frame`: `hud` holds the game's; the policy may change its status line.
    virtual void decorate(const game::ShownFrame& shown, std::int64_t frame, renderer::HudContent& hud) = 0;
    // The frame is on screen, or was skipped (timing.skipped).
    virtual void presented(const game::ShownFrame& shown, const FrameTiming& timing) = 0;
    // The PNG's name (without .png) of a screenshot of display frame `frame`.
    virtual std::string screenshotName(std::int64_t frame) const = 0;
};

class WindowLoop {
public:
    // Loads the protocol, reads the input script, opens the window and decides its display
    // clock: vsync at the protocol's refresh, else a timer at it; a known refresh that
    // differs refuses (throws) unless the run or the protocol allows it.
    WindowLoop(const LiveRun& run, const renderer::DataPaths& paths, std::ostream& progress);
    ~WindowLoop();
    WindowLoop(const WindowLoop&) = delete;
    WindowLoop& operator=(const WindowLoop&) = delete;

    const game::Study& study() const { return *study_; }
    const game::DisplaySize& display() const { return display_; }
    const renderer::GlInfo& glInfo() const { return window_.info(); }
    // The refresh the frames are shown at: the display's under vsync, else the timer's.
    double shownRefreshHz() const;
    // Whether the participant plays (not a bot or a recorded session).
    bool human() const { return player_ == nullptr; }
    // Where the photodiode marker is drawn (LiveRun::photonMarker, else the protocol's), or off.
    protocol::PhotonMarker photonMarker() const { return photonCorner_; }

    // Relative mouse mode while the participant plays; off on screens, at the end, for bots.
    void captureMouse(bool on);
    // A screen of the supervisor's flow (not part of the session): a dark backdrop and text.
    void showScreen(const std::string& banner, const std::string& status);
    // Shows a screen until one of `keys` is pressed; 0 when the window closed. `pending`:
    // keys already read with the one that opened the screen (a fast typist, a script).
    // `rest`, where given, receives the keys read after the one returned, for the next wait.
    char waitFor(const std::string& banner, const std::string& status, const std::string& keys,
                 const std::string& pending = "", std::string* rest = nullptr);
    // The sound check of the start screen: every feedback sound in turn, said on `progress`.
    void playSoundCheck(std::ostream& progress);
    // The window's last frame as PNG in the run's screenshot folder.
    void screenshot(const std::string& name);
    // Reads and drops what the window received: keeps it responsive while nothing is shown.
    void drainInput() { window_.pollInput(); }
    // Queues the input script's actions for `when` ("start", "end" or a frame number).
    void inject(const std::string& when);

    // A resumed session: the game was stepped through the kept frames, and `shown` was one of
    // them, in order. The player (a bot) and the frame maker learn what was on screen, and
    // run() goes on from the frame after the last.
    void sawBeforeResume(const game::ShownFrame& shown);

    struct End {
        bool aborted = false;  // the window closed or the supervisor ended it
        std::int64_t lastFrame = -1;  // the game's last shown frame
    };
    // Shows frames of the policy's game, one per display frame, until it finishes, a
    // recorded player runs out, or the supervisor ends it. Display frames a late frame took
    // are stepped in the game too and not shown (FrameTiming::skipped).
    End run(LoopPolicy& policy);

private:
    // What stops the frames for the supervisor: Esc, the window manager's close, or the window
    // leaving the participant (focus lost, minimised, hidden) while a human plays.
    enum class Stop { None, Escape, Close, Away };
    Stop stopFor(const Polled& polled) const;
    // The supervisor's pause: the display clock stops and a screen says why; true when Enter
    // resumes, false when Q (or a second close) ends the session. `keys`: those polled with it.
    bool pause(const std::string& keys, Stop stop, std::int64_t frame, const LoopPolicy& policy);
    FrameTiming show(const game::ShownFrame& shown, std::int64_t frame, LoopPolicy& policy,
                     const PhotonMarkerTiming::Answer& marker);

    // The window with what the display clock is decided from.
    struct Opened {
        std::unique_ptr<renderer::WindowContext> window;
        game::DisplaySize display;
        bool byVsync = false;
        double measuredHz = 0.0;
    };
    static Opened open(const LiveRun& run, const game::Study& study, std::ostream& progress);

    // In construction order: what draws needs the window's context, made current by open().
    const LiveRun& run_;
    std::ostream& progress_;
    std::unique_ptr<game::Study> study_;
    InputScript script_;
    Opened opened_;
    renderer::WindowContext& window_;
    const game::DisplaySize display_;
    const double countScale_;  // the participant's mouse counts as the protocol's
    std::unique_ptr<game::Player> player_;
    present::FrameMaker maker_;
    renderer::HudRenderer hud_;
    renderer::DisplayFrame screen_;
    FeedbackSounds sounds_;
    DisplayClock clock_;
    renderer::PassTimer timer_;
    // The photodiode marker: its corner or off, how the HUD draws it (none when off) and which
    // frames light it.
    const protocol::PhotonMarker photonCorner_;
    std::optional<renderer::HudPhotonMarker> photonMarker_;
    PhotonMarkerTiming photonTiming_;
    // What sawBeforeResume learnt: where run() starts, the player's next input, and the last
    // few frames that rendered a source (those the first frames after it may be made from).
    std::int64_t firstFrame_ = 0;
    bool playerStarted_ = false;
    game::FrameInput resumedInput_;
    std::deque<game::ShownFrame> keptSources_;
    bool quit_ = false;  // the last screen closed for a quit (a signal), not the window manager's close
};

}  // namespace warplab::live
