// Private to app/: a perceptual simulated participant. It sees only what a person
// sees -- the displayed frames, made exactly as the session's mode makes them, at a reduced
// resolution, plus the pointer and the text drawn on screen -- and acts through the same input
// as a person: mouse counts and button and key presses, once per displayed frame. Its hit
// rates therefore depend on what each mode shows and when it shows it.
//
// Two halves, so that "it never reads the world" is a property of the types, not a promise:
//   Eye                  -- GL. The only code that reads a game::ShownFrame. It draws the
//                           frame with FrameMaker (as `replay --render` and live sessions do),
//                           reads colour and object ids back and keeps the objects it finds;
//                           of the ShownFrame itself it copies only what is on screen (see see()).
//   SimulatedParticipant -- no GL, no game state: act(Percept) -> FrameInput. A Percept holds
//                           pixels-derived objects, the drawn pointer and the screen's text.
// PerceptualPlayer joins them as a game::Player for the runner ("--player sim[:SEED]").
//
// Deterministic: the same seed and the same percepts give the same inputs. Percepts come from
// a GL rasteriser, so a session is reproducible on the same GL implementation; the input log
// is recorded as for any player, so replay reproduces a session's outcomes anywhere.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "app/frame_maker.h"
#include "game/game.h"
#include "game/random.h"
#include "renderer/context.h"
#include "renderer/image.h"

namespace warplab::app {

// ---------------------------------------------------------------------------------------------
// Perception

// One object as the displayed image shows it. The id image is the frame's segmentation into
// objects -- what a person sees as one thing -- so identity across frames is the id; where it
// is and how big and what colour come from its pixels only.
struct SeenObject {
    std::uint32_t id = 0;
    glm::dvec2 centre{0.0};  // centroid of its pixels, display pixels (x right, y down, centres at +0.5)
    double radiusPx = 0.0;   // radius of the disc with its area, display pixels
    glm::dvec3 colour{0.0};  // mean displayed colour, 0..1
    int pixels = 0;          // percept pixels it covers
    bool greenish() const { return colour.g > colour.r; }
};

// The game objects (ids from scene::kIdTarget up; hangar and sky are background) in a displayed
// frame read back at the percept resolution, by id. `toDisplay`: display pixels per image pixel
// in x and y. Image rows are top-down (renderer/image.h).
std::vector<SeenObject> findObjects(const renderer::ImageU32& ids, const renderer::ImageRGBA8& colour,
                                    glm::dvec2 toDisplay);

// The displayed image's scene -- without the objects in it, which move on their own -- as a
// grey picture of block means: blurred, enough to recognise a view seen before and how far it
// has turned, or sharp, to tell how far it turned since the last frame.
struct Thumbnail {
    int width = 0, height = 0;
    std::vector<float> luma;         // 0..1, rows top-down; NaN where objects cover the cell
    glm::dvec2 cellPx{1.0};          // display pixels per cell in x and y
    float at(int x, int y) const { return luma[static_cast<std::size_t>(y) * width + x]; }
};
// Block means of the luminance over `block` x `block` pixels, leaving out game objects' pixels.
Thumbnail thumbnailOf(const renderer::ImageRGBA8& colour, const renderer::ImageU32& ids, int block,
                      glm::dvec2 toDisplay);
// The shift, in cells, that best lines `before` up with `now` (content at c in `before` is at
// c + shift in `now`): least mean squared difference over the cells of the central
// `centreShare` of `now` that overlap `before`, searched within `radius` of `guess`, refined
// below a cell by a parabola through the best cost and its neighbours. Shifts whose overlap
// covers less than `minOverlapShare` of that central part do not count; nullopt if none does.
std::optional<glm::dvec2> bestShift(const Thumbnail& before, const Thumbnail& now, glm::ivec2 guess, glm::ivec2 radius,
                                    double centreShare, double minOverlapShare);
// Where the centre of the view `before` lies in the view `now`, in display pixels from the
// centre of `now`, over the blurred pictures: shifts up to half the picture each way.
std::optional<glm::dvec2> whereViewIs(const Thumbnail& before, const Thumbnail& now);

// Everything the participant gets of one displayed frame.
struct Percept {
    double time = 0.0;                 // when the frame was on screen (the display clock)
    bool sceneShown = true;            // false: a screen without the scene (ready, rating, done)
    std::vector<SeenObject> objects;   // found in the displayed image
    Thumbnail picture;                 // the scene, blurred (4 x 4 pixel cells)
    Thumbnail detail;                  // the scene, sharp (one cell per percept pixel)
    // The pointer drawn into the frame: the reticle at the centre, or the cursor where this
    // frame draws it (so it has the mode's frame rate and lag). Display pixels.
    game::PointerKind pointer = game::PointerKind::None;
    glm::dvec2 pointerAt{0.0};
    // Text on screen.
    std::string phaseText;
    std::string banner;                // "HIT", "MISS", "TIMEOUT" or ""
    bool promptsEnter = false;         // "Press Enter to begin"
    std::optional<game::RatingPrompt> rating;
};

// How far the scene moved on screen from the frame `before` to the frame `now`, display pixels,
// searched around `guessPx` (coarse over the blurred pictures, then sharp): a turn of the view,
// seen in the pictures.
std::optional<glm::dvec2> howFarViewMoved(const Percept& before, const Percept& now, glm::dvec2 guessPx = {});

// ---------------------------------------------------------------------------------------------
// What the participant knows before it starts: the instructions and what practice teaches
// (how far the mouse moves the view or the cursor, the view's geometry). Never the world.
struct TaskKnowledge {
    game::DisplaySize display;
    double refreshHz = 60.0;          // only for the length of the very first frame
    double verticalFovDeg = 60.0;     // the view's geometry: turns a pixel offset into a turn
    double radiansPerCount = 0.0;     // reticle: how far one mouse count turns the view
    double pixelsPerCount = 1.0;      // cursor: how far one mouse count moves the cursor
    bool greenOnly = false;           // the click game's instruction: click green, never red
};

// The instructions for the study's game; throws std::invalid_argument for a game it has none for.
TaskKnowledge taskKnowledge(const game::Study& study, const game::DisplaySize& display);

// The participant's parameters. Defaults are published human values where the literature gives
// one (cited from memory by author, year and venue: the papers could not be consulted while
// writing this), and otherwise model choices, said as such.
struct ParticipantParams {
    // Visual reaction time: the participant acts on the frame that was on screen this long
    // ago. Simple visual reaction times are about 180-220 ms (Luce 1986, "Response Times",
    // Oxford University Press; Welford 1980, "Reaction Times", Academic Press).
    double reactionS = 0.2;
    // Smooth-pursuit gain: the share of the target's estimated velocity the hand follows.
    // Human smooth pursuit has a gain of about 0.9 for targets up to a few tens of degrees per
    // second, falling above (Lisberger, Morris & Tychsen 1987, Annu. Rev. Neurosci. 10:97-129;
    // Meyer, Lasker & Robinson 1985, Vision Res. 25:561-563). Used here for the hand that the
    // eye leads.
    double pursuitGain = 0.9;
    // Position correction, per second: the share of the predicted aiming error closed per
    // second (a first-order approach, time constant 1/8 s: 90 % of a turn in ~0.3 s, the order
    // of aimed-movement times, Fitts 1954, J. Exp. Psychol. 47:381-391). Model choice.
    double correctionPerS = 8.0;
    // Motion is estimated by a least-squares fit to the target's positions seen over this
    // window (speed judgements improve with viewing time over the first few hundred ms: De Bruyn
    // & Orban 1988, Vision Res. 28:1323-1335). Model choice within that range.
    double motionWindowS = 0.2;
    // The fit is a parabola -- a constant acceleration, which lets it anticipate falling things
    // as people do (an internal model of gravity: McIntyre, Zago, Berthoz & Lacquaniti 2001,
    // Nat. Neurosci. 4:693-694) -- once the positions span half the window; a line before.
    bool perceivesAcceleration = true;
    // A seen change of place faster than this, in degrees of view per second, is a jump, not
    // motion (a new target where the last one was, or the view misjudged). Model choice: five
    // times the upper limit of smooth pursuit below, far above any target's speed.
    double maxSeenSpeedDegPerS = 500.0;
    // ... of gravity-like size: an acceleration judged larger (a bounce inside the window, a
    // jerky low-rate picture) is taken as this much. Model choice: gravity seen from the
    // click game's camera is about 70 deg/s^2.
    double maxAccelerationDegPerS2 = 100.0;
    // Signal-dependent motor noise: the hand's velocity carries noise whose standard deviation
    // grows in proportion to the commanded speed (Harris & Wolpert 1998, Nature 394:780-784;
    // execution noise: van Beers, Haggard & Wolpert 2004, J. Neurophysiol. 91:1050-1063).
    // Standard deviation per unit of commanded speed: with the correlation below, a fast
    // movement ends off by a few per cent of its length, the order of the end-point scatter of
    // quick aimed movements. The value is a model choice, not a figure from those papers.
    double motorNoise = 0.05;
    // A small constant part (tremor and the like), mouse counts per second. Model choice.
    double motorNoiseFloorCountsPerS = 5.0;
    // The noise is smooth, not white: correlated over about a submovement, so its effect does
    // not depend on the display's frame rate. Model choice.
    double motorNoiseCorrelationS = 0.1;
    // Click rule: press when the aiming error predicted for the next frame and the error seen in
    // the frame acted on are both below this share of the target's seen radius, having followed
    // the target at least minAimS. Model choice (a speed-accuracy trade-off).
    double clickWithin = 0.7;
    double minAimS = 0.1;
    // A clicked object is not aimed at again until it has been seen gone, or this long.
    double forgetClickedS = 1.0;
    // Reticle games: with nothing to aim at, the participant turns back to the view it started
    // with (where targets appear), recognised in the picture, when it is further off than this.
    double homeWithinDeg = 5.0;
    // Smooth pursuit saturates: at most this fast, in degrees of the view per second (Meyer,
    // Lasker & Robinson 1985 measured an upper limit near 100 deg/s).
    double maxPursuitDegPerS = 100.0;
    // Cursor games: the participant knows where its cursor is from its hand (efference copy),
    // and corrects that belief towards where it sees the cursor -- in the frame it acts on,
    // against where its hand was when that frame was shown -- with this time constant. Model
    // choice: slower than the loop's delay (reaction time plus a 200 ms lag), so that a lagging
    // cursor misleads it without making it oscillate without end.
    double recalibrationS = 0.3;
    double enterAfterS = 0.5;         // the supervisor presses Enter this long after the prompt
    double answerAfterS = 1.0;        // reading a rating statement before answering it
    // Percept resolution: width in pixels (height keeps the display's aspect). 160 x 90 puts
    // ~0.67 degrees in a pixel at 60 degrees of view; centroids of a target a few pixels wide
    // are still sub-pixel. A speed trade-off (llvmpipe draws such frames in milliseconds), not
    // human acuity.
    int perceptWidth = 160;
};

// ---------------------------------------------------------------------------------------------
// The control law's parts, in the hand's units: radians of turn (x: yaw right, y: pitch up)
// for a reticle, display pixels (x right, y down) for a cursor.

// Where a seen point is relative to the pointer, in hand units.
glm::dvec2 offsetFromPointer(const TaskKnowledge& knowledge, game::PointerKind pointer, glm::dvec2 pointerAt,
                             glm::dvec2 point);
// A seen radius in display pixels, in hand units.
double sizeInHandUnits(const TaskKnowledge& knowledge, game::PointerKind pointer, double radiusPx);

struct Sample {
    double time = 0.0;
    glm::dvec2 position{0.0};
};
struct MotionEstimate {
    double time = 0.0;               // the last sample's
    glm::dvec2 position{0.0};        // on the fitted curve at `time`
    glm::dvec2 velocity{0.0};        // 0 from a single sample
    glm::dvec2 acceleration{0.0};    // 0 from a line
    glm::dvec2 positionAt(double t) const {
        const double d = t - time;
        return position + velocity * d + 0.5 * acceleration * d * d;
    }
    glm::dvec2 velocityAt(double t) const { return velocity + acceleration * (t - time); }
};
// The least-squares fit to time-ordered samples (at least one): a parabola when `acceleration`
// and the samples span at least `minSpanForAcceleration` seconds with four or more of them,
// else a line (two or more), else the one position at rest.
MotionEstimate estimateMotion(const std::vector<Sample>& samples, bool acceleration = false,
                              double minSpanForAcceleration = 0.1);

// The hand's velocity command: follow the target's velocity predicted for `now` with the
// pursuit gain and close the error to where the target is predicted to be at correctionPerS.
glm::dvec2 pursuitVelocity(const MotionEstimate& target, double now, glm::dvec2 hand, const ParticipantParams& params);

// The click rule: the pointer is predicted on the target at the next frame, and was seen on it
// in the frame it acts on (a person confirms by eye before pressing), both within clickWithin
// of its radius, after aiming at it at least minAimS.
bool decidesToClick(glm::dvec2 predictedError, glm::dvec2 seenError, double targetRadius, double aimedForS,
                    const ParticipantParams& params);

// ---------------------------------------------------------------------------------------------
// The participant: percepts in, input out. No GL and no game state.
class SimulatedParticipant {
public:
    SimulatedParticipant(const TaskKnowledge& knowledge, const ParticipantParams& params, std::uint64_t seed);
    // The input for the next frame, given the frame on screen now. Once per displayed frame,
    // in order.
    game::FrameInput act(const Percept& percept);

    // Where it believes it points, in the units of the world as it sees it (see remember()).
    glm::dvec2 pointerBelief() const { return aim_; }

private:
    struct Thing {
        std::uint32_t id;
        glm::dvec2 where;   // in the world as it knows it: see remember()
        glm::dvec2 offset;  // from the pointer, as the frame shows it
        double radius;      // hand units
        bool green;
    };
    struct Sighting {
        double time;
        bool valid;        // shows a scene in play (no banner, not a screen)
        std::vector<Thing> things;
        Thumbnail picture;
        glm::dvec2 hand;   // where the hand was as it was shown
        glm::dvec2 view;   // reticle: the view's direction the frame shows, as seen (see remember())
        game::PointerKind pointer;
        glm::dvec2 pointerAt;
    };
    struct Moment {        // one frame of a match, for rating it afterwards
        glm::dvec2 pointerAt, hand;
        bool changed;      // the image differed from the frame before
    };
    game::FrameInput play(const Percept& percept, double dt);
    game::FrameInput rate(const Percept& percept);
    void move(game::FrameInput& input, glm::dvec2 velocity, double dt, bool pursuing);
    void remember(const Percept& percept);
    glm::dvec2 homeward(const Sighting& view, glm::dvec2 aim, double now);  // hand velocity back to the start view
    double handUnitsPerRadian() const;
    int ratingFor(const std::string& statement, int min, int max);
    void judgeMatch();

    TaskKnowledge knowledge_;
    ParticipantParams params_;
    game::Random random_;
    glm::dvec2 unitsPerCount_;   // hand units per count in x and y, signed as the game reads them
    glm::dvec2 hand_{0.0};       // where it has commanded its hand to be (efference copy)
    glm::dvec2 calibration_{0.0};  // cursor: where it sees the cursor, less where its hand says
    glm::dvec2 carry_{0.0};      // counts commanded but not yet sent (mice send whole counts)
    glm::dvec2 noise_{0.0};      // the motor noise's current velocity, hand units per second
    double lastTime_ = -1.0;
    std::deque<Sighting> sightings_;
    std::optional<std::uint32_t> target_;
    double aimingSince_ = 0.0;
    std::map<std::uint32_t, double> clicked_;
    std::optional<Thumbnail> home_;  // the view it started with ...
    glm::dvec2 homeHand_{0.0};       // ... and where its hand was then
    // Reticle: the direction of the view as the frames show it, followed by how far the scene
    // has moved in the picture since a key frame.
    glm::dvec2 view_{0.0};
    std::optional<Percept> key_;   // the frame the view is measured against ...
    glm::dvec2 keyView_{0.0};      // ... the view it showed ...
    glm::dvec2 keyShift_{0.0};     // ... and how far the scene has moved since, display pixels
    glm::dvec2 previousHand_{0.0};
    glm::dvec2 aim_{0.0};  // where it believes it points now, in the units of Thing::where
    double lastHomeLook_ = -1.0;
    std::optional<glm::dvec2> homeSeen_;  // the start view, last recognised (units of Thing::where)
    bool buttonDown_ = false;
    std::uint32_t keysDown_ = 0;
    double promptSince_ = -1.0;
    bool enterPressed_ = false;  // for the prompt on screen
    // Rating: what the last match felt like.
    std::vector<Moment> match_;
    std::vector<SeenObject> previousObjects_;
    double smoothness_ = 4.0, responsiveness_ = 4.0;
    bool judged_ = true;
    int statement_ = -1;
    double statementSince_ = 0.0;
};

// ---------------------------------------------------------------------------------------------
// The eye: GL. Makes each displayed frame as the mode makes it, at the percept resolution.
// What it reads of a ShownFrame, all of it: (1) whatever FrameMaker reads to draw the frame --
// the same drawing a participant's window shows; (2) what the HUD draws over it: the pointer
// (reticle or cursor position), banner, phase text, Enter prompt, rating screen, and whether
// the scene is shown at all (`blank`); (3) its display time; (4) to skip drawing an image that
// is already on screen, whether the frame is frozen or a held copy of the source last drawn
// (`frozen`, `schedule.kind`, `sourceFrame`): the same pixels either way. Never the scene's
// objects, the camera, the mode or the outcome for itself.
class Eye {
public:
    // Needs a current GL context. `rendering`: the protocol's (study.rendering()).
    Eye(const renderer::DataPaths& paths, const game::DisplaySize& display, const protocol::RenderSettings& rendering,
        int perceptWidth);
    // Call for every frame the game steps, in order.
    Percept see(const game::ShownFrame& shown);
    int width() const { return width_; }
    int height() const { return height_; }

private:
    game::DisplaySize display_;
    int width_, height_;
    FrameMaker maker_;
    renderer::DisplayFrame frame_;
    std::vector<SeenObject> lastObjects_;
    Thumbnail lastPicture_, lastDetail_;
    bool haveImage_ = false;            // an image of the scene is on screen (no screen since)
    std::int64_t lastMadeSource_ = -1;  // the source it copies (rendered or held), else -1
};

// A game::Player that sees with an Eye and acts as a SimulatedParticipant.
class PerceptualPlayer final : public game::Player {
public:
    // `context`: the GL context the eye draws with, owned for the player's lifetime; null to use
    // the one current on this thread (tests).
    PerceptualPlayer(std::unique_ptr<renderer::GlContext> context, const game::Study& study,
                     const game::DisplaySize& display, const renderer::DataPaths& paths, std::uint64_t seed,
                     const ParticipantParams& params = {});
    game::FrameInput next(const game::ShownFrame& shown) override;
    // The GL implementation the percepts come from (sessions record it: percepts, and so the
    // inputs, are reproducible on the same one).
    std::string glDescription() const;

private:
    std::unique_ptr<renderer::GlContext> context_;  // first: destroyed after the GL objects below
    std::unique_ptr<Eye> eye_;
    SimulatedParticipant participant_;
};

}  // namespace warplab::app
