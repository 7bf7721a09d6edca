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
    renderer::ConventionalRenderer conventional(paths);
    std::map<std::string, std::unique_ptr<renderer::UpconversionMethod>> methods;
    auto method = [&](const std::string& name) -> renderer::UpconversionMethod& {
        auto& m = methods[name];
        if (!m) m = renderer::makeMethod(name, paths);
        return *m;
    };
    renderer::HudRenderer hud(paths);
    renderer::DisplayFrame displayFrame(width, height);
    std::map<std::int64_t, std::unique_ptr<renderer::SourceFrame>> sources;  // by session frame
    std::map<std::string, bool> saidStandIn;
    ReplayRenderResult result;
    auto disagree = [&](const std::string& what) {
        if (result.disagreements.size() < 10) result.disagreements.push_back(what);
        ++result.disagreed;
    };

    // Logged pointer events by frame: what their displayed outcome says was under the pointer.
    std::map<std::int64_t, std::uint32_t> loggedObject;
    const auto game = study->newGame(data.header.seed, display);
    for (const auto& e : data.events)
        if (const auto id = game->displayedObject(e)) loggedObject[e.frame] = *id;

    for (const auto& in : data.inputs) {
        if (in.frame > request.lastFrame) break;
        const game::ShownFrame shown = game->step({in.mouseDx, in.mouseDy, in.buttons, in.keys});
        game->takeEvents();
        // Sources are needed from before the range too (held, lagged and warped frames); none
        // older than what the frame on screen is made from will be needed again.
        if (shown.rendersNow) {
            auto source = std::make_unique<renderer::SourceFrame>(width, height);
            source->depicts = shown.render;
            conventional.render(shown.render, source->gbuffer);
            sources[shown.frame] = std::move(source);
        }
        if (!shown.blank)
            while (!sources.empty() && sources.begin()->first < shown.sourceFrame) sources.erase(sources.begin());
        if (shown.frame < request.firstFrame) continue;

        if (!shown.blank) {
            auto it = sources.find(shown.sourceFrame);
            if (it == sources.end()) {
                // Lag modes open with frames queued before the mode started: the scene as it was.
                auto before = std::make_unique<renderer::SourceFrame>(width, height);
                before->depicts = {shown.camera, shown.scene};
                conventional.render(before->depicts, before->gbuffer);
                it = sources.emplace(shown.sourceFrame, std::move(before)).first;
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
                if (!mode.standInFor.empty() && !saidStandIn[shown.mode]) {
                    out << "replay: " << shown.mode << " frames are drawn with '" << name << "' until the "
                        << mode.standInFor << " renderer exists\n";
                    saidStandIn[shown.mode] = true;
                }
            }
            if (kind == game::FrameKind::Interpolated) {
                const auto next = sources.find(shown.nextSourceFrame);
                input.next = next == sources.end() ? it->second.get() : next->second.get();
            }
            method(name).produce(input, displayFrame);

            // Cross-check the analytic scoring against the id buffer, on frames whose image is
            // an exact render of what they depict (rendered or held; warped and interpolated
            // images only approximate it).
            const bool exact = kind == game::FrameKind::Rendered || kind == game::FrameKind::Held;
            if (!shown.frozen && exact) {
                const double px = shown.pointer == game::PointerKind::Cursor ? shown.cursor.x * toFrameX : width * 0.5;
                const double py = shown.pointer == game::PointerKind::Cursor ? shown.cursor.y * toFrameY : height * 0.5;
                const int ix = std::clamp(static_cast<int>(px), 0, width - 1);
                const int iy = std::clamp(static_cast<int>(py), 0, height - 1);
                const auto ids = renderer::readBack(displayFrame).ids;
                const std::uint32_t seen = gameObject(ids.at(ix, iy));
                const game::PointerProbe probe = game->probePointer(shown);
                const double radiansPerPixel = glm::radians(static_cast<double>(shown.camera.verticalFovDeg)) / height;
                if (probe.silhouetteMarginRad > kSilhouetteMarginPx * radiansPerPixel) {
                    ++result.checked;
                    if (seen != probe.objectId)
                        disagree("frame " + std::to_string(shown.frame) + ": id " + std::to_string(seen) +
                                 " under the pointer, the analytic model says " + std::to_string(probe.objectId));
                    const auto logged = loggedObject.find(shown.frame);
                    if (logged != loggedObject.end()) {
                        ++result.eventsChecked;
                        if (seen != logged->second)
                            disagree("frame " + std::to_string(shown.frame) + ": id " + std::to_string(seen) +
                                     " under the pointer, the logged displayed outcome names " +
                                     std::to_string(logged->second));
                    }
                } else {
                    ++result.nearSilhouette;
                }
            }
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
