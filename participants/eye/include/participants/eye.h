// The simulated participant's eye (GL) and the player that joins it to the participant
// (participants/participant.h): the eye draws each displayed frame as the session's condition
// makes it, through the same FrameMaker a participant's window uses, and perceives it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "game/game.h"
#include "participants/participant.h"
#include "participants/perception.h"
#include "participants/population.h"
#include "present/frame_maker.h"
#include "renderer/context.h"

namespace warplab::participants {

// ---------------------------------------------------------------------------------------------
// The eye: GL. Makes each displayed frame as the condition makes it, at the percept resolution.
// What it reads of a ShownFrame, all of it: (1) whatever FrameMaker reads to draw the frame --
// the same drawing a participant's window shows; (2) what the HUD draws over it: the pointer
// (reticle or cursor position), banner, phase text, Enter prompt, rating screen, and whether
// the scene is shown at all (`blank`); (3) its display time; (4) to skip drawing an image that
// is already on screen, whether the frame is frozen or a held copy of the source last drawn
// (`frozen`, `schedule.made`, `sourceFrame`): the same pixels either way; and a held or
// rendered frame is read at the source FrameMaker would copy (FrameMaker::shownUnchanged), the
// same pixels without the copy. Never the scene's objects, the camera, the condition or the outcome
// for itself.
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
    present::FrameMaker maker_;
    renderer::DisplayFrame frame_;
    std::vector<SeenObject> lastObjects_;
    Thumbnail lastPicture_, lastDetail_;
    bool haveImage_ = false;  // an image of the scene is on screen (no screen since)
    std::int64_t lastMadeSource_ = -1;  // the source it copies (rendered or held), else -1
};

// Makes PerceptualPlayers for the GL-free runner, each with a headless context of its own
// (`backend`: OSMesa or EGL) and the shaders under `paths`, the participant with a seed drawn
// from `population` (participants/population.h).
game::SeeingPlayerMaker perceptualPlayerMaker(const renderer::DataPaths& paths, renderer::GlBackend backend,
                                              const Population& population);

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
    std::string perceivedWith() const override;
    // Its traits (participantJson), recorded in the session's header.
    std::string model() const override { return model_; }

private:
    std::unique_ptr<renderer::GlContext> context_;  // first: destroyed after the GL objects below
    std::unique_ptr<Eye> eye_;
    SimulatedParticipant participant_;
    std::string model_;
};

}  // namespace warplab::participants
