#include "present/replay_render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <memory>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "game/registry.h"
#include "session/session_store.h"
#include "present/frame_maker.h"
#include "renderer/hud.h"
#include "renderer/upconvert.h"
#include "scene/usage_error.h"

namespace warplab::present {
namespace {

// How close to a silhouette (in pixels of the re-rendered frame) the pointer may be before
// the cross-check stops counting it: the analytic sphere and its tessellated, rasterised
// image may honestly disagree there.
constexpr double kSilhouetteMarginPx = 2.0;

// Game objects have ids from kIdTarget up; the hangar and the sky both mean "nothing".
std::uint32_t gameObject(std::uint32_t id) { return id >= scene::kIdTarget ? id : scene::kIdNone; }

// The cross-check of the analytic scoring against the id buffer, on frames whose image is an
// exact render of what they depict: a render copied (rendered or held), and a held render
// late-warped by the camera's rotation (the games' cameras only turn about their eye, so a
// rotation reprojection is the render from the new camera, objects where the render had them).
// Other warped and interpolated images, shown anew or repeated, only approximate what they
// depict.
bool exactImage(const game::ShownFrame& shown) {
    const auto kind = shown.schedule.made;  // a repeated B-frame is held, and still a B-frame
    if (kind == condition::FrameKind::Rendered || kind == condition::FrameKind::Held) return true;
    return kind == condition::FrameKind::Warped && shown.condition.lateWarp == condition::LateWarp::Rotation &&
        shown.condition.fillKind() == condition::Fill::Hold;
}

class PointerCheck {
public:
    PointerCheck(const game::Game& game, const session::SessionData& data, double toFrameX, double toFrameY)
        : game_(game), toFrameX_(toFrameX), toFrameY_(toFrameY) {
        for (const auto& e : data.events)
            if (const auto id = game.displayedObject(e)) loggedObject_[e.frame] = *id;
    }

    // `ids`: the displayed frame's id attachment (the HUD leaves it untouched).
    void check(const game::ShownFrame& shown, const image::ImageU32& ids, ReplayRenderResult& result) {
        if (shown.blank || shown.frozen || !exactImage(shown)) return;
        const int width = ids.width, height = ids.height;
        const bool cursor = shown.pointer == game::PointerKind::Cursor;
        const int ix = std::clamp(static_cast<int>(cursor ? shown.cursor.x * toFrameX_ : width * 0.5), 0, width - 1);
        const int iy = std::clamp(static_cast<int>(cursor ? shown.cursor.y * toFrameY_ : height * 0.5), 0, height - 1);
        const std::uint32_t seen = gameObject(ids.at(ix, iy));
        const game::PointerProbe probe = game_.probePointer(shown);
        const double radiansPerPixel = glm::radians(static_cast<double>(shown.camera.verticalFovDeg)) / height;
        if (probe.silhouetteMarginRad <= kSilhouetteMarginPx * radiansPerPixel) {
            ++result.nearSilhouette;
            return;
        }
        ++result.checked;
        const std::string where =
            "frame " + std::to_string(shown.frame) + ": id " + std::to_string(seen) + " under the pointer, ";
        if (seen != probe.objectId)
            disagree(result, where + "the analytic model says " + std::to_string(probe.objectId));
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

// The photodiode marker as the session's window drew it: in the corner its header names, or
// for a file from before the header named it, the protocol's; white on the frames the window
// lit, which its frame rows mark (docs/session-format.md).
class RecordedPhotonMarker {
public:
    RecordedPhotonMarker(const session::SessionData& data, const game::Study& study, const std::string& path) {
        const std::string& stored = data.header.photonMarker;
        const auto corner =
            stored.empty() ? study.rendering().photonMarker : protocol::valueNamed<protocol::PhotonMarker>(stored);
        if (!corner)
            throw std::runtime_error("session file " + path + " has photon_marker '" + stored +
                                     "' in its header, which is no corner of the marker (off, top_left, top_right, "
                                     "bottom_left, bottom_right)");
        marker_ = hudPhotonMarker(*corner);
        if (!marker_) return;
        for (const auto& f : data.frames) {
            if (f.detailJson.find("\"photon_marker\"") == std::string::npos) continue;
            const auto detail = nlohmann::json::parse(f.detailJson, nullptr, false);
            if (detail.is_object() && detail.value("photon_marker", false)) lit_.insert(f.frame);
        }
    }
    // Onto the HUD of display frame `frame`.
    void draw(std::int64_t frame, renderer::HudContent& content) const {
        content.photonMarker = marker_;
        if (content.photonMarker) content.photonMarker->lit = lit_.count(frame) > 0;
    }

private:
    std::optional<renderer::HudPhotonMarker> marker_;
    std::set<std::int64_t> lit_;
};

}  // namespace

ReplayRenderResult renderReplay(const ReplayRender& request, const renderer::DataPaths& paths,
                                renderer::GlBackend backend, std::ostream& out, std::ostream& progress) {
    const session::SessionData data = session::readSession(request.sessionPath);
    // Before any work: a range past the end would re-simulate the whole session to write nothing.
    const std::int64_t lastRecorded = data.inputs.empty() ? -1 : data.inputs.back().frame;
    if (request.firstFrame > lastRecorded)
        throw UsageError("option --frames starts at frame " + std::to_string(request.firstFrame) + ", but " +
                         request.sessionPath + " ends at frame " + std::to_string(lastRecorded));
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
    FrameMaker maker(paths, width, height, study->rendering());
    renderer::HudRenderer hud(paths);
    renderer::DisplayFrame displayFrame(width, height);
    const auto game = study->newGame(data.header.seed, display);
    PointerCheck pointerCheck(*game, data, toFrameX, toFrameY);
    const RecordedPhotonMarker photonMarker(data, *study, request.sessionPath);
    ReplayRenderResult result;
    // Display frames the live session stepped through without showing (its display clock):
    // kept as sources, since later frames may be made from them, but never pictures.
    std::set<std::int64_t> skipped;
    for (const auto& f : data.frames)
        if (f.kind == session::kSkippedFrameKind) skipped.insert(f.frame);

    const std::int64_t lastFrame = std::min(request.lastFrame, lastRecorded);
    if (request.firstFrame > 0)
        progress << "replay --render: re-simulating frames 0 to " << request.firstFrame - 1
                 << " without drawing them, then drawing " << request.firstFrame << " to " << lastFrame << "\n";
    using Clock = std::chrono::steady_clock;
    const auto every = std::chrono::duration<double>(request.progressEveryS);
    auto said = Clock::now();
    for (const auto& in : data.inputs) {
        if (in.frame > request.lastFrame) break;
        if (Clock::now() - said >= every) {
            said = Clock::now();
            progress << "replay --render: " << (in.frame < request.firstFrame ? "re-simulating" : "drawing")
                     << " frame " << in.frame << " of " << lastFrame << "\n";
        }
        if (game::resumedBefore(data.header, in.frame)) game->resumeHere();
        const game::ShownFrame shown = game->step({in.mouseDx, in.mouseDy, in.buttons, in.keys, in.text});
        game->takeEvents();
        maker.keepSource(shown);
        if (shown.frame < request.firstFrame) continue;
        if (skipped.count(shown.frame)) {
            ++result.skipped;
            continue;
        }
        if (!shown.blank) maker.make(shown, displayFrame);
        for (const std::string& note : maker.takeNotes()) out << "note: " << note << "\n";
        renderer::HudContent content = hudFor(shown, toFrameX, toFrameY);
        photonMarker.draw(shown.frame, content);
        hud.draw(content, displayFrame.buffer());
        // One read-back a frame serves both the check (ids) and the PNG (colour).
        const renderer::DisplayImages images = renderer::readBack(displayFrame);
        pointerCheck.check(shown, images.ids, result);

        char file[64];
        std::snprintf(file, sizeof file, "/frame_%07lld.png", static_cast<long long>(shown.frame));
        image::writePng(request.outDir + file, images.colour);
        ++result.written;
    }
    out << "wrote " << result.written << " frames to " << request.outDir;
    if (result.skipped > 0) out << " (and not " << result.skipped << " the session skipped: never shown)";
    out << "; pointer cross-check on " << result.checked << " frames whose image is exact (" << result.eventsChecked
        << " of them logged clicks or shots, " << result.nearSilhouette << " skipped within " << kSilhouetteMarginPx
        << " px of a silhouette): the id read back disagrees on " << result.disagreed << "\n";
    for (const auto& d : result.disagreements) out << "  " << d << "\n";
    return result;
}

}  // namespace warplab::present
