// The falling-sphere click game (seed 000 section 8; slides: seed 003) as a deterministic
// state machine on the display clock. Red and green spheres fall and bounce in a box seen by
// a fixed camera; the player moves a cursor and clicks: a clicked sphere vanishes and counts
// as a green or a red hit, a click on empty space as a miss. Matches of a fixed length,
// one per condition and round in a seeded order, each followed by the protocol's questions (by
// default Yang et al.'s four statements, rated 1-7). The cursor is part of the displayed frame, so it shares the condition's frame rate
// and lag with the spheres. No GL; a session is a pure function of protocol, seed and input.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "game/depiction.h"
#include "game/frame_history.h"
#include "game/game.h"
#include "game/questionnaire.h"
#include "physics/falling_spheres.h"
#include "click/click_protocol.h"

namespace warplab::game {

// What a click hit, in the world or in the frame on screen.
struct ClickHit {
    std::optional<physics::Sphere> sphere;  // nullopt: empty space
    std::string outcome() const { return !sphere ? "miss" : (sphere->green ? "green" : "red"); }
};

// The first sphere along a ray (spheres may hide each other).
ClickHit firstSphereAlong(const glm::dvec3& eye, const glm::dvec3& dir, const std::vector<physics::Sphere>& spheres,
                          double radius);

class ClickGame final : public FreePlayGame {
public:
    ClickGame(const protocol::ClickProtocol& protocol, std::uint64_t seed, const DisplaySize& display);

    ShownFrame step(const FrameInput& input) override;
    bool finished() const override { return phase_ == Phase::Done; }
    std::string phase() const override;
    std::vector<session::EventRecord> takeEvents() override;
    bool atCommitPoint() const override { return commitPoint_; }
    session::FrameRecord frameRecord(const ShownFrame& shown) const override;
    bool isOutcome(const session::EventRecord& event) const override { return event.type == "click"; }
    PointerProbe probePointer(const ShownFrame& shown) const override;
    std::optional<std::uint32_t> displayedObject(const session::EventRecord& event) const override;
    // Match events recorded before bidirectional reprojection existed say that a stand-in drew
    // the condition's frames ("stand_in": the rendering, not the game).
    std::vector<std::string> renderDetailKeys() const override { return {"stand_in"}; }
    // Free play: one endless match in `mode` (the click game has no difficulty levels).
    void switchTo(const std::string& condition, int difficulty) override;

    struct Match {
        int index = 0;  // over the whole session
        int round = 0;  // index into protocol.rounds
        std::string condition;
        int inRound = 0, ofRound = 0;  // its place in its round, and the round's match count
    };
    const std::vector<Match>& matches() const { return matches_; }
    // The world of the match in progress (tests); nullptr between matches.
    const physics::FallingSpheres* world() const { return world_ ? &*world_ : nullptr; }
    const scene::CameraState& camera() const { return camera_; }
    glm::dvec2 cursor() const { return cursor_; }
    static std::uint32_t objectId(const physics::Sphere& sphere);

private:
    enum class Phase : std::uint8_t { Ready, Instructions, Match, Questions, Done };

    // The match at matchIndex_, or first its round's instructions where it opens a round.
    void openMatch();
    void beginMatch();
    void endMatch();
    void answer(const Answer& answer);
    // After the last question (or the match, without questions): the next match, or the end.
    void nextMatch();
    ShownFrame matchFrame(bool click);
    ShownFrame screenFrame();  // ready, instructions, question and done screens
    std::vector<physics::Sphere> depictedSpheres(const condition::ScheduledFrame& f) const;
    void emit(session::EventRecord event);
    // An event of the match in progress: its round, index and condition, and the detail with the
    // round's name and whether it is scored (unless the detail says what "scored" means).
    session::EventRecord matchEvent(const char* type, nlohmann::json detail) const;
    double now() const { return static_cast<double>(frame_) / protocol_.refreshHz; }
    // "Match 2 of 7 (practice)": where the participant is in the round being played.
    std::string matchCounter(const Match& m) const;

    protocol::ClickProtocol protocol_;
    std::uint64_t seed_;
    DisplaySize display_;
    physics::FallingSphereSettings physics_;
    scene::CameraState camera_;
    std::int64_t stepsPerFrame_ = 1;

    std::int64_t frame_ = -1;
    glm::dvec2 cursor_;
    std::uint32_t previousButtons_ = 0, previousKeys_ = 0;
    ClickGate clickGate_;

    Phase phase_ = Phase::Ready;
    std::vector<Match> matches_;
    std::size_t matchIndex_ = 0;
    std::int64_t matchStart_ = 0;
    std::optional<physics::FallingSpheres> world_;
    std::optional<condition::ConditionSchedule> schedule_;
    FrameHistory<std::vector<physics::Sphere>> worldHistory_;  // the world at each frame of the match
    FrameHistory<glm::dvec2> cursorHistory_;
    int greenHits_ = 0, redHits_ = 0, misses_ = 0;
    Questionnaire questions_;
    std::int64_t instructionsShown_ = 0;  // the first frame of the instructions screen

    bool freePlay_ = false;

    EventQueue events_;
    bool commitPoint_ = false;
};

}  // namespace warplab::game
