#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <iostream>
#include <thread>

#include "commands.h"
#include "physics/target_scene.h"
#include "shooter/shooter_protocol.h"
#include "renderer/upconvert.h"
#include "renderer/window.h"
#include "scene/limits.h"

namespace warplab::app {
namespace {

// Where a flag's value stops making a frame worth looking at. The field of view, the pitch
// and the speed are the protocols' own limits (shooter/shooter_protocol.h), so a frame a
// protocol can ask for can always be rendered here, and the other way round.
// 100 turns either way: the camera holds yaw as float radians, and at 628 rad a float still
// resolves 0.0035 degrees, under a tenth of a pixel at 1080 lines over 60 degrees.
constexpr double kMaxYawDeg = 36000;
// 11.6 days of scene time, far past any session; at the fastest target (100 m/s) the 1e8 m
// it has travelled still fold into the hallway to 1e-8 m. Time starts at 0, when it spawns.
constexpr double kMaxSceneTimeS = 1e6;
constexpr double kMaxShowS = 3600;  // a preview window, not a kiosk

// Linear eye-space distance from window depth, for the false-colour depth image.
image::ImageF linearDepth(const image::ImageF& windowDepth, float nearPlane, float farPlane) {
    image::ImageF out = windowDepth;
    for (float& d : out.data) {
        const float ndc = 2.0f * d - 1.0f;
        d = 2.0f * nearPlane * farPlane / (farPlane + nearPlane - ndc * (farPlane - nearPlane));
    }
    return out;
}

image::ImageF idsAsFloat(const image::ImageU32& ids) {
    image::ImageF out;
    out.width = ids.width;
    out.height = ids.height;
    out.channels = 1;
    out.data.assign(ids.data.begin(), ids.data.end());
    return out;
}

// Everything `warplab render` was asked for, read and range-checked before any context or
// file is made.
struct RenderRequest {
    int width = 0, height = 0;
    double time = 0.0, fov = 0.0, speed = 0.0, yaw = 0.0, pitch = 0.0;
    double sourceTime = 0.0, sourceYaw = 0.0, sourcePitch = 0.0;
    std::optional<double> nextTime;  // unset: one source period after sourceTime
    std::uint64_t seed = 1;
    double show = 0.0;
    bool aimAtTarget = false;
    std::string out, depthPath, idsPath, velocityPath, rawPrefix, truthPath, errorPath;
    double guardBand = 0.0;
    int supersampling = 1;
    std::string methodName;  // "" = the conventional frame itself
};

RenderRequest readRequest(const ParsedArgs& args) {
    RenderRequest r;
    r.width = static_cast<int>(args.integer("width", 640, 1, scene::kMaxImageSize));
    r.height = static_cast<int>(args.integer("height", 360, 1, scene::kMaxImageSize));
    r.time = args.number("time", 0.0, 0.0, kMaxSceneTimeS);
    r.fov = args.number("fov", 60.0, protocol::kMinVerticalFovDeg, protocol::kMaxVerticalFovDeg);
    r.speed = args.number("speed", 2.0, 0.0, protocol::kMaxBaseSpeedMPerS);
    r.yaw = args.number("yaw", 0.0, -kMaxYawDeg, kMaxYawDeg);
    r.pitch = args.number("pitch", 0.0, -protocol::kMaxCameraPitchDeg, protocol::kMaxCameraPitchDeg);
    r.sourceTime = args.number("source-time", r.time, 0.0, kMaxSceneTimeS);
    r.sourceYaw = args.number("source-yaw", r.yaw, -kMaxYawDeg, kMaxYawDeg);
    r.sourcePitch = args.number("source-pitch", r.pitch, -protocol::kMaxCameraPitchDeg, protocol::kMaxCameraPitchDeg);
    // Without the flag it follows from the method's source rate, known once the method is made.
    const double nextTime = args.number("next-time", 0.0, 0.0, kMaxSceneTimeS);
    if (args.has("next-time")) r.nextTime = nextTime;
    r.seed = static_cast<std::uint64_t>(args.integer("seed", 1, 0, (1LL << 62)));
    r.show = args.number("show", 0.0, 0.0, kMaxShowS);
    r.aimAtTarget = args.flag("aim-at-target");
    r.out = args.path("out", "frame.png");
    r.depthPath = args.path("depth", "");
    r.idsPath = args.path("ids", "");
    r.velocityPath = args.path("velocity", "");
    r.rawPrefix = args.path("raw", "");
    r.truthPath = args.path("truth", "");
    r.errorPath = args.path("error", "");
    // As a study's warp condition renders its sources (protocol display.guard_band, .supersampling).
    const protocol::RenderSettings studyDefaults;
    r.guardBand = args.number("guard-band", studyDefaults.guardBand, 0.0, scene::kMaxGuardBand);
    r.supersampling = static_cast<int>(args.integer("ssaa", studyDefaults.supersampling, 1, scene::kMaxSupersampling));
    r.methodName = args.string("method", "");
    if (args.has("method") && r.methodName.find_first_not_of(" \t") == std::string::npos)
        throw UsageError("option --method of 'warplab render' needs a method name, got '" + r.methodName + "'");
    // An unknown name is a wrong command line (exit 2), found before a context is made.
    try {
        if (!r.methodName.empty()) renderer::requireMethod(r.methodName);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("option --method: ") + e.what());
    }
    if (r.methodName.empty() &&
        (args.has("source-time") || args.has("truth") || args.has("source-yaw") || args.has("source-pitch") ||
         args.has("next-time") || args.has("error") || args.has("guard-band")))
        throw UsageError(
            "options --source-time, --next-time, --source-yaw, --source-pitch, --truth, --error and --guard-band need "
            "--method");
    return r;
}

// A frame made by an upconversion method, and its pixels read back.
struct MethodFrame {
    std::unique_ptr<renderer::DisplayFrame> frame;
    renderer::DisplayImages images;
};

// The frame at --time made by the method from a source rendered at --source-time (and, for a
// method that needs one, the next source); writes --truth and --error, prints the PSNR.
MethodFrame makeWithMethod(const RenderRequest& r, const renderer::DataPaths& paths,
                           renderer::ConventionalRenderer& conventional, const scene::FrameDescription& frame,
                           const image::ImageRGBA8& truth,
                           const std::function<scene::FrameDescription(double, double, double)>& frameAt) {
    auto method = renderer::makeMethod(r.methodName, paths);
    const renderer::GuardBand band =
        method->info().takesGuardBand ? renderer::guardBandFor(r.width, r.height, r.guardBand) : renderer::GuardBand{};
    renderer::SourceFrame previous(r.width, r.height, band), next(r.width, r.height, band);
    renderer::renderSource(conventional, frameAt(r.sourceTime, r.sourceYaw, r.sourcePitch), previous);
    renderer::UpconversionInput input;
    input.displayTime = r.time;
    input.camera = frame.camera;
    input.scene = &frame.scene;
    input.previous = &previous;
    if (method->info().needsNext) {
        renderer::renderSource(
            conventional,
            frameAt(r.nextTime ? *r.nextTime : r.sourceTime + 1.0 / method->info().sourceRateHz, r.yaw, r.pitch), next);
        input.next = &next;
    }
    auto shown = std::make_unique<renderer::DisplayFrame>(r.width, r.height);
    method->produce(input, *shown);
    if (!r.truthPath.empty()) {
        image::writePng(r.truthPath, truth);
        std::cout << "wrote " << r.truthPath << " (ground truth at t=" << r.time << " s)\n";
    }
    renderer::DisplayImages display = renderer::readBack(*shown);
    std::cout << r.methodName << ": PSNR " << image::psnr(display.colour, truth) << " dB against ground truth\n";
    if (!r.errorPath.empty()) {
        // x4: the few-unit errors of a good warp show, a wrong surface saturates.
        image::writePng(r.errorPath, image::absoluteErrorImage(display.colour, truth, 4));
        std::cout << "wrote " << r.errorPath << " (|error| x4 against ground truth)\n";
    }
    return {std::move(shown), std::move(display)};
}

// --depth, --ids, --velocity and --raw: the frame's buffers as false colour and raw PFM.
void writeBuffers(const RenderRequest& r, const renderer::GBufferImages& images, const scene::CameraState& cam) {
    if (!r.depthPath.empty()) {
        // The ramp spans the nearest to the farthest geometry in view, not the whole frustum,
        // so the hallway's depth structure is visible; the far plane (sky) stays black.
        const image::ImageF distance = linearDepth(images.depth, cam.nearPlane, cam.farPlane);
        float farthest = cam.nearPlane * 2.0f;
        for (std::size_t i = 0; i < distance.data.size(); ++i)
            if (images.depth.data[i] < 1.0f) farthest = std::max(farthest, distance.data[i]);
        image::writePng(r.depthPath,
                        image::depthFalseColour(distance, cam.nearPlane, std::min(farthest * 1.001f, cam.farPlane)));
    }
    if (!r.idsPath.empty()) image::writePng(r.idsPath, image::idFalseColour(images.ids));
    if (!r.velocityPath.empty())
        image::writePng(r.velocityPath,
                        image::velocityFalseColour(images.velocity, static_cast<float>(std::max(r.speed, 1e-3))));
    if (!r.rawPrefix.empty()) {
        image::writePfm(r.rawPrefix + "-depth.pfm", images.depth);
        image::writePfm(r.rawPrefix + "-ids.pfm", idsAsFloat(images.ids));
        image::writePfm(r.rawPrefix + "-velocity.pfm", images.velocity);
    }
}

}  // namespace

int runRender(const ParsedArgs& args) {
    const RenderRequest r = readRequest(args);
    const auto backend = backendFrom(args, renderer::GlBackend::OSMesa);
    const renderer::DataPaths paths = dataPathsFrom(args);

    physics::TargetSceneConfig config;
    config.verticalFovDeg = static_cast<float>(r.fov);
    config.aspect = static_cast<double>(r.width) / r.height;
    config.targetSpeed = r.speed;
    config.seed = r.seed;
    const physics::TargetScene shooter(config);

    const auto frameAt = [&](double t, double yawDeg, double pitchDeg) {
        scene::FrameDescription f;
        f.camera = shooter.restingCamera();
        f.scene = shooter.snapshot(t);
        if (r.aimAtTarget) {
            const glm::vec3 toTarget = f.scene.objects.front().position - f.camera.eye;
            f.camera.yaw = std::atan2(toTarget.x, -toTarget.z);
            f.camera.pitch = std::asin(toTarget.y / glm::length(toTarget));
        } else {
            f.camera.yaw = static_cast<float>(yawDeg * M_PI / 180.0);
            f.camera.pitch = static_cast<float>(pitchDeg * M_PI / 180.0);
        }
        return f;
    };
    const scene::FrameDescription frame = frameAt(r.time, r.yaw, r.pitch);

    renderer::ContextOptions options;
    options.backend = backend;
    options.width = r.width;
    options.height = r.height;
    options.title = "warplab render";
    // --gl window shows the frame: a window with its context; otherwise a headless context.
    const std::unique_ptr<renderer::WindowContext> window =
        backend == renderer::GlBackend::Window ? renderer::createWindow(options) : nullptr;
    const std::unique_ptr<renderer::GlContext> headless = window ? nullptr : renderer::createContext(options);
    const renderer::GlContext& context = window ? static_cast<renderer::GlContext&>(*window) : *headless;
    renderer::ShadingOptions shading;
    shading.supersampling = r.supersampling;
    renderer::ConventionalRenderer conventional(paths, shading);
    renderer::GBuffer gbuffer(r.width, r.height);
    conventional.render(frame, gbuffer);
    renderer::GBufferImages images = renderer::readBack(gbuffer);
    const renderer::GBuffer* onScreen = &gbuffer;
    MethodFrame shown;
    if (!r.methodName.empty()) {
        shown = makeWithMethod(r, paths, conventional, frame, images.colour, frameAt);
        // The displayed frame replaces the conventional one in every output below.
        images.colour = shown.images.colour;
        images.ids = shown.images.ids;
        onScreen = &shown.frame->buffer();
    }

    if (window) {
        // The window shows the G-buffer's colour; what we save is the window's own pixels.
        const int dw = window->drawableWidth(), dh = window->drawableHeight();
        renderer::blitToDefaultFramebuffer(*onScreen, dw, dh);
        image::writePng(r.out, renderer::readDefaultFramebuffer(dw, dh));
        window->swapBuffers();
        const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(r.show);
        while (std::chrono::steady_clock::now() < until && window->pumpEvents())
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
    } else {
        image::writePng(r.out, images.colour);
    }
    std::cout << "wrote " << r.out << " (" << r.width << "x" << r.height << ", t=" << r.time << " s, "
              << context.info().renderer << ")\n";
    writeBuffers(r, images, frame.camera);
    return 0;
}

// The command's options, beside the code that reads them (defaults and limits as it uses
// them, so that --help cannot tell another story).
Command renderCommand() {
    const protocol::RenderSettings study;
    return {
        {"render",
         "Render one frame of the shooter scene headlessly and write it as PNG; optionally the\n"
         "depth, object-id and velocity buffers as false-colour PNGs and as raw PFM images.",
         "warplab render [--time T] [--out frame.png] [options]",
         {
             {"time", "SECONDS", "scene time of the frame, 0..1e6", "0"},
             {"yaw", "DEGREES", "camera yaw, positive turns right, -36000..36000", "0"},
             {"pitch", "DEGREES",
              "camera pitch, positive looks up, " + range(-protocol::kMaxCameraPitchDeg, protocol::kMaxCameraPitchDeg),
              "0"},
             {"aim-at-target", "", "turn the camera to the target's centre (overrides --yaw/--pitch)", ""},
             {"fov", "DEGREES",
              "vertical field of view, " + range(protocol::kMinVerticalFovDeg, protocol::kMaxVerticalFovDeg) +
                  " (as in protocols)",
              "60"},
             {"width", "PIXELS", "image width, " + range(1, scene::kMaxImageSize), "640"},
             {"height", "PIXELS", "image height, " + range(1, scene::kMaxImageSize), "360"},
             {"seed", "N", "target spawn seed", "1"},
             {"speed", "M/S", "target speed, " + range(0, protocol::kMaxBaseSpeedMPerS), "2"},
             {"out", "PATH", "colour image (PNG)", "frame.png"},
             {"depth", "PATH", "false-colour depth image (PNG)", ""},
             {"ids", "PATH", "false-colour object-id image (PNG)", ""},
             {"velocity", "PATH", "false-colour velocity image (PNG)", ""},
             {"raw", "PREFIX", "also write PREFIX-depth.pfm (window depth), PREFIX-ids.pfm, PREFIX-velocity.pfm", ""},
             {"show", "SECONDS", "with --gl window: keep the window open this long, 0..3600", "0"},
             {"method", "NAME", "make the frame with an upconversion method (e.g. warp-sparse8) instead", ""},
             {"source-time", "SECONDS", "with --method: when the source frame was rendered, 0..1e6", "--time"},
             {"source-yaw", "DEGREES", "with --method: the source frame's camera yaw", "--yaw"},
             {"source-pitch", "DEGREES", "with --method: the source frame's camera pitch", "--pitch"},
             {"next-time", "SECONDS", "with --method blend: the next source frame's time, 0..1e6", "source + 1/15 s"},
             {"truth", "PATH", "with --method: also write the ground truth (conventional at --time)", ""},
             {"error", "PATH", "with --method: also write |method - ground truth| x4 as a grey image", ""},
             {"guard-band", "FRACTION",
              "with --method: a warp's sources reach this much further each side, " + range(0, scene::kMaxGuardBand),
              shown(study.guardBand)},
             {"ssaa", "N",
              "supersample every conventional frame NxN (antialiasing), " + range(1, scene::kMaxSupersampling),
              shown(study.supersampling)},
             glOption("osmesa"),
             dataDirOption(),
         }},
        &runRender};
}

}  // namespace warplab::app
