#include "participants/eye.h"

#include <algorithm>
#include <cmath>

#include "renderer/upconvert.h"

namespace warplab::participants {
namespace {

constexpr int kPictureBlock = 4;  // percept pixels per side of a Thumbnail cell

}  // namespace

// ---------------------------------------------------------------------------------------------
// The eye

Eye::Eye(const renderer::DataPaths& paths, const game::DisplaySize& display, const protocol::RenderSettings& rendering,
         int perceptWidth)
    : display_(display),
      width_(std::max(16, perceptWidth)),
      height_(std::max(9, static_cast<int>(std::lround(static_cast<double>(width_) * display.height / display.width)))),
      maker_(paths, width_, height_, rendering),
      frame_(width_, height_) {}

Percept Eye::see(const game::ShownFrame& shown) {
    // What is read of the ShownFrame is listed at Eye in the header; FrameMaker (the same code
    // that draws a participant's window) reads what it needs to draw the frame.
    maker_.keepSource(shown);
    Percept p;
    p.time = shown.time;
    p.sceneShown = !shown.blank;
    p.pointer = shown.pointer;
    if (shown.pointer == game::PointerKind::Reticle) p.pointerAt = {display_.width * 0.5, display_.height * 0.5};
    if (shown.pointer == game::PointerKind::Cursor) p.pointerAt = shown.cursor;
    p.phaseText = shown.phaseText;
    p.banner = shown.banner;
    p.promptsEnter = shown.promptsEnter;
    p.question = shown.question;
    if (shown.blank) {
        haveImage_ = false;
        return p;
    }
    // A frozen frame, or a held one of the source last shown as it was rendered, is the image
    // already on screen pixel for pixel (a hold copies its source): the same percept, without
    // drawing it again.
    const auto kind = shown.schedule.made;
    const bool same =
        haveImage_ && (shown.frozen || (kind == condition::FrameKind::Held && shown.sourceFrame == lastMadeSource_));
    if (!same) {
        // A held or rendered frame is its source copied: read there, the copy is not made.
        const renderer::SourceFrame* unchanged = maker_.shownUnchanged(shown);
        if (unchanged == nullptr) maker_.make(shown, frame_);
        const renderer::DisplayImages images =
            unchanged != nullptr ? renderer::readShown(*unchanged) : renderer::readBack(frame_, false);
        const glm::dvec2 toDisplay(static_cast<double>(display_.width) / width_,
                                   static_cast<double>(display_.height) / height_);
        lastObjects_ = findObjects(images.ids, images.colour, toDisplay);
        lastPicture_ = thumbnailOf(images.colour, images.ids, kPictureBlock, toDisplay);
        lastDetail_ = thumbnailOf(images.colour, images.ids, 1, toDisplay);
        haveImage_ = true;
        const bool copy =
            !shown.frozen && (kind == condition::FrameKind::Held || kind == condition::FrameKind::Rendered);
        lastMadeSource_ = copy ? shown.sourceFrame : -1;
    }
    p.objects = lastObjects_;
    p.picture = lastPicture_;
    p.detail = lastDetail_;
    return p;
}

// ---------------------------------------------------------------------------------------------
// The player

PerceptualPlayer::PerceptualPlayer(std::unique_ptr<renderer::GlContext> context, const game::Study& study,
                                   const game::DisplaySize& display, const renderer::DataPaths& paths,
                                   std::uint64_t seed, const ParticipantParams& params)
    : context_(std::move(context)),
      eye_(std::make_unique<Eye>(paths, display, study.rendering(), params.perceptWidth)),
      participant_(taskKnowledge(study, display), params, seed),
      model_(participantJson(params)) {}

game::FrameInput PerceptualPlayer::next(const game::ShownFrame& shown) { return participant_.act(eye_->see(shown)); }

game::SeeingPlayerMaker perceptualPlayerMaker(const renderer::DataPaths& paths, renderer::GlBackend backend,
                                              const Population& population) {
    return
        [paths, backend, population](std::uint64_t seed, const game::Study& study, const game::DisplaySize& display) {
            renderer::ContextOptions options;
            options.backend = backend;
            options.visible = false;
            return std::make_unique<PerceptualPlayer>(renderer::createContext(options), study, display, paths, seed,
                                                      drawParticipant(population, seed));
        };
}

std::string PerceptualPlayer::perceivedWith() const {
    std::string text =
        context_ ? context_->info().renderer + ", OpenGL " + context_->info().version : "current context";
    return text + " (the simulated participant's percepts, " + std::to_string(eye_->width()) + "x" +
        std::to_string(eye_->height()) + ")";
}

}  // namespace warplab::participants
