// A perceptual simulated participant. It sees only what a person
// sees -- the displayed frames, made exactly as the session's condition makes them, at a reduced
// resolution, plus the pointer and the text drawn on screen -- and acts through the same input
// as a person: mouse counts and button and key presses, once per displayed frame. Its hit
// rates therefore depend on what each condition shows and when it shows it.
//
// Two halves, so that "it never reads the world" is a property of the types, not a promise:
//   Eye                  -- GL (participants/eye.h, library warplab_participants_eye). The
//                           only code that reads a game::ShownFrame. It draws the
//                           frame with FrameMaker (as `replay --render` and live sessions do),
//                           reads colour and object ids back and keeps the objects it finds;
//                           of the ShownFrame itself it copies only what is on screen (see see()).
//   SimulatedParticipant -- no GL, no game state (this header and participants/perception.h,
//                           library warplab_participants): act(Percept) -> FrameInput. A Percept holds
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

#include "game/game.h"
#include "game/random.h"
#include "participants/perception.h"

namespace warplab::participants {

// ---------------------------------------------------------------------------------------------
// What the participant knows before it starts: the instructions and what practice teaches
// (how far the mouse moves the view or the cursor, the view's geometry). Never the world.
struct TaskKnowledge {
    game::DisplaySize display;
    double refreshHz = 60.0;  // only for the length of the very first frame
    double verticalFovDeg = 60.0;  // the view's geometry: turns a pixel offset into a turn
    double radiansPerCount = 0.0;  // reticle: how far one mouse count turns the view
    double pixelsPerCount = 1.0;  // cursor: how far one mouse count moves the cursor
    bool greenOnly = false;  // the click game's instruction: click green, never red
};

// What the study tells its participants (Study::instructions), as the participant uses it.
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
    // The longer it has aimed at one target, the less sure it waits to be: the criterion grows
    // by this share of itself per second of aiming (an urgency signal: Cisek, Puskas & El-Murr
    // 2009, J. Neurosci. 29:11560-11571). People in the thesis's study rarely let the 3 s pass
    // (1.6 % timeouts, seed 004 §6). Model choice.
    double urgencyPerS = 0.5;
    // The click game: with no green sphere in sight for this long, it clicks a red one away to
    // make room (the field holds a fixed number of spheres and only a click frees a place).
    // Model choice; Yang et al.'s people hit 1.9 to 6.7 red spheres per 45 s match.
    double clearRedAfterS = 1.0;
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
    // The display's delay, as the participant sees it -- how late the pointer on screen follows
    // its hand -- is bridged by its internal model by this share: it extrapolates the targets
    // and its own pointer that much further. People adapt to a constant visual feedback delay
    // within minutes, in part (Cunningham, Billock & Tsou 2001, Psychol. Sci. 12:532-535;
    // Smith 1972 on delayed sensory feedback); how fully is a trait of the population.
    double delayAdaptation = 0.0;
    // The delay is judged over the last `delayWindowS` of play and followed with this time
    // constant. Model choices.
    double delayWindowS = 1.0;
    double delayFollowS = 0.5;
    // Rating: the felt value (1..7) is stretched about the scale's middle by ratingScale,
    // shifted by ratingBias and blurred by Gaussian noise of ratingNoise (each answer its own),
    // then rounded. People differ in how much of a scale they use and where they sit on it
    // (response styles: Baumgartner & Steenkamp 2001, J. Marketing Res. 38:143-156).
    double ratingScale = 1.0;
    double ratingBias = 0.0;
    double ratingNoise = 0.0;
    // Two-interval task (games/discrimination): asked which interval was the more responsive,
    // it compares the delays it judged between its hand and the picture in each, each blurred by
    // Gaussian noise of this standard deviation in ms (one draw per interval and question). The
    // noise is the judgement's limit: the 75 %-correct threshold of a two-interval task
    // (Phi(delta / (sqrt(2) sigma)) = 0.75) is then about 0.95 sigma, plus what the delay fit
    // itself misjudges. Additive in ms, not a share of the delay: people moving a virtual object
    // by hand told latency changes of under 33 ms, probably under 16.7 ms, apart in a forced
    // choice whatever the base latency (27, 94 or 194 ms) -- Ellis, Young, Adelstein & Ehrlich
    // 1999, Proc. Human Factors and Ergonomics Society 43 (cited from memory). The value is a
    // model choice within that.
    double delayJudgementNoiseMs = 15.0;
    // ... and asked which was the smoother, the rates at which the picture changed, each blurred
    // by Gaussian noise of this standard deviation on a natural-log scale (0.15: a 75 % threshold
    // near a sixth of the rate). Model choice: a ratio of rates, as Weber's law has it for most
    // magnitudes, at a size not fitted to any study.
    double smoothnessJudgementNoise = 0.15;
    double enterAfterS = 0.5;  // the supervisor presses Enter this long after the prompt
    double answerAfterS = 1.0;  // reading a rating statement before answering it
    // Percept resolution: width in pixels (height keeps the display's aspect). 128 x 72 puts
    // ~0.83 degrees in a pixel at 60 degrees of view; centroids of a target a few pixels wide
    // are still sub-pixel. A speed trade-off, not human acuity: llvmpipe's cost of a percept is
    // mostly per pixel, and 160 x 90 made `warplab demo` 1.3 times slower for figures within
    // the noise of these (docs/simulated-participant.md, "Speed").
    int perceptWidth = 128;
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
    double time = 0.0;  // the last sample's
    glm::dvec2 position{0.0};  // on the fitted curve at `time`
    glm::dvec2 velocity{0.0};  // 0 from a single sample
    glm::dvec2 acceleration{0.0};  // 0 from a line
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
class IntervalJudge;  // judgement.h: the two intervals of a discrimination trial

class SimulatedParticipant {
public:
    SimulatedParticipant(const TaskKnowledge& knowledge, const ParticipantParams& params, std::uint64_t seed);
    ~SimulatedParticipant();
    SimulatedParticipant(SimulatedParticipant&&) noexcept;
    SimulatedParticipant& operator=(SimulatedParticipant&&) noexcept;
    // The input for the next frame, given the frame on screen now. Once per displayed frame,
    // in order.
    game::FrameInput act(const Percept& percept);

    // Where it believes it points, in the units of the world as it sees it (see remember()).
    glm::dvec2 pointerBelief() const { return aim_; }
    // How late, in seconds, it sees the pointer on screen follow its hand (0 until judged).
    double seenDelay() const { return seenDelay_; }

private:
    struct Thing {
        std::uint32_t id;
        glm::dvec2 where;  // in the world as it knows it: see remember()
        glm::dvec2 offset;  // from the pointer, as the frame shows it
        double radius;  // hand units
        bool green;
    };
    struct Sighting {
        double time;
        double onset;  // when this image first appeared (a held image shows what it showed then)
        bool valid;  // shows a scene in play (no banner, not a screen)
        std::vector<Thing> things;
        Thumbnail picture;
        glm::dvec2 view;  // reticle: the view's direction the frame shows, as seen (see remember())
        game::PointerKind pointer;
        glm::dvec2 pointerAt;
    };
    struct Moment {  // one frame of a match, for rating it afterwards
        glm::dvec2 pointerAt, hand;
        bool changed;  // the image differed from the frame before
    };
    game::FrameInput play(const Percept& percept, double dt);
    // play's steps, in the order it takes them: what it sees (the sighting it acts on, or none
    // yet), which object it goes for, and the hand's pursuit of it and the click.
    const Sighting* perceive(const Percept& percept, double dt);
    void chooseTarget(const Sighting& view, glm::dvec2 pointer, double now);
    void pursue(game::FrameInput& input, const Sighting& view, glm::dvec2 pointer, double now, double dt);
    static const Thing* sees(const Sighting& s, std::uint32_t id);  // the object as `s` shows it, if it does
    game::FrameInput rate(const Percept& percept);
    void move(game::FrameInput& input, glm::dvec2 velocity, double dt, bool pursuing);
    void remember(const Percept& percept);
    glm::dvec2 homeward(const Sighting& view, glm::dvec2 aim, double now);  // hand velocity back to the start view
    glm::dvec2 handAt(double time) const;  // where the hand was, from its log
    void judgeDelay(double now);  // updates seenDelay_ from the pointer log
    double bridged() const { return params_.delayAdaptation * seenDelay_; }
    double handUnitsPerRadian() const;
    int ratingFor(const std::string& statement, int min, int max);
    int choiceFor(const game::QuestionPrompt& question);
    void judgeMatch();

    TaskKnowledge knowledge_;
    ParticipantParams params_;
    game::Random random_;
    game::Random ratingRandom_;  // its own stream: answering a question moves no hand
    std::unique_ptr<IntervalJudge> intervals_;  // with its own stream, for the same reason
    glm::dvec2 unitsPerCount_;  // hand units per count in x and y, signed as the game reads them
    glm::dvec2 hand_{0.0};  // where it has commanded its hand to be (efference copy)
    glm::dvec2 calibration_{0.0};  // cursor: where it sees the cursor, less where its hand says
    glm::dvec2 carry_{0.0};  // counts commanded but not yet sent (mice send whole counts)
    glm::dvec2 noise_{0.0};  // the motor noise's current velocity, hand units per second
    double lastTime_ = -1.0;
    std::deque<Sighting> sightings_;
    // The hand's log (time shown, hand) and the pointer seen at each new image (its onset,
    // the cursor or the view as seen), for judging the display's delay.
    std::deque<std::pair<double, glm::dvec2>> handLog_;
    std::deque<std::pair<double, glm::dvec2>> pointerLog_;
    double seenDelay_ = 0.0;  // s: how late the pointer on screen follows the hand
    double lastDelayJudged_ = -1.0;
    std::optional<Percept> lastPercept_;  // to tell a new image from a held one
    double onset_ = 0.0;
    std::optional<std::uint32_t> target_;
    double aimingSince_ = 0.0;
    double lastGreenSeen_ = 0.0;
    std::map<std::uint32_t, double> clicked_;
    std::optional<Thumbnail> home_;  // the view it started with ...
    glm::dvec2 homeHand_{0.0};  // ... and where its hand was then
    // Reticle: the direction of the view as the frames show it, followed by how far the scene
    // has moved in the picture since a key frame.
    glm::dvec2 view_{0.0};
    std::optional<Percept> key_;  // the frame the view is measured against ...
    glm::dvec2 keyView_{0.0};  // ... the view it showed ...
    glm::dvec2 keyShift_{0.0};  // ... and how far the scene has moved since, display pixels
    glm::dvec2 previousHand_{0.0};
    glm::dvec2 aim_{0.0};  // where it believes it points now, in the units of Thing::where
    double lastHomeLook_ = -1.0;
    std::optional<glm::dvec2> homeSeen_;  // the start view, last recognised (units of Thing::where)
    bool buttonDown_ = false;
    std::uint32_t keysDown_ = 0;
    double promptSince_ = -1.0;
    std::string promptText_;  // the prompt's phase text, to tell one prompt from the next
    bool enterPressed_ = false;  // for the prompt on screen
    // Rating: what the last match felt like.
    std::vector<Moment> match_;
    std::vector<SeenObject> previousObjects_;
    double smoothness_ = 4.0, responsiveness_ = 4.0;
    bool judged_ = true;
    int statement_ = -1;
    std::optional<int> answer_;  // to the question on screen, once decided
    double statementSince_ = 0.0;
    bool typed_ = false;  // a text answer has been typed and waits for Enter
};

}  // namespace warplab::participants
