// What every game shares (DESIGN.md "Games plug in"): the input of one displayed frame, what
// that frame shows, and the three interfaces the runner, replay, `replay --render` and the
// bench's study paths use without naming a game:
//   Study  -- a parsed protocol bound to its game: makes games and bots;
//   Game   -- a deterministic state machine stepped once per displayed frame;
//   Player -- whoever produces the input: a bot, the simulated participant, a recorded session.
// A game is a module of its own (games/shooter/, games/click/) plus one line in
// games/src/games.cpp (or a registerGame call); nothing outside it names the game.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "condition/schedule.h"
#include "game/results.h"
#include "session/rows.h"
#include "protocol/questions.h"
#include "protocol/study_protocol.h"
#include "scene/scene.h"

namespace warplab::game {

inline constexpr std::uint32_t kButtonLeft = 1u;  // FrameInput::buttons
// FrameInput::keys. Enter: the supervisor begins the experiment (or the next match).
inline constexpr std::uint32_t kKeyEnter = 1u;
// Digits 1..9 answer a rating screen: bit kKeyDigit1 << (digit - 1).
inline constexpr std::uint32_t kKeyDigit1 = 1u << 1;
inline constexpr std::uint32_t digitKey(int digit) { return kKeyDigit1 << (digit - 1); }
// In FrameInput::text: the Backspace key, which takes back the last character typed.
inline constexpr char kTextBackspace = '\b';

struct FrameInput {
    double mouseDx = 0.0;  // mouse counts since the previous frame; +x right
    double mouseDy = 0.0;  // +y down
    std::uint32_t buttons = 0;
    std::uint32_t keys = 0;
    // What was typed since the previous frame, UTF-8, in order, each Backspace as
    // kTextBackspace: the answer to a text question (the window's text input; "" otherwise).
    // Braced, so that the many {dx, dy, buttons, keys} initialisers need not name it.
    std::string text{};
};

// The session's display, in pixels. Its aspect shapes the view, and the click game's cursor
// lives in its pixels, so replay needs it to reproduce what was under the pointer.
struct DisplaySize {
    int width = 1920, height = 1080;
    double aspect() const { return static_cast<double>(width) / height; }
};

enum class PointerKind : std::uint8_t { None, Reticle, Cursor };

// A question screen (after a match or a block, protocol/questions.h): one question, answered
// by a digit key or a click on its box (Likert, choice), or typed and ended with Enter (text).
struct QuestionPrompt {
    protocol::QuestionKind kind = protocol::QuestionKind::Likert;
    std::string prompt;
    int index = 0, count = 0;  // question `index` of `count`
    // Likert: the scale, and the labels under its two ends.
    int min = 1, max = 7;
    std::string minLabel = "strongly disagree", maxLabel = "strongly agree";
    // What each box says: its value (Likert), its option (choice, numbered from 1).
    std::vector<std::string> boxLabels;
    // One box per answer to click on: x, y, width, height in display pixels. A text question
    // has one, the field the answer is typed into.
    std::vector<glm::dvec4> boxes;
    int highlighted = -1;  // the box under the cursor, -1 for none
    std::string typed;  // text: the answer so far
    std::string hint;  // how to answer it, in the participant's words: what the keys and clicks do
};

// What one displayed frame shows, for the renderer, the HUD and a player looking at it.
struct ShownFrame {
    std::int64_t frame = 0;  // display frame since the session started
    double time = 0.0;  // its display time, seconds
    // The condition it is shown in (its name; "" for a screen shown between conditions) and its
    // parts: what the frame maker draws it with.
    condition::Condition condition;
    condition::ScheduledFrame schedule;  // the condition's account of this frame (schedule-local)
    scene::CameraState camera;  // the camera the frame depicts
    scene::SceneSnapshot scene;  // the world as the frame depicts it
    bool rendersNow = false;  // render `render` conventionally at this frame
    scene::FrameDescription render;  // ... the source of this and the following frames
    std::int64_t sourceFrame = 0;  // session frame whose render this frame is made from
    std::int64_t nextSourceFrame = -1;  // bidirectional: the later source
    bool frozen = false;  // a pause: the last frame stays on screen
    // The latest session frame whose input the picture shows: the frame whose camera or pointer
    // a scheduled frame depicts (cameraFrame), or the frame itself for what the game draws as it
    // responds (screens, the freeze frame after a shot). A press at frame p is on screen from
    // the first frame shown with inputFrame >= p: what a photodiode marker lights on.
    std::int64_t inputFrame = 0;
    bool blank = false;  // nothing of the scene is shown (e.g. a rating screen)

    // The pointer as this frame depicts it: the reticle at the centre, or the cursor drawn
    // into the frame, so it shares the condition's frame rate and lag. Display pixels, x right,
    // y down, continuous (pixel centres at +0.5).
    PointerKind pointer = PointerKind::Reticle;
    glm::dvec2 cursor{0.0};

    std::string banner;  // "HIT", "MISS", "TIMEOUT" ... ; "" = none
    bool bannerGood = false;  // green when true, red when false
    std::string phaseText;  // for the participant and supervisor
    std::string feedback;  // "hit", "miss" or "timeout" on the frame a shot or click is judged: a sound
    bool promptsEnter = false;  // waiting for Enter: the supervisor's, or the participant's after reading
    // A screen of instructions that opens a phase (the protocol's text): read, then Enter.
    std::string instructions;
    std::optional<QuestionPrompt> question;
};

// What the frame on screen shows under its pointer, worked out from the world model and the
// condition's timing -- the analytic side of `replay --render`'s cross-check against the id buffer.
struct PointerProbe {
    std::uint32_t objectId = scene::kIdNone;  // a game object's id, or kIdNone for none
    // Angle between the pointer's ray and the nearest silhouette it is judged against. Within
    // a pixel or two of one, the tessellated render and the exact sphere may honestly
    // disagree: the cross-check skips such frames (the renderer knows its pixel size).
    double silhouetteMarginRad = 0.0;
};

class Game {
public:
    virtual ~Game() = default;
    // Advances one displayed frame with that frame's input.
    virtual ShownFrame step(const FrameInput& input) = 0;
    virtual bool finished() const = 0;
    virtual std::string phase() const = 0;  // for progress lines
    // Events produced since the last call, in order.
    virtual std::vector<session::EventRecord> takeEvents() = 0;
    // True when the last step completed a trial, match or phase: the session store commits.
    virtual bool atCommitPoint() const = 0;
    // The session goes on here after an interruption (run --resume): called before the step of
    // the first frame played after it, by the resumed run and by every replay of its file
    // (resumedBefore), so that what a game resets for a participant who sat down again (the
    // shooter's view, from its format 7) is played the same each time.
    virtual void resumeHere() {}
    virtual session::FrameRecord frameRecord(const ShownFrame& shown) const = 0;
    // Events that are scored outcomes ("N/N outcomes reproduced").
    virtual bool isOutcome(const session::EventRecord& event) const = 0;
    virtual PointerProbe probePointer(const ShownFrame& shown) const = 0;
    // For a logged pointer event (a shot or click): the object its displayed outcome names
    // (kIdNone for empty space); nullopt for any other event.
    virtual std::optional<std::uint32_t> displayedObject(const session::EventRecord& event) const = 0;
    // Keys of this game's event details that say how frames were drawn, not what was played:
    // replay, which does not redo the rendering, leaves them out of its comparison, so that
    // the sessions that carry them still replay.
    virtual std::vector<std::string> renderDetailKeys() const { return {}; }
};

// Free play, for pilots and demonstrations: the game runs on without end, nothing counts, and
// the supervisor switches the condition (and, where the game has one, the difficulty) live. The
// runner records nothing of it.
class FreePlayGame : public Game {
public:
    // Starts over in the condition named `condition` at `difficulty` from the next frame (a new
    // target or a new field).
    virtual void switchTo(const std::string& condition, int difficulty) = 0;
};

class Study;

class Player {
public:
    virtual ~Player() = default;
    // The input of the first frame, before anything is on screen.
    virtual FrameInput first() { return {}; }
    // Given the frame now on screen, the input for the next frame.
    virtual FrameInput next(const ShownFrame& shown) = 0;
    // False once a recorded player has no more input: the session ends there.
    virtual bool hasMore() const { return true; }
    // What drew the frames this player looked at, "" for a player that sees none. Sessions
    // record it: such a player's inputs are reproducible on the same GL implementation.
    virtual std::string perceivedWith() const { return {}; }
    // A simulated player's own parameters as a JSON object, "" for others. Sessions record it.
    virtual std::string model() const { return {}; }
};

// Makes a player that sees (the perceptual simulated participant) from its seed. It draws
// what it sees, so it is made where GL is: the GL-free runner is handed one of these.
using SeeingPlayerMaker =
    std::function<std::unique_ptr<Player>(std::uint64_t seed, const Study& study, const DisplaySize& display)>;

// Plays back the input record of a stored session, frame by frame.
class RecordedPlayer final : public Player {
public:
    explicit RecordedPlayer(std::vector<session::InputRecord> records) : records_(std::move(records)) {}
    FrameInput first() override { return take(); }
    FrameInput next(const ShownFrame&) override { return take(); }
    bool hasMore() const override { return next_ <= records_.size(); }

private:
    FrameInput take() {
        if (next_ >= records_.size()) {
            ++next_;  // past the end: hasMore() turns false
            return {};
        }
        const auto& r = records_[next_++];
        return {r.mouseDx, r.mouseDy, r.buttons, r.keys, r.text};
    }
    std::vector<session::InputRecord> records_;
    std::size_t next_ = 0;
};

// What a participant is told before a study, and learns in its practice: what they point
// with, the view's geometry, how far the mouse moves the pointer, and which objects to go for.
// A simulated participant plays from this alone, never from the game's name or its protocol.
struct Instructions {
    enum class Targets : std::uint8_t {
        All,  // shoot the target
        GreenOnly,  // click the green spheres, never the red
    };
    PointerKind pointer = PointerKind::Reticle;
    double verticalFovDeg = 60.0;  // the view's geometry: turns a pixel offset into a turn
    double radiansPerCount = 0.0;  // reticle: how far one mouse count turns the view
    double pixelsPerCount = 1.0;  // cursor: how far one mouse count moves the cursor
    Targets targets = Targets::All;
    std::string task;  // the rule in words, as the participant hears it
};

// How far a session got, counted as a supervisor counts it: the shooter's test trials, the
// click game's matches.
struct Progress {
    std::string unit;  // plural noun: "test trials", "matches"
    std::size_t done = 0, planned = 0;  // planned 0: the protocol plans no number of them
};

// Whether the session of `header` went on after an interruption at display frame `frame` (its
// `resumed` list): a replay calls Game::resumeHere() before stepping that frame.
inline bool resumedBefore(const session::SessionHeader& header, std::int64_t frame) {
    for (const session::Resumption& r : header.resumed)
        if (r.frame == frame) return true;
    return false;
}

// The list of conditions a study plan counterbalances across participants (docs/study-plan.md).
struct CounterbalancedList {
    std::vector<std::string> conditions;  // in the protocol's order
    // The game plays them in the order given, so a plan's order is what each participant
    // plays; false: the session seed shuffles them (or their trials) anyway.
    bool blocked = false;
};

// A protocol file parsed and bound to its game.
class Study {
public:
    virtual ~Study() = default;
    virtual std::string game() const = 0;  // the protocol's "game"
    virtual std::string name() const = 0;  // the protocol's "name"
    virtual std::string protocolJson() const = 0;  // canonical copy, stored in the session
    virtual double refreshHz() const = 0;
    virtual std::unique_ptr<Game> newGame(std::uint64_t seed, const DisplaySize& display) const = 0;
    // The same game in free play (see FreePlayGame), starting in the condition named `condition`
    // at `difficulty`.
    virtual std::unique_ptr<FreePlayGame> newFreePlay(std::uint64_t seed, const DisplaySize& display,
                                                      const std::string& condition, int difficulty) const = 0;
    virtual std::unique_ptr<Player> newBot(std::uint64_t seed, const DisplaySize& display) const = 0;
    // The names of the conditions this protocol plays, in its order.
    virtual std::vector<std::string> conditionNames() const = 0;
    // Those of them the part the study analyses runs (the shooter's test, the click game's
    // matches), in the protocol's order; the others serve only practice or training.
    virtual std::vector<std::string> analysedConditions() const { return conditionNames(); }
    // The conditions it can name: the presets and those the protocol defines.
    virtual const condition::ConditionTable& conditions() const = 0;
    // How far one mouse count turns the camera, radians; 0 where the mouse does not turn it
    // (the click game's cursor). Live sessions scale a participant's counts to it.
    virtual double mouseRadiansPerCount() const { return 0.0; }
    virtual Instructions instructions() const = 0;
    // A live session on a display known to run at another refresh: warn (true) or refuse.
    virtual bool warnsOnRefreshMismatch() const = 0;
    // How the session's frames are rendered: the protocol's guard band and supersampling.
    virtual protocol::RenderSettings rendering() const = 0;
    // A stored session's events (of a session run with this protocol) as export's rows.
    // Events of other types are skipped; a session cut short gives what it has.
    virtual SessionResults results(const std::vector<session::EventRecord>& events) const = 0;
    // How far a session of this protocol with these events got, of what the protocol plans.
    virtual Progress progress(const std::vector<session::EventRecord>& events) const = 0;
    // What a study plan counterbalances in this protocol; nullopt: a game without such a list,
    // which a plan refuses.
    virtual std::optional<CounterbalancedList> counterbalanced() const { return std::nullopt; }
    // `protocolText` (this protocol as its file has it) with the counterbalanced list in
    // `order`, the rest as the file has it: the copy a participant's session runs. Called only
    // where counterbalanced() has a list.
    virtual std::string withConditionOrder(const std::string& protocolText,
                                           const std::vector<std::string>& order) const {
        (void)order;
        return protocolText;
    }
};

}  // namespace warplab::game
