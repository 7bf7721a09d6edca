#include "participants/participant.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "judgement.h"
#include "scene/scene.h"

namespace warplab::participants {
namespace {

constexpr double kMaxPitch = 1.5;  // the shooter's camera never pitches further (radians)

double focalPixels(const TaskKnowledge& knowledge) {
    return 0.5 * knowledge.display.height / std::tan(glm::radians(knowledge.verticalFovDeg) * 0.5);
}

}  // namespace

TaskKnowledge taskKnowledge(const game::Study& study, const game::DisplaySize& display) {
    const game::Instructions told = study.instructions();
    TaskKnowledge k;
    k.display = display;
    k.refreshHz = study.refreshHz();
    k.verticalFovDeg = told.verticalFovDeg;
    k.radiansPerCount = told.pointer == game::PointerKind::Reticle ? told.radiansPerCount : 0.0;
    k.pixelsPerCount = told.pixelsPerCount;
    k.greenOnly = told.targets == game::Instructions::Targets::GreenOnly;
    return k;
}

// ---------------------------------------------------------------------------------------------
// The control law's parts

glm::dvec2 offsetFromPointer(const TaskKnowledge& knowledge, game::PointerKind pointer, glm::dvec2 pointerAt,
                             glm::dvec2 point) {
    if (pointer != game::PointerKind::Reticle) return point - pointerAt;
    // The turn that brings the point under the reticle: its direction in the view, as yaw
    // (right) and pitch (up) offsets. Exact for a level view; near enough otherwise, and the
    // loop closes on what it sees next.
    const double f = focalPixels(knowledge);
    const double dx = (point.x - pointerAt.x) / f, dy = -(point.y - pointerAt.y) / f;
    return {std::atan(dx), std::atan2(dy, std::sqrt(1.0 + dx * dx))};
}

double sizeInHandUnits(const TaskKnowledge& knowledge, game::PointerKind pointer, double radiusPx) {
    if (pointer != game::PointerKind::Reticle) return radiusPx;
    return std::atan(radiusPx / focalPixels(knowledge));
}

MotionEstimate estimateMotion(const std::vector<Sample>& samples, bool acceleration, double minSpanForAcceleration) {
    if (samples.empty()) throw std::invalid_argument("estimateMotion: needs at least one sample");
    MotionEstimate e;
    e.time = samples.back().time;
    e.position = samples.back().position;
    const double span = samples.back().time - samples.front().time;
    if (samples.size() < 2 || span <= 1e-9) return e;
    // Least squares in time relative to the last sample: p(s) = c0 + c1 s (+ c2 s^2).
    const bool parabola = acceleration && samples.size() >= 4 && span >= minSpanForAcceleration;
    const int n = parabola ? 3 : 2;
    double m[3][3] = {};
    glm::dvec2 r[3] = {glm::dvec2(0.0), glm::dvec2(0.0), glm::dvec2(0.0)};
    for (const auto& sample : samples) {
        const double t = sample.time - e.time;
        const double powers[3] = {1.0, t, t * t};
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) m[i][j] += powers[i] * powers[j];
            r[i] += powers[i] * sample.position;
        }
    }
    // Gaussian elimination (the matrix is symmetric positive definite for distinct times).
    for (int k = 0; k < n; ++k)
        for (int i = k + 1; i < n; ++i) {
            const double f = m[i][k] / m[k][k];
            for (int j = k; j < n; ++j) m[i][j] -= f * m[k][j];
            r[i] -= f * r[k];
        }
    glm::dvec2 c[3] = {glm::dvec2(0.0), glm::dvec2(0.0), glm::dvec2(0.0)};
    for (int i = n - 1; i >= 0; --i) {
        glm::dvec2 sum = r[i];
        for (int j = i + 1; j < n; ++j) sum -= m[i][j] * c[j];
        c[i] = sum / m[i][i];
    }
    e.position = c[0];
    e.velocity = c[1];
    if (parabola) e.acceleration = 2.0 * c[2];
    return e;
}

glm::dvec2 pursuitVelocity(const MotionEstimate& target, double now, glm::dvec2 hand, const ParticipantParams& params) {
    // Where the target is now, predicted from what was seen a reaction time ago (the delay
    // bridged by an internal model; cf. Miall, Weir, Wolpert & Stein 1993, J. Motor Behav.
    // 25:203-216), and where the hand is now (efference copy; Wolpert, Ghahramani & Jordan
    // 1995, Science 269:1880-1882).
    return params.pursuitGain * target.velocityAt(now) + params.correctionPerS * (target.positionAt(now) - hand);
}

bool decidesToClick(glm::dvec2 predictedError, glm::dvec2 seenError, double targetRadius, double aimedForS,
                    const ParticipantParams& params) {
    const double within = params.clickWithin * (1.0 + params.urgencyPerS * std::max(0.0, aimedForS)) * targetRadius;
    return aimedForS >= params.minAimS && glm::length(predictedError) < within && glm::length(seenError) < within;
}

// ---------------------------------------------------------------------------------------------
// The participant

SimulatedParticipant::SimulatedParticipant(const TaskKnowledge& knowledge, const ParticipantParams& params,
                                           std::uint64_t seed)
    : knowledge_(knowledge),
      params_(params),
      random_(game::mix(seed ^ 0x5133A1E7ULL)),
      ratingRandom_(game::mix(seed ^ 0x7A71A6E5ULL)),
      intervals_(std::make_unique<IntervalJudge>(game::mix(seed ^ 0x1D7E2A15ULL), params.delayJudgementNoiseMs,
                                                 params.smoothnessJudgementNoise)) {
    if (knowledge.radiansPerCount > 0.0) {
        // Mouse right turns right (+yaw); mouse down (+y) pitches down.
        unitsPerCount_ = {knowledge.radiansPerCount, -knowledge.radiansPerCount};
    } else {
        unitsPerCount_ = {knowledge.pixelsPerCount, knowledge.pixelsPerCount};
        hand_ = {knowledge.display.width * 0.5, knowledge.display.height * 0.5};
    }
}

SimulatedParticipant::~SimulatedParticipant() = default;
SimulatedParticipant::SimulatedParticipant(SimulatedParticipant&&) noexcept = default;
SimulatedParticipant& SimulatedParticipant::operator=(SimulatedParticipant&&) noexcept = default;

void SimulatedParticipant::move(game::FrameInput& input, glm::dvec2 velocity, double dt, bool pursuing) {
    if (!pursuing) {
        velocity = glm::dvec2(0.0);
        noise_ = glm::dvec2(0.0);  // a hand at rest on the mouse
    } else {
        // Signal-dependent noise, smooth in time (an Ornstein-Uhlenbeck process whose spread
        // follows the commanded speed), so the frame rate does not change how much there is.
        const double a = std::exp(-dt / params_.motorNoiseCorrelationS);
        const double spread =
            params_.motorNoise * glm::length(velocity) + params_.motorNoiseFloorCountsPerS * std::abs(unitsPerCount_.x);
        const glm::dvec2 kick(random_.gaussian(), random_.gaussian());
        noise_ = a * noise_ + std::sqrt(1.0 - a * a) * spread * kick;
    }
    const glm::dvec2 intended = velocity * dt;
    hand_ += intended;
    if (knowledge_.radiansPerCount > 0.0) {
        hand_.y = std::clamp(hand_.y, -kMaxPitch, kMaxPitch);
    } else {
        // The cursor stops at the display's edges, and the participant knows it.
        const glm::dvec2 edge(knowledge_.display.width, knowledge_.display.height);
        hand_ = glm::clamp(hand_ + calibration_, glm::dvec2(0.0), edge) - calibration_;
    }
    // Mice send whole counts; what is left over goes with the next frame.
    const glm::dvec2 counts = (intended + noise_ * dt) / unitsPerCount_ + carry_;
    const glm::dvec2 sent = glm::round(counts);
    carry_ = counts - sent;
    input.mouseDx = sent.x;
    input.mouseDy = sent.y;
}

namespace {

// The same image as the frame before: the same objects in the same places over the same
// picture, to the bit (a held frame is drawn once and perceived once by the eye).
bool sameImage(const Percept& a, const Percept& b) {
    if (a.sceneShown != b.sceneShown || a.objects.size() != b.objects.size() || a.pointerAt != b.pointerAt ||
        a.detail.luma.size() != b.detail.luma.size())
        return false;
    for (std::size_t i = 0; i < a.objects.size(); ++i)
        if (a.objects[i].id != b.objects[i].id || a.objects[i].centre != b.objects[i].centre) return false;
    return a.detail.luma.empty() ||
        std::memcmp(a.detail.luma.data(), b.detail.luma.data(), a.detail.luma.size() * sizeof(float)) == 0;
}

}  // namespace

glm::dvec2 SimulatedParticipant::handAt(double time) const {
    return handLog_.empty() ? hand_ : positionAt(handLog_, time);
}

void SimulatedParticipant::judgeDelay(double now) {
    // How late the pointer on screen follows the hand (fitDelay), judged a few times a second
    // over the last delayWindowS of play, a frame's precision, and followed slowly.
    if (now - lastDelayJudged_ < 0.1 || pointerLog_.size() < 4) return;
    const double dt = now - std::max(lastDelayJudged_, now - 1.0);
    lastDelayJudged_ = now;
    const std::optional<double> best = fitDelay(pointerLog_, handLog_, 1.0 / knowledge_.refreshHz);
    if (!best) return;
    seenDelay_ += (*best - seenDelay_) * (1.0 - std::exp(-dt / params_.delayFollowS));
}

void SimulatedParticipant::remember(const Percept& percept) {
    // A held image shows what it showed when it appeared: it is seen then, not now.
    if (!lastPercept_ || !sameImage(*lastPercept_, percept)) onset_ = percept.time;
    const bool newImage = onset_ == percept.time;
    lastPercept_ = percept;
    handLog_.emplace_back(percept.time, hand_);
    while (handLog_.size() > 2 && handLog_[1].first < percept.time - 2.0) handLog_.pop_front();
    // Where the hand was as each frame was shown is in handLog_.
    Sighting s{percept.time,    onset_,           percept.sceneShown && percept.banner.empty(), {}, {}, {},
               percept.pointer, percept.pointerAt};
    const bool reticle = percept.pointer == game::PointerKind::Reticle;
    if (reticle) {
        s.picture = percept.picture;
        if (!home_ && s.valid) {  // the view it starts with, and where its hand was then
            home_ = percept.picture;
            homeHand_ = hand_;
        }
        // The view turns as the scene moves in the picture: a frame held on screen is a view
        // that stands still, whatever the hand does meanwhile. Where the pictures cannot be
        // lined up (a new scene), the hand's own turn stands in.
        // Against a key frame rather than frame by frame, so that small errors do not add up;
        // a new key frame once the view has turned a tenth of the picture away from it.
        const double f = focalPixels(knowledge_);
        const auto toTurn = [&](glm::dvec2 shift) {
            return glm::dvec2(std::atan(-shift.x / f), std::atan(shift.y / f));
        };
        std::optional<glm::dvec2> moved;
        // Searched around where the hand's turn since the last frame would put it.
        const glm::dvec2 turn = hand_ - previousHand_;
        const glm::dvec2 guess = keyShift_ + glm::dvec2(-f * std::tan(turn.x), f * std::tan(turn.y));
        if (key_ && percept.sceneShown) moved = howFarViewMoved(*key_, percept, guess);
        if (moved) {
            view_ = keyView_ + toTurn(*moved);
            keyShift_ = *moved;
        } else {
            view_ = key_ ? view_ + (hand_ - previousHand_) : hand_;
        }
        const double far = 0.1 * knowledge_.display.width;
        if (!moved || std::abs(keyShift_.x) > far || std::abs(keyShift_.y) > far) {
            key_ = percept;
            keyView_ = view_;
            keyShift_ = glm::dvec2(0.0);
        }
        s.view = view_;
        previousHand_ = hand_;
    }
    for (const SeenObject& o : percept.objects) {
        const glm::dvec2 offset = offsetFromPointer(knowledge_, percept.pointer, percept.pointerAt, o.centre);
        // Where it is in the world as the participant sees it. A turning view: the view's
        // direction as seen plus the turn that would bring it under the reticle. A fixed view
        // with a cursor: where it is on the screen, which does not move.
        const glm::dvec2 where = reticle ? view_ + offset : o.centre;
        s.things.push_back(
            {o.id, where, offset, sizeInHandUnits(knowledge_, percept.pointer, o.radiusPx), o.greenish()});
    }
    // The pointer as each new image shows it: the cursor where it is drawn, the view as seen.
    std::optional<glm::dvec2> pointerSeen;
    if (s.valid && newImage && s.pointer != game::PointerKind::None) {
        pointerSeen = reticle ? s.view : s.pointerAt;
        pointerLog_.emplace_back(percept.time, *pointerSeen);
        while (!pointerLog_.empty() && pointerLog_.front().first < percept.time - params_.delayWindowS)
            pointerLog_.pop_front();
    }
    intervals_->see(percept.time, newImage, pointerSeen);
    judgeDelay(percept.time);
    sightings_.push_back(std::move(s));
    const double keepFrom = percept.time - params_.reactionS - params_.motionWindowS - 0.05;
    while (sightings_.size() > 1 && sightings_[1].time <= keepFrom) sightings_.pop_front();
}

game::FrameInput SimulatedParticipant::play(const Percept& percept, double dt) {
    game::FrameInput input;
    const double now = percept.time;
    const Sighting* view = perceive(percept, dt);
    judged_ = false;
    statement_ = -1;

    if (view == nullptr) {
        move(input, {}, dt, false);
        return input;
    }
    // Where it points now: with a reticle, the view the frame it acts on showed, turned on by
    // what the hand has done since (efference copy); with a cursor, its hand, corrected by what
    // it has seen of the cursor.
    // The image it acts on appeared at its onset and showed the view as it was a seen delay
    // before that, as far as the internal model bridges it.
    const glm::dvec2 pointer = view->pointer == game::PointerKind::Reticle
        ? view->view + (hand_ - handAt(view->onset - bridged()))
        : hand_ + calibration_;
    aim_ = pointer;
    chooseTarget(*view, pointer, now);
    if (!target_) {
        const glm::dvec2 home = homeward(*view, pointer, now);
        move(input, home, dt, home != glm::dvec2(0.0));
        return input;
    }
    homeSeen_.reset();
    pursue(input, *view, pointer, now, dt);
    return input;
}

const SimulatedParticipant::Sighting* SimulatedParticipant::perceive(const Percept& percept, double dt) {
    // What it has seen of the frames shown so far (in hand coordinates, from the hand as it was
    // when each was on screen), and the one it acts on: a reaction time old.
    remember(percept);
    const double now = percept.time;
    const Sighting* view = nullptr;
    for (const auto& s : sightings_)
        if (s.time <= now - params_.reactionS + 1e-9) view = &s;

    // What the match feels like, for the ratings after it.
    bool changed = percept.objects.size() != previousObjects_.size();
    for (std::size_t i = 0; !changed && i < percept.objects.size(); ++i)
        changed = percept.objects[i].id != previousObjects_[i].id ||
            glm::length(percept.objects[i].centre - previousObjects_[i].centre) > 1e-3;
    previousObjects_ = percept.objects;
    if (percept.pointer == game::PointerKind::Cursor) match_.push_back({percept.pointerAt, hand_, changed});
    // Where the cursor is, it knows from its hand and corrects by what it sees: the cursor in the
    // frame it acts on against where its hand was when that frame drew it -- the image's onset
    // less the display's delay as judged -- slowly. (Against where the hand was at the onset, a
    // lagging cursor would drag the belief back along every movement, and the hand would swing.)
    if (view != nullptr && view->valid && view->pointer == game::PointerKind::Cursor) {
        const double rate = 1.0 - std::exp(-dt / params_.recalibrationS);
        calibration_ += rate * ((view->pointerAt - handAt(view->onset - seenDelay_)) - calibration_);
    }
    return view;
}

const SimulatedParticipant::Thing* SimulatedParticipant::sees(const Sighting& s, std::uint32_t id) {
    if (!s.valid) return nullptr;
    for (const auto& t : s.things)
        if (t.id == id) return &t;
    return nullptr;
}

void SimulatedParticipant::chooseTarget(const Sighting& view, glm::dvec2 pointer, double now) {
    // A clicked object is left alone until it has been seen gone (or for a while).
    for (auto it = clicked_.begin(); it != clicked_.end();) {
        const bool gone = view.time > it->second && sees(view, it->first) == nullptr;
        it = gone || now - it->second > params_.forgetClickedS ? clicked_.erase(it) : std::next(it);
    }
    if (target_ && (sees(view, *target_) == nullptr || clicked_.count(*target_))) target_.reset();
    // Where only red is left, the field fills up with it (a clicked sphere is what makes room
    // for a new one): after a while without a green one in sight, a red one is cleared away.
    bool greenInSight = false;
    for (const auto& t : view.things) greenInSight = greenInSight || (t.green && !clicked_.count(t.id));
    if (greenInSight || !view.valid) lastGreenSeen_ = now;
    const bool clearRed = knowledge_.greenOnly && now - lastGreenSeen_ > params_.clearRedAfterS;
    if (target_ || !view.valid) return;
    // The easiest one: the nearest, counting how far each moves while the participant reacts
    // and the display lags, as it sees that lag -- where the display is late, a sphere
    // resting on the floor is an easier choice than a falling one, and people choose so.
    // It chooses once it has watched the field a tenth of a second: how each one moves is
    // part of the choice.
    const Sighting* before = nullptr;  // an image about a tenth of a second older
    for (const auto& s : sightings_)
        if (s.valid && s.time <= view.time - 0.1 + 1e-9) before = &s;
    const double lead = params_.reactionS + seenDelay_;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : before != nullptr ? view.things : std::vector<Thing>{}) {
        if ((knowledge_.greenOnly && !t.green && !clearRed) || clicked_.count(t.id)) continue;
        double d = glm::length(t.where - pointer);
        if (const Thing* then = sees(*before, t.id))
            d += glm::length(t.where - then->where) / (view.time - before->time) * lead;
        if (d < best) {
            best = d;
            target_ = t.id;
            aimingSince_ = now;
        }
    }
}

void SimulatedParticipant::pursue(game::FrameInput& input, const Sighting& view, glm::dvec2 pointer, double now,
                                  double dt) {
    const glm::dvec2 handBefore = hand_;
    std::vector<Sample> samples;
    const double maxSeenSpeed = handUnitsPerRadian() * glm::radians(params_.maxSeenSpeedDegPerS);
    for (const auto& s : sightings_) {
        if (s.time > view.time) break;
        if (s.onset < view.onset - params_.motionWindowS - 1e-9) continue;
        // A frame held on screen shows nothing new: motion is judged from the changes seen. A
        // change faster than any target moves is a jump, not motion -- a new target, or the
        // view misjudged (the hall repeats itself) -- and the motion is judged afresh from it.
        const Thing* t = sees(s, *target_);
        if (!t || (!samples.empty() && samples.back().position == t->where)) continue;
        if (!samples.empty() &&
            glm::length(t->where - samples.back().position) > maxSeenSpeed * (s.onset - samples.back().time))
            samples.clear();
        samples.push_back({s.onset, t->where});
    }
    MotionEstimate seen = estimateMotion(samples, params_.perceivesAcceleration, 0.5 * params_.motionWindowS);
    const double maxAcceleration = handUnitsPerRadian() * glm::radians(params_.maxAccelerationDegPerS2);
    if (glm::length(seen.acceleration) > maxAcceleration)
        seen.acceleration *= maxAcceleration / glm::length(seen.acceleration);
    // Extrapolated across its reaction time and the share of the display's delay it bridges.
    const double ahead = now + bridged();
    glm::dvec2 velocity = pursuitVelocity(seen, ahead, pointer, params_);
    // Pursuit saturates (Meyer, Lasker & Robinson 1985): the part that follows the target's
    // motion is no faster than maxPursuitDegPerS.
    const glm::dvec2 follow = params_.pursuitGain * seen.velocityAt(ahead);
    const double maxSpeed = handUnitsPerRadian() * glm::radians(params_.maxPursuitDegPerS);
    if (glm::length(follow) > maxSpeed) velocity -= follow * (1.0 - maxSpeed / glm::length(follow));
    move(input, velocity, dt, true);
    // The press counts at the next frame, with the hand where it has just been sent.
    const glm::dvec2 predicted = seen.positionAt(ahead + dt);
    const Thing& inView = *sees(view, *target_);
    aim_ = pointer + (hand_ - handBefore);
    // A discrimination interval asks it to track the target, and nothing is shot.
    if (intervals_->inInterval()) return;
    if (decidesToClick(predicted - aim_, inView.offset, inView.radius, now - aimingSince_, params_)) {
        input.buttons = game::kButtonLeft;
        clicked_[*target_] = now;
        target_.reset();
    }
}

double SimulatedParticipant::handUnitsPerRadian() const {
    return knowledge_.radiansPerCount > 0.0 ? 1.0 : focalPixels(knowledge_);
}

glm::dvec2 SimulatedParticipant::homeward(const Sighting& view, glm::dvec2 aim, double now) {
    if (!home_ || !view.valid || view.pointer != game::PointerKind::Reticle) return glm::dvec2(0.0);
    // Looks for the start view in the picture a few times a second, not every frame.
    if (!homeSeen_ || now - lastHomeLook_ >= 0.1) {
        lastHomeLook_ = now;
        const auto shift = whereViewIs(*home_, view.picture);
        if (!shift) {
            // Too far off to recognise it: back by how far the hand has turned since (the view
            // turns with the hand, but for the pitch the game stops at its limit).
            homeSeen_.reset();
            const glm::dvec2 back = homeHand_ - hand_;
            return glm::length(back) <= glm::radians(params_.homeWithinDeg) ? glm::dvec2(0.0)
                                                                            : params_.correctionPerS * back;
        }
        homeSeen_ = view.view + offsetFromPointer(knowledge_, view.pointer, view.pointerAt, view.pointerAt + *shift);
    }
    const glm::dvec2 off = *homeSeen_ - aim;
    if (glm::length(off) <= glm::radians(params_.homeWithinDeg)) return glm::dvec2(0.0);
    return params_.correctionPerS * off;
}

void SimulatedParticipant::judgeMatch() {
    judged_ = true;
    if (match_.size() < 3) return;
    const double dt = 1.0 / knowledge_.refreshHz;
    // Smooth: how often the picture changed (a new image per display frame at best).
    int changes = 0;
    for (const auto& m : match_) changes += m.changed;
    const double imagesPerS = changes / (match_.size() * dt);
    smoothness_ = 1.0 + 6.0 * std::min(1.0, imagesPerS / 60.0);
    // Responsive: how late the cursor on screen follows the hand -- the delay that best lines
    // up the cursor's movements with the hand's (over a quarter-second baseline, so that the
    // slow drift between where the hand thinks it is and where it is does not count).
    const auto n = static_cast<std::int64_t>(match_.size());
    const std::int64_t baseline = std::max<std::int64_t>(1, std::llround(0.25 / dt));
    const std::int64_t maxLag = std::llround(0.5 / dt);
    double bestError = std::numeric_limits<double>::infinity();
    std::int64_t bestLag = 0;
    for (std::int64_t lag = 0; lag <= maxLag && lag + baseline < n; ++lag) {
        double error = 0.0;
        for (std::int64_t j = lag + baseline; j < n; ++j) {
            const glm::dvec2 shown = match_[j].pointerAt - match_[j - baseline].pointerAt;
            const glm::dvec2 moved = match_[j - lag].hand - match_[j - lag - baseline].hand;
            const glm::dvec2 d = shown - moved;
            error += glm::dot(d, d);
        }
        error /= static_cast<double>(n - lag - baseline);
        if (error < bestError - 1e-9) {
            bestError = error;
            bestLag = lag;
        }
    }
    responsiveness_ = std::clamp(7.0 - bestLag * dt * 1000.0 / 25.0, 1.0, 7.0);
    match_.clear();
}

int SimulatedParticipant::ratingFor(const std::string& statement, int min, int max) {
    std::string text = statement;
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const double enjoyed = (smoothness_ + responsiveness_) / 2.0;
    double value = 4.0;  // on 1..7; neither agree nor disagree with what it has no feeling about
    if (text.find("enjoy") != std::string::npos)
        value = enjoyed;
    else if (text.find("difficult") != std::string::npos)
        value = 8.0 - enjoyed;
    else if (text.find("responsive") != std::string::npos)
        value = responsiveness_;
    else if (text.find("smooth") != std::string::npos)
        value = smoothness_;
    // This participant's use of the scale, and the noise of one answer.
    value =
        4.0 + params_.ratingScale * (value - 4.0) + params_.ratingBias + params_.ratingNoise * ratingRandom_.gaussian();
    return std::clamp(static_cast<int>(std::lround(min + (value - 1.0) / 6.0 * (max - min))), min, max);
}

int SimulatedParticipant::choiceFor(const game::QuestionPrompt& question) {
    // Which of two intervals was the more responsive (or smoother): the one it judged so.
    if (question.boxes.size() == 2)
        if (const std::optional<int> interval = intervals_->answer(question.prompt)) return *interval;
    // A choice it has no feeling about: the options in turn.
    return 1 + question.index % std::max(1, static_cast<int>(question.boxes.size()));
}

game::FrameInput SimulatedParticipant::rate(const Percept& percept) {
    game::FrameInput input;
    if (!judged_) judgeMatch();
    const game::QuestionPrompt& r = *percept.question;
    if (r.index != statement_) {
        statement_ = r.index;
        statementSince_ = percept.time;
        answer_.reset();
    }
    if (percept.time - statementSince_ < params_.answerAfterS) {
        typed_ = false;
        return input;
    }
    // A text question it has no feeling about: a few words typed and sent.
    if (r.kind == protocol::QuestionKind::Text) {
        if (!typed_)
            input.text = "no comment";
        else
            input.keys = game::kKeyEnter;
        typed_ = true;
        return input;
    }
    const int value = answer_
        ? *answer_
        : (r.kind == protocol::QuestionKind::Choice ? choiceFor(r) : ratingFor(r.prompt, r.min, r.max));
    answer_ = value;  // decided once per question (its noise drawn once)
    if (value >= 1 && value <= 9) {
        input.keys = game::digitKey(value);
        return input;
    }
    // No digit key for it: click its box (the cursor is live on the rating screen).
    const auto box =
        r.boxes.at(static_cast<std::size_t>(r.kind == protocol::QuestionKind::Choice ? value - 1 : value - r.min));
    const glm::dvec2 centre(box.x + box.z * 0.5, box.y + box.w * 0.5);
    calibration_ = percept.pointerAt - hand_;  // the cursor is live here: seen where it is
    move(input, params_.correctionPerS * (centre - percept.pointerAt), 1.0 / knowledge_.refreshHz, true);
    const glm::dvec2 off = glm::abs(percept.pointerAt - centre);
    if (off.x < box.z * 0.3 && off.y < box.w * 0.3) input.buttons = game::kButtonLeft;
    return input;
}

game::FrameInput SimulatedParticipant::act(const Percept& percept) {
    const double dt =
        lastTime_ < 0.0 || percept.time <= lastTime_ ? 1.0 / knowledge_.refreshHz : percept.time - lastTime_;
    lastTime_ = percept.time;
    // Which interval of a discrimination trial is on screen, if any (a question closes it).
    intervals_->follow(percept.question ? std::string() : percept.phaseText, percept.time, hand_);
    game::FrameInput input;
    if (percept.question) {
        input = rate(percept);
    } else if (percept.sceneShown) {
        input = play(percept, dt);
    } else {
        // A screen between matches: nothing to aim at; where a cursor shows live, the hand
        // sees where it is.
        if (percept.pointer == game::PointerKind::Cursor) calibration_ = percept.pointerAt - hand_;
        sightings_.clear();
        pointerLog_.clear();
        target_.reset();
        move(input, {}, dt, false);
    }
    // The supervisor's Enter, once per prompt.
    if (percept.promptsEnter) {
        // Another prompt straight after one (the supervisor's Enter, then instructions) is
        // told by its text.
        if (promptSince_ < 0.0 || percept.phaseText != promptText_) {
            promptSince_ = percept.time;
            enterPressed_ = false;
        }
        promptText_ = percept.phaseText;
        if (percept.time - promptSince_ >= params_.enterAfterS && !enterPressed_) {
            input.keys |= game::kKeyEnter;
            enterPressed_ = true;
        }
    } else {
        promptSince_ = -1.0;
        enterPressed_ = false;
    }
    // Presses last one frame: the games count the press, not the hold.
    if (buttonDown_) input.buttons = 0;
    buttonDown_ = input.buttons != 0;
    input.keys &= ~keysDown_;
    keysDown_ = input.keys;
    return input;
}

}  // namespace warplab::participants
