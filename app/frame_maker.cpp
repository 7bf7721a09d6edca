#include "app/frame_maker.h"

namespace warplab::app {

renderer::HudContent hudFor(const game::ShownFrame& shown, double toFrameX, double toFrameY) {
    renderer::HudContent content;
    content.backdrop = shown.blank;
    content.reticle = shown.pointer == game::PointerKind::Reticle;
    if (shown.pointer == game::PointerKind::Cursor)
        content.cursor = glm::vec2(static_cast<float>(shown.cursor.x * toFrameX), static_cast<float>(shown.cursor.y * toFrameY));
    content.banner = shown.banner;
    content.bannerGood = shown.bannerGood;
    content.status = shown.phaseText;
    if (shown.rating) {
        renderer::HudRating r;
        r.statement = shown.rating->statement;
        for (const auto& b : shown.rating->boxes)
            r.boxes.emplace_back(b.x * toFrameX, b.y * toFrameY, b.z * toFrameX, b.w * toFrameY);
        r.highlighted = shown.rating->highlighted;
        r.firstValue = shown.rating->min;
        r.minLabel = shown.rating->minLabel;
        r.maxLabel = shown.rating->maxLabel;
        content.rating = r;
    }
    return content;
}

void FrameMaker::keepSource(const game::ShownFrame& shown) {
    if (shown.rendersNow) {
        auto source = std::make_unique<renderer::SourceFrame>(width_, height_);
        source->depicts = shown.render;
        // Bidirectional reprojection's I-frames carry their backward flow towards the previous
        // I-frame, drawn in the same pass (seed 000 section 5).
        const bool flow = !shown.mode.empty() &&
                          game::modeSpec(shown.mode).upconversion == game::Upconversion::Bidirectional &&
                          !sources_.empty() && method(game::modeSpec(shown.mode).method).info().usesSourceFlow;
        if (flow) conventional_.render(shown.render, source->gbuffer, sources_.rbegin()->second->depicts);
        else conventional_.render(shown.render, source->gbuffer);
        sources_[shown.frame] = std::move(source);
    }
    // None older than what the frame on screen is made from will be needed again.
    if (!shown.blank)
        while (!sources_.empty() && sources_.begin()->first < shown.sourceFrame) sources_.erase(sources_.begin());
}

void FrameMaker::make(const game::ShownFrame& shown, renderer::DisplayFrame& display) {
    auto it = sources_.find(shown.sourceFrame);
    if (it == sources_.end()) {
        // Lag modes open with frames queued before the mode started: the scene as it was.
        auto before = std::make_unique<renderer::SourceFrame>(width_, height_);
        before->depicts = {shown.camera, shown.scene};
        conventional_.render(before->depicts, before->gbuffer);
        it = sources_.emplace(shown.sourceFrame, std::move(before)).first;
    }
    renderer::UpconversionInput input;
    input.displayTime = shown.scene.time;  // the instant the frame depicts (frozen frames: the shot's)
    input.camera = shown.camera;
    input.previous = it->second.get();
    input.scene = &shown.scene;
    std::string name = "hold120";
    const auto kind = shown.schedule.kind;
    if (kind == game::FrameKind::Warped || kind == game::FrameKind::Interpolated) {
        name = game::modeSpec(shown.mode).method;
    }
    if (kind == game::FrameKind::Interpolated) {
        const auto next = sources_.find(shown.nextSourceFrame);
        input.next = next == sources_.end() ? it->second.get() : next->second.get();
    }
    method(name).produce(input, display);
}

renderer::UpconversionMethod& FrameMaker::method(const std::string& name) {
    auto& m = methods_[name];
    if (!m) m = renderer::makeMethod(name, paths_);
    return *m;
}

}  // namespace warplab::app
