#include "app/replay_render.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

#include "game/shooter_game.h"
#include "physics/ray.h"
#include "protocol/session_store.h"
#include "protocol/shooter_protocol.h"
#include "renderer/hud.h"
#include "renderer/upconvert.h"
#include "scene/camera.h"

namespace warplab::app {

void renderReplay(const ReplayRender& request, const renderer::DataPaths& paths, renderer::GlBackend backend,
                  std::ostream& out) {
    const protocol::SessionData data = protocol::readSession(request.sessionPath);
    const auto protocol = protocol::parseShooterProtocol(data.header.protocolJson, request.sessionPath);
    const int width = request.width > 0 ? request.width : data.header.displayWidth;
    const int height = request.height > 0 ? request.height : data.header.displayHeight;
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
    renderer::DisplayFrame display(width, height);
    std::map<std::int64_t, std::unique_ptr<renderer::SourceFrame>> sources;  // by session frame
    bool saidBlend = false;
    int written = 0, checked = 0, agreed = 0;

    // The aspect the session was scored with: the target plane must be the same one.
    game::ShooterGame game(protocol, data.header.seed,
                           static_cast<double>(data.header.displayWidth) / data.header.displayHeight);
    for (const auto& in : data.inputs) {
        if (in.frame > request.lastFrame) break;
        const game::ShownFrame shown = game.step({in.mouseDx, in.mouseDy, in.buttons, in.keys});
        game.takeEvents();
        // Sources are needed from before the range too (held, lagged and warped frames); none
        // older than what the frame on screen is made from will be needed again.
        if (shown.rendersNow) {
            auto source = std::make_unique<renderer::SourceFrame>(width, height);
            source->depicts = shown.render;
            conventional.render(shown.render, source->gbuffer);
            sources[shown.frame] = std::move(source);
        }
        while (!sources.empty() && sources.begin()->first < shown.sourceFrame) sources.erase(sources.begin());
        if (shown.frame < request.firstFrame) continue;

        auto it = sources.find(shown.sourceFrame);
        if (it == sources.end()) {
            // Lag modes open with frames queued before the mode started: the hallway as it was.
            auto before = std::make_unique<renderer::SourceFrame>(width, height);
            before->depicts = {shown.camera, {}};
            conventional.render(before->depicts, before->gbuffer);
            it = sources.emplace(shown.sourceFrame, std::move(before)).first;
        }
        renderer::UpconversionInput input;
        input.displayTime = shown.scene.time;  // the instant the frame depicts (frozen frames: the shot's)
        input.camera = shown.camera;
        input.previous = it->second.get();
        std::string name = "hold120";
        if (shown.schedule.kind == game::FrameKind::Warped) name = game::modeSpec(shown.mode).method;
        if (shown.schedule.kind == game::FrameKind::Interpolated) {
            name = "blend";
            const auto next = sources.find(shown.nextSourceFrame);
            input.next = next == sources.end() ? it->second.get() : next->second.get();
            if (!saidBlend)
                out << "replay: interpolated frames are drawn with blend until the bidirectional reprojection "
                       "renderer exists\n";
            saidBlend = true;
        }
        method(name).produce(input, display);
        if (!shown.frozen && shown.schedule.kind == game::FrameKind::Rendered && shown.sourceFrame == shown.frame) {
            // Cross-check the analytic scoring: is the target under the reticle?
            const bool idSaysTarget =
                renderer::readBack(display).ids.at(width / 2, height / 2) == scene::kIdTarget;
            bool analytic = false;
            if (!shown.scene.objects.empty())
                analytic = physics::raySphereHit(glm::dvec3(shown.camera.eye),
                                                 glm::dvec3(scene::forwardDirection(shown.camera.yaw, shown.camera.pitch)),
                                                 glm::dvec3(shown.scene.objects.front().position),
                                                 protocol.targetRadius)
                               .has_value();
            ++checked;
            agreed += idSaysTarget == analytic;
        }
        renderer::HudContent content;
        content.banner = shown.banner;
        content.bannerGood = shown.banner == "HIT";
        content.status = shown.phaseText;
        hud.draw(content, display.buffer());

        char file[64];
        std::snprintf(file, sizeof file, "/frame_%07lld.png", static_cast<long long>(shown.frame));
        renderer::writePng(request.outDir + file, renderer::readBack(display).colour);
        ++written;
    }
    out << "wrote " << written << " frames to " << request.outDir << "; reticle cross-check on " << checked
        << " rendered frames: the id read back agrees with the analytic outcome on " << agreed << "\n";
}

}  // namespace warplab::app
