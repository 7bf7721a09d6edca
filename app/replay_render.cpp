#include "app/replay_render.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

#include "game/registry.h"
#include "protocol/session_store.h"
#include "renderer/hud.h"
#include "renderer/upconvert.h"

namespace warplab::app {
namespace {

// How close to a silhouette (in pixels of the re-rendered frame) the pointer may be before
// the cross-check stops counting it: the analytic sphere and its tessellated, rasterised
// image may honestly disagree there.
constexpr double kSilhouetteMarginPx = 2.0;

// Game objects have ids from kIdTarget up; the hangar and the sky both mean "nothing".
std::uint32_t gameObject(std::uint32_t id) { return id >= scene::kIdTarget ? id : scene::kIdNone; }

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

// Makes each displayed frame the way its mode makes it, from the conventional renders it
// keeps: a held or rendered frame is its source copied (hold120); warped and interpolated
// frames use the mode's method (or its stand-in, said once).
class FrameMaker {
public:
    FrameMaker(const renderer::DataPaths& paths, int width, int height, std::ostream& out)
        : paths_(paths), conventional_(paths), width_(width), height_(height), out_(out) {}

    // Every step's frame, also outside the requested range: held, lagged and warped frames
    // need sources from before it.
    void keepSource(const game::ShownFrame& shown) {
        if (shown.rendersNow) {
            auto source = std::make_unique<renderer::SourceFrame>(width_, height_);
            source->depicts = shown.render;
            conventional_.render(shown.render, source->gbuffer);
            sources_[shown.frame] = std::move(source);
        }
        // None older than what the frame on screen is made from will be needed again.
        if (!shown.blank)
            while (!sources_.empty() && sources_.begin()->first < shown.sourceFrame) sources_.erase(sources_.begin());
    }

    void make(const game::ShownFrame& shown, renderer::DisplayFrame& display) {
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
        std::string name = "hold120";
        const auto kind = shown.schedule.kind;
        if (kind == game::FrameKind::Warped || kind == game::FrameKind::Interpolated) {
            const auto& mode = game::modeSpec(shown.mode);
            name = mode.method;
            if (!mode.standInFor.empty() && !saidStandIn_[shown.mode]) {
                out_ << "replay: " << shown.mode << " frames are drawn with '" << name << "' until the "
                     << mode.standInFor << " renderer exists\n";
                saidStandIn_[shown.mode] = true;
            }
        }
        if (kind == game::FrameKind::Interpolated) {
            const auto next = sources_.find(shown.nextSourceFrame);
            input.next = next == sources_.end() ? it->second.get() : next->second.get();
        }
        method(name).produce(input, display);
    }

private:
    renderer::UpconversionMethod& method(const std::string& name) {
        auto& m = methods_[name];
        if (!m) m = renderer::makeMethod(name, paths_);
        return *m;
    }

    renderer::DataPaths paths_;
    renderer::ConventionalRenderer conventional_;
    int width_, height_;
    std::ostream& out_;
    std::map<std::int64_t, std::unique_ptr<renderer::SourceFrame>> sources_;  // by session frame
    std::map<std::string, std::unique_ptr<renderer::UpconversionMethod>> methods_;
    std::map<std::string, bool> saidStandIn_;
};

// The cross-check of the analytic scoring against the id buffer, on frames whose image is an
// exact render of what they depict (rendered or held; warped and interpolated images only
// approximate it).
class PointerCheck {
public:
    PointerCheck(const game::Game& game, const protocol::SessionData& data, double toFrameX, double toFrameY)
        : game_(game), toFrameX_(toFrameX), toFrameY_(toFrameY) {
        for (const auto& e : data.events)
            if (const auto id = game.displayedObject(e)) loggedObject_[e.frame] = *id;
    }

    void check(const game::ShownFrame& shown, const renderer::DisplayFrame& display, ReplayRenderResult& result) {
        const auto kind = shown.schedule.kind;
        if (shown.blank || shown.frozen || !(kind == game::FrameKind::Rendered || kind == game::FrameKind::Held)) return;
        const int width = display.width(), height = display.height();
        const bool cursor = shown.pointer == game::PointerKind::Cursor;
        const int ix = std::clamp(static_cast<int>(cursor ? shown.cursor.x * toFrameX_ : width * 0.5), 0, width - 1);
        const int iy = std::clamp(static_cast<int>(cursor ? shown.cursor.y * toFrameY_ : height * 0.5), 0, height - 1);
        const std::uint32_t seen = gameObject(renderer::readBack(display).ids.at(ix, iy));
        const game::PointerProbe probe = game_.probePointer(shown);
        const double radiansPerPixel = glm::radians(static_cast<double>(shown.camera.verticalFovDeg)) / height;
        if (probe.silhouetteMarginRad <= kSilhouetteMarginPx * radiansPerPixel) {
            ++result.nearSilhouette;
            return;
        }
        ++result.checked;
        const std::string where = "frame " + std::to_string(shown.frame) + ": id " + std::to_string(seen) +
                                  " under the pointer, ";
        if (seen != probe.objectId) disagree(result, where + "the analytic model says " + std::to_string(probe.objectId));
        const auto logged = loggedObject_.find(shown.frame);
        if (logged == loggedObject_.end()) return;
        ++result.eventsChecked;
        if (seen != logged->second)
            disagree(result, where + "the logged displayed outcome names " + std::to_string(logged->second));
    }

private:
    static void disagree(ReplayRenderResult& result, const std::string& what) {
        if (result.disagreements.size() < 10) result.disagreements.push_back(what);
        ++result.disagreed;
    }

    const game::Game& game_;
    double toFrameX_, toFrameY_;
    std::map<std::int64_t, std::uint32_t> loggedObject_;  // what logged shots and clicks say was under the pointer
};

}  // namespace

ReplayRenderResult renderReplay(const ReplayRender& request, const renderer::DataPaths& paths,
                                renderer::GlBackend backend, std::ostream& out) {
    const protocol::SessionData data = protocol::readSession(request.sessionPath);
    const auto study = game::parseStudy(data.header.protocolJson, request.sessionPath);
    const game::DisplaySize display{data.header.displayWidth, data.header.displayHeight};
    const int width = request.width > 0 ? request.width : display.width;
    const int height = request.height > 0 ? request.height : display.height;
    const double toFrameX = static_cast<double>(width) / display.width;
    const double toFrameY = static_cast<double>(height) / display.height;
    std::filesystem::create_directories(request.outDir);

    renderer::ContextOptions options;
    options.backend = backend;
    options.visible = false;
    const auto context = renderer::createContext(options);
    FrameMaker maker(paths, width, height, out);
    renderer::HudRenderer hud(paths);
    renderer::DisplayFrame displayFrame(width, height);
    const auto game = study->newGame(data.header.seed, display);
    PointerCheck pointerCheck(*game, data, toFrameX, toFrameY);
    ReplayRenderResult result;

    for (const auto& in : data.inputs) {
        if (in.frame > request.lastFrame) break;
        const game::ShownFrame shown = game->step({in.mouseDx, in.mouseDy, in.buttons, in.keys});
        game->takeEvents();
        maker.keepSource(shown);
        if (shown.frame < request.firstFrame) continue;
        if (!shown.blank) {
            maker.make(shown, displayFrame);
            pointerCheck.check(shown, displayFrame, result);
        }
        hud.draw(hudFor(shown, toFrameX, toFrameY), displayFrame.buffer());

        char file[64];
        std::snprintf(file, sizeof file, "/frame_%07lld.png", static_cast<long long>(shown.frame));
        renderer::writePng(request.outDir + file, renderer::readBack(displayFrame).colour);
        ++result.written;
    }
    out << "wrote " << result.written << " frames to " << request.outDir << "; pointer cross-check on "
        << result.checked << " rendered or held frames (" << result.eventsChecked << " of them logged clicks or shots, "
        << result.nearSilhouette << " skipped within " << kSilhouetteMarginPx
        << " px of a silhouette): the id read back disagrees on " << result.disagreed << "\n";
    for (const auto& d : result.disagreements) out << "  " << d << "\n";
    return result;
}

}  // namespace warplab::app
