#include "click_game.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "game/random.h"
#include "game/screen.h"
#include "physics/ray.h"
#include "scene/hangar_layout.h"

namespace warplab::game {
namespace {

const glm::vec3 kRed{0.85f, 0.15f, 0.12f};
const glm::vec3 kGreen{0.15f, 0.75f, 0.2f};

// Seed tags: each purpose draws from its own stream, so adding one never shifts another.
constexpr int kTagMatchOrder = 40;
constexpr int kTagWorld = 41;

// Trajectories in the frame log are for plotting, not replay (replay re-simulates): a tenth
// of a millimetre keeps the rows short.
double rounded(double v) { return std::round(v * 1e4) / 1e4; }

scene::ObjectState objectFor(const physics::Sphere& s, double radius) {
    scene::ObjectState o;
    o.id = ClickGame::objectId(s);
    o.shape = scene::Shape::Sphere;
    o.position = glm::vec3(s.position);
    o.velocity = glm::vec3(s.velocity);
    o.halfExtents = glm::vec3(static_cast<float>(radius));
    o.colour = s.green ? kGreen : kRed;
    return o;
}

physics::FallingSphereSettings physicsFrom(const protocol::ClickProtocol& p) {
    physics::FallingSphereSettings s;
    s.gravity = p.gravity;
    s.radius = p.sphereRadius;
    s.restitution = p.restitution;
    s.stepRateHz = p.stepRateHz;
    s.sphereCount = p.sphereCount;
    s.greenShare = p.greenShare;
    s.spawnDelayS = p.spawnDelayS;
    s.spawnSpeed = p.spawnSpeedMPerS;
    return s;
}

}  // namespace

ClickHit firstSphereAlong(const glm::dvec3& eye, const glm::dvec3& dir, const std::vector<physics::Sphere>& spheres,
                          double radius) {
    ClickHit hit;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& s : spheres) {
        const auto t = physics::raySphereHit(eye, dir, s.position, radius);
        if (t && *t < nearest) {
            nearest = *t;
            hit.sphere = s;
        }
    }
    return hit;
}

std::uint32_t ClickGame::objectId(const physics::Sphere& sphere) { return scene::kIdFirstSphere + sphere.id; }

ClickGame::ClickGame(const protocol::ClickProtocol& protocol, std::uint64_t seed, const DisplaySize& display)
    : protocol_(protocol),
      seed_(seed),
      display_(display),
      physics_(physicsFrom(protocol)),
      clickGate_(protocol.clickTiming == protocol::ClickTiming::InputReads),
      questions_(protocol.questions, protocol.refreshHz, display,
                 /*legacyLayout=*/protocol.formatVersion < protocol::kClickQuestionsSince) {
    using L = scene::HangarLayout;
    camera_.eye = {L::kEyeX, L::kEyeY, L::kEyeZ};
    camera_.verticalFovDeg = static_cast<float>(protocol.verticalFovDeg);
    camera_.pitch = static_cast<float>(glm::radians(protocol.cameraPitchDeg));
    const std::optional<std::int64_t> steps = condition::wholeRatio(protocol.stepRateHz, protocol.refreshHz);
    if (!steps)
        throw std::invalid_argument("ClickGame: physics.step_rate_hz must be a whole multiple of the display refresh");
    stepsPerFrame_ = *steps;
    cursor_ = {display.width * 0.5, display.height * 0.5};
    physics::FallingSpheres(physics_, seed);  // throws now, naming the field, if the settings cannot work
    for (std::size_t r = 0; r < protocol.rounds.size(); ++r) {
        std::vector<std::string> order;
        for (const auto& condition : protocol.conditions)
            for (int i = 0; i < protocol.rounds[r].matchesPerCondition; ++i) order.push_back(condition);
        if (protocol.shuffle) shuffle(order, subSeed(seed, kTagMatchOrder, static_cast<int>(r)));
        for (std::size_t i = 0; i < order.size(); ++i)
            matches_.push_back({static_cast<int>(matches_.size()), static_cast<int>(r), order[i], static_cast<int>(i),
                                static_cast<int>(order.size())});
    }
}

void ClickGame::switchTo(const std::string& condition, int) {
    condition::ConditionSchedule(protocol_.conditionTable.at(condition),
                                 protocol_.refreshHz);  // throws for a condition this display cannot run
    freePlay_ = true;
    matches_ = {{0, 0, condition, 0, 1}};
    matchIndex_ = 0;
    beginMatch();  // from the next frame, with a fresh field
    takeEvents();  // free play records nothing
}

std::string ClickGame::phase() const {
    switch (phase_) {
        case Phase::Ready: return "ready";
        case Phase::Instructions: return "instructions";
        case Phase::Match: return "match";
        case Phase::Questions: return "questions";
        case Phase::Done: return "done";
    }
    return "?";
}

std::vector<session::EventRecord> ClickGame::takeEvents() { return events_.take(); }

void ClickGame::emit(session::EventRecord event) {
    event.frame = frame_;
    event.eventTime = now();
    if (event.phase.empty()) event.phase = phase();
    events_.push(std::move(event));
}

session::EventRecord ClickGame::matchEvent(const char* type, nlohmann::json detail) const {
    const Match& m = matches_[matchIndex_];
    const auto& round = protocol_.rounds[static_cast<std::size_t>(m.round)];
    session::EventRecord e;
    e.type = type;
    e.phase = round.name;
    e.trial = m.index;
    e.condition = m.condition;
    detail["round"] = round.name;
    if (!detail.contains("scored")) detail["scored"] = round.scored;
    e.detailJson = detail.dump();
    return e;
}

void ClickGame::openMatch() {
    const Match& m = matches_[matchIndex_];
    const bool opensRound = matchIndex_ == 0 || matches_[matchIndex_ - 1].round != m.round;
    if (freePlay_ || !opensRound || protocol_.rounds[static_cast<std::size_t>(m.round)].instructions.empty())
        return beginMatch();
    phase_ = Phase::Instructions;
    instructionsShown_ = frame_ + 1;
}

void ClickGame::beginMatch() {
    const Match& m = matches_[matchIndex_];
    phase_ = Phase::Match;
    // Matches begin on a screen's frame (Enter, the last rating): the match's own frames, and
    // its schedule's renders, start with the next one.
    matchStart_ = frame_ + 1;
    world_.emplace(physics_, subSeed(seed_, kTagWorld, m.index));
    schedule_.emplace(protocol_.conditionTable.at(m.condition), protocol_.refreshHz, pacingSeed(seed_, matchStart_));
    worldHistory_.clear();
    // The cursor stays where the hand left it; frames before the match shows its own
    // history (lag, bireproj) show it where the match found it.
    cursorHistory_.clear();
    greenHits_ = redHits_ = misses_ = 0;
    clickGate_.clear();
    emit(matchEvent("match_start", nlohmann::json::object()));
    commitPoint_ = true;
}

void ClickGame::endMatch() {
    emit(matchEvent("match",
                    {{"green_hits", greenHits_},
                     {"red_hits", redHits_},
                     {"misses", misses_},
                     {"clicks", greenHits_ + redHits_ + misses_},
                     {"duration_s", protocol_.matchS}}));
    commitPoint_ = true;
    world_.reset();
    schedule_.reset();
    if (!questions_.empty()) {
        phase_ = Phase::Questions;
        questions_.open(frame_);
        return;
    }
    nextMatch();
}

void ClickGame::nextMatch() {
    if (++matchIndex_ < matches_.size()) return openMatch();
    phase_ = Phase::Done;
}

std::string ClickGame::matchCounter(const Match& m) const {
    const bool scored = protocol_.rounds[static_cast<std::size_t>(m.round)].scored;
    return "Match " + std::to_string(m.inRound + 1) + " of " + std::to_string(m.ofRound) +
        (scored ? "" : " (practice)");
}

void ClickGame::answer(const Answer& a) {
    if (protocol_.formatVersion < protocol::kClickQuestionsSince) {
        // Files older than format 4 rate statements, and their sessions log "rating" events
        // with these keys: kept, so that they replay.
        emit(matchEvent("rating",
                        {{"statement_index", a.questionIndex},
                         {"statement", questions_.questions()[static_cast<std::size_t>(a.questionIndex)].prompt},
                         {"value", *a.value},
                         {"answered_with", a.answeredWith}}));
    } else {
        emit(matchEvent("answer", questions_.answerDetail(a)));
    }
    commitPoint_ = true;
    if (!questions_.answeredAll()) return;
    nextMatch();
    if (phase_ != Phase::Done) return;
    session::EventRecord done;
    done.type = "phase";
    done.phase = "done";
    emit(done);
}

std::vector<physics::Sphere> ClickGame::depictedSpheres(const condition::ScheduledFrame& f) const {
    using Spheres = std::vector<physics::Sphere>;
    auto at = [&](std::int64_t frame) -> std::optional<Spheres> { return worldHistory_.at(frame); };
    auto move = [](Spheres spheres, double dt) {
        for (auto& s : spheres) s.position += s.velocity * dt;
        return spheres;
    };
    const WorldDepiction d =
        depictWorld(schedule_->condition(), f, {matchStart_, protocol_.refreshHz}, WorldClock::Schedule);
    // A B-frame shows the world of the instant it depicts (the schedule's sceneTime), late by
    // the interpolation lag and no more: a sphere only one of the I-frames has (clicked away, or
    // newly entered) is shown as that instant's world has it, there or gone, as the shooter's
    // target is. (Shown from the nearer I-frame instead, a clicked sphere would stay up to half
    // an I-period past the depicted instant, past the latency the schedule gives.)
    const std::optional<Spheres> then = d.how == Depicted::Interpolated ? at(d.depictedFrame) : std::nullopt;
    auto blend = [&then](const Spheres& before, const Spheres& after, double a, double spanS) {
        auto in = [](const Spheres& list, auto id) {
            return std::find_if(list.begin(), list.end(), [&](const auto& o) { return o.id == id; });
        };
        Spheres out;
        for (const auto& s : before) {
            const auto other = in(after, s.id);
            if (other == after.end()) continue;
            physics::Sphere m = s;
            m.position = s.position + (other->position - s.position) * a;
            m.velocity = (other->position - s.position) / spanS;
            out.push_back(m);
        }
        if (then)
            for (const auto& s : *then)
                if (in(before, s.id) == before.end() || in(after, s.id) == after.end()) out.push_back(s);
        std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.id < y.id; });
        return out;
    };
    return *depictedState<Spheres>(d, at, move, blend);
}

ShownFrame ClickGame::screenFrame() {
    ShownFrame shown = screenShownFrame(frame_, now(), camera_, PointerKind::Cursor, cursor_);
    switch (phase_) {
        case Phase::Ready:
            shown.phaseText = "Press Enter to begin";
            shown.promptsEnter = true;
            shown.pointer = PointerKind::None;
            break;
        case Phase::Instructions:
            shown.instructions = protocol_.rounds[static_cast<std::size_t>(matches_[matchIndex_].round)].instructions;
            shown.phaseText = "Press Enter when you have read this";
            shown.promptsEnter = true;
            shown.pointer = PointerKind::None;
            break;
        case Phase::Questions: {
            const Match& m = matches_[matchIndex_];
            shown.question = questions_.prompt(cursor_);
            const bool allLikert = std::all_of(questions_.questions().begin(), questions_.questions().end(),
                                               [](const auto& q) { return q.kind == protocol::QuestionKind::Likert; });
            shown.phaseText = matchCounter(m) +
                (allLikert ? ": rate the match you just played" : ": about the match you just played");
            break;
        }
        case Phase::Match:
        case Phase::Done:
            shown.phaseText = "Thank you";
            shown.pointer = PointerKind::None;
            break;
    }
    return shown;
}

ShownFrame ClickGame::matchFrame(bool click) {
    const double refresh = protocol_.refreshHz;
    const Match& match = matches_[matchIndex_];
    const std::int64_t k = frame_ - matchStart_;
    if (k > 0) world_->advance(stepsPerFrame_);
    worldHistory_.record(frame_, world_->spheres());
    cursorHistory_.record(frame_, cursor_);

    const SchedulePlacement placement{matchStart_, refresh};
    const condition::ScheduledFrame f = schedule_->frame(k);
    ShownFrame shown = scheduledShownFrame(frame_, schedule_->condition(), f, placement);
    shown.camera = camera_;
    shown.pointer = PointerKind::Cursor;
    shown.cursor = cursorHistory_.at(cameraFrame(f, placement));
    const auto depicted = depictedSpheres(f);
    for (const auto& s : depicted) shown.scene.objects.push_back(objectFor(s, physics_.radius));
    if (f.rendersNow) {
        shown.render.camera = camera_;
        shown.render.scene.time = now();
        for (const auto& s : world_->spheres()) shown.render.scene.objects.push_back(objectFor(s, physics_.radius));
    }
    shown.phaseText = matchCounter(match);

    click = clickGate_.pass(click, f);
    if (click) {
        // World: the cursor where the mouse has it now, against the world now. Displayed:
        // the cursor and spheres as the frame on screen shows them.
        const ScreenMapping screen(camera_, display_);
        const ClickHit world = firstSphereAlong(screen.eye(), screen.ray(cursor_), world_->spheres(), physics_.radius);
        const ClickHit displayed = firstSphereAlong(screen.eye(), screen.ray(shown.cursor), depicted, physics_.radius);
        // How far the cursor was from the nearest green sphere's centre on screen (world).
        double nearestGreenPx = std::numeric_limits<double>::quiet_NaN();
        for (const auto& s : world_->spheres()) {
            const auto p = s.green ? screen.project(s.position) : std::nullopt;
            if (p && !(glm::length(*p - cursor_) >= nearestGreenPx)) nearestGreenPx = glm::length(*p - cursor_);
        }
        const ClickHit& judged = protocol_.scoring == protocol::Scoring::World ? world : displayed;
        std::string scored = judged.outcome();
        // A clicked sphere vanishes, red or green ("circles disappear when clicked", seed 000
        // section 8), and can be clicked away only once: under lag its image lingers after it
        // is gone, and a click on the ghost is a miss.
        if (judged.sphere && !world_->remove(judged.sphere->id)) scored = "miss";
        shown.feedback = scored == "green" ? "hit" : "miss";
        greenHits_ += scored == "green";
        redHits_ += scored == "red";
        misses_ += scored == "miss";
        auto idOf = [](const ClickHit& h) { return h.sphere ? static_cast<std::int64_t>(h.sphere->id) : -1; };
        session::EventRecord e = matchEvent("click",
                                            {{"scored", scored},
                                             {"match_time", static_cast<double>(k) / refresh},
                                             {"cursor_x", cursor_.x},
                                             {"cursor_y", cursor_.y},
                                             {"shown_cursor_x", shown.cursor.x},
                                             {"shown_cursor_y", shown.cursor.y},
                                             {"world_sphere", idOf(world)},
                                             {"displayed_sphere", idOf(displayed)},
                                             {"nearest_green_px", nearestGreenPx}});
        e.worldOutcome = world.outcome();
        e.displayedOutcome = displayed.outcome();
        emit(e);
    }
    if (freePlay_)
        shown.phaseText = "Free play: " + match.condition;
    else if (k + 1 >= std::llround(protocol_.matchS * refresh))
        endMatch();
    return shown;
}

ShownFrame ClickGame::step(const FrameInput& input) {
    ++frame_;
    commitPoint_ = false;
    const bool click = (input.buttons & kButtonLeft) && !(previousButtons_ & kButtonLeft);
    const std::uint32_t pressed = input.keys & ~previousKeys_;
    previousButtons_ = input.buttons;
    previousKeys_ = input.keys;
    cursor_.x = std::clamp(cursor_.x + input.mouseDx * protocol_.cursorPixelsPerCount, 0.0,
                           static_cast<double>(display_.width));
    cursor_.y = std::clamp(cursor_.y + input.mouseDy * protocol_.cursorPixelsPerCount, 0.0,
                           static_cast<double>(display_.height));

    if (frame_ == 0) {
        session::EventRecord e;
        e.type = "phase";
        emit(e);
        commitPoint_ = true;
    }
    switch (phase_) {
        case Phase::Ready: {
            ShownFrame shown = screenFrame();
            if (pressed & kKeyEnter) openMatch();
            return shown;
        }
        case Phase::Instructions: {
            ShownFrame shown = screenFrame();
            if (pressed & kKeyEnter) {
                const Match& m = matches_[matchIndex_];
                const auto& round = protocol_.rounds[static_cast<std::size_t>(m.round)];
                session::EventRecord e;
                e.type = "instructions";
                e.phase = round.name;
                e.detailJson =
                    nlohmann::json{
                        {"round", round.name},
                        {"read_s", static_cast<double>(frame_ - instructionsShown_ + 1) / protocol_.refreshHz}}
                        .dump();
                emit(e);
                beginMatch();
            }
            return shown;
        }
        case Phase::Match: return matchFrame(click);
        case Phase::Questions: {
            ShownFrame shown = screenFrame();
            if (const auto a = questions_.step(frame_, *shown.question, pressed, click, input.text)) answer(*a);
            return shown;
        }
        case Phase::Done: return screenFrame();
    }
    return screenFrame();
}

session::FrameRecord ClickGame::frameRecord(const ShownFrame& shown) const {
    session::FrameRecord r = frameRecordOf(shown);
    nlohmann::json detail{{"cursor", {shown.cursor.x, shown.cursor.y}}};
    // Spheres where the frame shows something new; a held frame shows the frame before it again.
    if (!shown.blank && shown.schedule.kind != condition::FrameKind::Held) {
        nlohmann::json spheres = nlohmann::json::array();
        for (const auto& o : shown.scene.objects)
            spheres.push_back({o.id - scene::kIdFirstSphere, o.colour == kGreen ? 1 : 0, rounded(o.position.x),
                               rounded(o.position.y), rounded(o.position.z)});
        detail["spheres"] = std::move(spheres);
    }
    r.detailJson = detail.dump();
    return r;
}

PointerProbe ClickGame::probePointer(const ShownFrame& shown) const {
    PointerProbe probe;
    probe.silhouetteMarginRad = std::numeric_limits<double>::infinity();
    if (shown.blank) return probe;
    const ScreenMapping screen(shown.camera, display_);
    const glm::dvec3 dir = screen.ray(shown.cursor);
    std::vector<physics::Sphere> spheres;
    for (const auto& o : shown.scene.objects) {
        physics::Sphere s;
        s.id = o.id - scene::kIdFirstSphere;
        s.position = glm::dvec3(o.position);  // as the renderer draws it: float positions
        spheres.push_back(s);
        const double distance = glm::length(s.position - screen.eye());
        const double angularRadius = std::asin(std::min(1.0, physics_.radius / distance));
        const double offAxis = physics::angleBetweenRayAndPoint(screen.eye(), dir, s.position);
        probe.silhouetteMarginRad = std::min(probe.silhouetteMarginRad, std::abs(offAxis - angularRadius));
    }
    const ClickHit hit = firstSphereAlong(screen.eye(), dir, spheres, physics_.radius);
    probe.objectId = hit.sphere ? objectId(*hit.sphere) : scene::kIdNone;
    return probe;
}

std::optional<std::uint32_t> ClickGame::displayedObject(const session::EventRecord& event) const {
    if (event.type != "click") return std::nullopt;
    const auto detail = nlohmann::json::parse(event.detailJson, nullptr, false);
    if (detail.is_discarded() || !detail.contains("displayed_sphere")) return std::nullopt;
    const std::int64_t id = detail["displayed_sphere"].get<std::int64_t>();
    return id < 0 ? scene::kIdNone : scene::kIdFirstSphere + static_cast<std::uint32_t>(id);
}

}  // namespace warplab::game
