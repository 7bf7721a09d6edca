#include "present/frame_maker.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace warplab::present {

namespace {

// The method that shows a source as it was rendered: the bench's hold at the display's own
// rate, which copies its one source to every frame.
constexpr const char* kShowSource = "hold120";

renderer::HudQuestion::Kind hudKind(protocol::QuestionKind kind) {
    switch (kind) {
        case protocol::QuestionKind::Likert: return renderer::HudQuestion::Kind::Likert;
        case protocol::QuestionKind::Choice: return renderer::HudQuestion::Kind::Choice;
        case protocol::QuestionKind::Text: return renderer::HudQuestion::Kind::Text;
    }
    throw std::invalid_argument("hudFor: a question of an unknown kind");
}

renderer::HudQuestion hudQuestionFor(const game::QuestionPrompt& q, double toFrameX, double toFrameY) {
    renderer::HudQuestion r;
    r.kind = hudKind(q.kind);
    r.prompt = q.prompt;
    for (const auto& b : q.boxes) r.boxes.emplace_back(b.x * toFrameX, b.y * toFrameY, b.z * toFrameX, b.w * toFrameY);
    r.boxLabels = q.boxLabels;
    // A Likert prompt without box labels numbers its boxes from its minimum.
    if (q.kind == protocol::QuestionKind::Likert && r.boxLabels.empty())
        for (std::size_t i = 0; i < q.boxes.size(); ++i)
            r.boxLabels.push_back(std::to_string(q.min + static_cast<int>(i)));
    r.highlighted = q.highlighted;
    if (q.kind == protocol::QuestionKind::Likert) {
        r.minLabel = q.minLabel;
        r.maxLabel = q.maxLabel;
    }
    r.typed = q.typed;
    r.hint = q.hint;
    return r;
}

}  // namespace

renderer::HudContent hudFor(const game::ShownFrame& shown, double toFrameX, double toFrameY) {
    renderer::HudContent content;
    content.backdrop = shown.blank;
    content.reticle = shown.pointer == game::PointerKind::Reticle;
    if (shown.pointer == game::PointerKind::Cursor)
        content.cursor =
            glm::vec2(static_cast<float>(shown.cursor.x * toFrameX), static_cast<float>(shown.cursor.y * toFrameY));
    content.banner = shown.banner;
    content.bannerGood = shown.bannerGood;
    content.status = shown.phaseText;
    content.paragraph = shown.instructions;
    if (shown.question) content.question = hudQuestionFor(*shown.question, toFrameX, toFrameY);
    return content;
}

std::optional<renderer::HudPhotonMarker> hudPhotonMarker(protocol::PhotonMarker corner) {
    using Corner = renderer::HudPhotonMarker::Corner;
    switch (corner) {
        case protocol::PhotonMarker::Off: return std::nullopt;
        case protocol::PhotonMarker::TopLeft: return renderer::HudPhotonMarker{Corner::TopLeft, false};
        case protocol::PhotonMarker::TopRight: return renderer::HudPhotonMarker{Corner::TopRight, false};
        case protocol::PhotonMarker::BottomLeft: return renderer::HudPhotonMarker{Corner::BottomLeft, false};
        case protocol::PhotonMarker::BottomRight: return renderer::HudPhotonMarker{Corner::BottomRight, false};
    }
    return std::nullopt;
}

FrameMaker::FrameMaker(const renderer::DataPaths& paths, int width, int height,
                       const protocol::RenderSettings& rendering)
    : paths_(paths),
      conventional_(paths,
                    [&] {
                        renderer::ShadingOptions shading;
                        shading.supersampling = rendering.supersampling;
                        return shading;
                    }()),
      width_(width),
      height_(height),
      warpBand_(renderer::guardBandFor(width, height, rendering.guardBand)) {}

renderer::SourceFrame& FrameMaker::rendered(Kept& kept) {
    if (kept.frame) return *kept.frame;
    const auto spare = std::find_if(spare_.begin(), spare_.end(), [&](const auto& f) { return f->band == kept.band; });
    if (spare != spare_.end()) {
        kept.frame = std::move(*spare);
        spare_.erase(spare);
    } else {
        kept.frame = std::make_unique<renderer::SourceFrame>(width_, height_, kept.band);
    }
    renderer::renderSource(conventional_, kept.shows, *kept.frame, kept.flowTo ? &*kept.flowTo : nullptr);
    ++rendersDrawn_;
    return *kept.frame;
}

void FrameMaker::release(Kept& kept) {
    if (kept.frame) spare_.push_back(std::move(kept.frame));
}

void FrameMaker::prepareFor(const game::Study& study) {
    method(kShowSource);
    for (const std::string& condition : study.conditionNames()) {
        const condition::Condition& c = study.conditions().at(condition);
        for (const std::string& name : {c.sourceMethod(), c.warpMethod(), c.interpolationMethod()})
            if (!name.empty()) method(name);
    }
}

void FrameMaker::keepSource(const game::ShownFrame& shown) {
    if (shown.rendersNow) {
        // The method that makes the condition's other frames from its sources (its fill, or
        // its late warp) says what they need.
        const std::string name = shown.condition.name.empty() ? std::string() : shown.condition.sourceMethod();
        const renderer::MethodInfo* info = name.empty() ? nullptr : &method(name).info();
        Kept kept{nullptr, shown.render, {}, std::nullopt};
        // Warps render beyond the displayed field of view, so what a turn brings into view is
        // really there; the frames they show as rendered are the band's inside (hold).
        if (info && info->takesGuardBand) kept.band = warpBand_;
        // Bidirectional reprojection's I-frames carry their backward flow towards the previous
        // I-frame, drawn in the same pass (seed 000 section 5).
        if (info && info->usesSourceFlow && !sources_.empty()) kept.flowTo = sources_.rbegin()->second.shows;
        auto [it, fresh] = sources_.try_emplace(shown.frame);
        if (!fresh) release(it->second);
        it->second = std::move(kept);
    }
    // None older than what the frame on screen is made from will be needed again.
    if (!shown.blank)
        while (!sources_.empty() && sources_.begin()->first < shown.sourceFrame) {
            release(sources_.begin()->second);
            sources_.erase(sources_.begin());
        }
}

void FrameMaker::make(const game::ShownFrame& shown, renderer::DisplayFrame& display) {
    std::string name = kShowSource;
    const auto kind = shown.schedule.made;  // a repeated frame is made as the one it repeats
    // Warped frames: the fill's warp, or the late warp of a held frame (to the display
    // instant's camera: shown.camera; and, with depth, the objects moved on to shown.scene.time).
    if (kind == condition::FrameKind::Warped) name = shown.condition.warpMethod();
    if (kind == condition::FrameKind::Interpolated) name = shown.condition.interpolationMethod();
    renderer::UpconversionMethod& shows = method(name);
    auto it = sources_.find(shown.sourceFrame);
    if (it == sources_.end()) {
        // Lag conditions open with frames queued before the condition started: the scene as it was.
        it = sources_.emplace(shown.sourceFrame, Kept{nullptr, {shown.camera, shown.scene}, {}, std::nullopt}).first;
    } else if (!shows.info().acceptsGuardBand && !(it->second.band == renderer::GuardBand{})) {
        // A warp condition's source shown by a method that takes no band (at a change of condition): drawn
        // again without it.
        release(it->second);
        it->second.band = {};
        it->second.flowTo.reset();
    }
    renderer::UpconversionInput input;
    input.displayTime = shown.scene.time;  // the instant the frame depicts (frozen frames: the shot's)
    input.camera = shown.camera;
    input.previous = &rendered(it->second);
    input.scene = &shown.scene;
    if (kind == condition::FrameKind::Interpolated) {
        const auto next = sources_.find(shown.nextSourceFrame);
        input.next = next == sources_.end() ? input.previous : &rendered(next->second);
    }
    shows.produce(input, display);
}

const renderer::SourceFrame* FrameMaker::shownUnchanged(const game::ShownFrame& shown) {
    const auto kind = shown.schedule.made;
    if (kind != condition::FrameKind::Held && kind != condition::FrameKind::Rendered) return nullptr;
    const auto it = sources_.find(shown.sourceFrame);
    if (it == sources_.end() || !(it->second.band == renderer::GuardBand{})) return nullptr;
    return &rendered(it->second);  // make() would show it by kShowSource: a copy
}

renderer::UpconversionMethod& FrameMaker::method(const std::string& name) {
    auto& m = methods_[name];
    if (!m) {
        // A method this context cannot run (warp-splat below OpenGL 4.3) is shown by its
        // fallback, and the session says so rather than stopping a participant's run.
        const std::string why = renderer::methodUnavailable(name);
        const std::string fallback = why.empty() ? std::string() : renderer::methodFallback(name);
        if (fallback.empty()) {
            m = renderer::makeMethod(name, paths_);  // throws the reason when there is one and no fallback
        } else {
            notes_.push_back(why + "; its frames are made with " + fallback + " instead");
            m = renderer::makeMethod(fallback, paths_);
        }
    }
    return *m;
}

std::vector<std::string> FrameMaker::takeNotes() { return std::exchange(notes_, {}); }

}  // namespace warplab::present
