#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <thread>

#include "commands.h"
#include "game/shooter_scene.h"
#include "protocol/shooter_protocol.h"
#include "renderer/upconvert.h"
#include "renderer/window.h"
#include "scene/limits.h"

namespace warplab::app {
namespace {

// Where a flag's value stops making a frame worth looking at. The field of view, the pitch
// and the speed are the protocols' own limits (protocol/shooter_protocol.h), so a frame a
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

}  // namespace

int runRender(const ParsedArgs& args) {
    // Every flag is read, and refused with its range, before any context or file is made.
    const int width = static_cast<int>(args.integer("width", 640, 1, scene::kMaxImageSize));
    const int height = static_cast<int>(args.integer("height", 360, 1, scene::kMaxImageSize));
    const double time = args.number("time", 0.0, 0.0, kMaxSceneTimeS);
    const double fov = args.number("fov", 60.0, protocol::kMinVerticalFovDeg, protocol::kMaxVerticalFovDeg);
    const double speed = args.number("speed", 2.0, 0.0, protocol::kMaxBaseSpeedMPerS);
    const double yaw = args.number("yaw", 0.0, -kMaxYawDeg, kMaxYawDeg);
    const double pitch = args.number("pitch", 0.0, -protocol::kMaxCameraPitchDeg, protocol::kMaxCameraPitchDeg);
    const double sourceTime = args.number("source-time", time, 0.0, kMaxSceneTimeS);
    const double sourceYaw = args.number("source-yaw", yaw, -kMaxYawDeg, kMaxYawDeg);
    const double sourcePitch =
        args.number("source-pitch", pitch, -protocol::kMaxCameraPitchDeg, protocol::kMaxCameraPitchDeg);
    // Without the flag it follows from the method's source rate, known once the method is made.
    const double nextTime = args.number("next-time", 0.0, 0.0, kMaxSceneTimeS);
    const auto seed = static_cast<std::uint64_t>(args.integer("seed", 1, 0, (1LL << 62)));
    const double show = args.number("show", 0.0, 0.0, kMaxShowS);
    const std::string out = args.path("out", "frame.png");
    const std::string depthPath = args.path("depth", ""), idsPath = args.path("ids", "");
    const std::string velocityPath = args.path("velocity", ""), rawPrefix = args.path("raw", "");
    const std::string truthPath = args.path("truth", ""), errorPath = args.path("error", "");
    // As a study's warp mode renders its sources (protocol display.guard_band, .supersampling).
    const protocol::RenderSettings studyDefaults;
    const double guardBand = args.number("guard-band", studyDefaults.guardBand, 0.0, scene::kMaxGuardBand);
    const int supersampling =
        static_cast<int>(args.integer("ssaa", studyDefaults.supersampling, 1, scene::kMaxSupersampling));
    const std::string methodName = args.string("method", "");
    if (args.has("method") && methodName.find_first_not_of(" \t") == std::string::npos)
        throw UsageError("option --method of 'warplab render' needs a method name, got '" + methodName + "'");
    if (methodName.empty() && (args.has("source-time") || args.has("truth") || args.has("source-yaw") ||
                               args.has("source-pitch") || args.has("next-time") || args.has("error") ||
                               args.has("guard-band")))
        throw UsageError(
            "options --source-time, --next-time, --source-yaw, --source-pitch, --truth, --error and --guard-band need "
            "--method");
    const auto backend = backendFrom(args, renderer::GlBackend::OSMesa);
    const renderer::DataPaths paths = dataPathsFrom(args);

    game::ShooterSceneConfig config;
    config.verticalFovDeg = static_cast<float>(fov);
    config.aspect = static_cast<double>(width) / height;
    config.targetSpeed = speed;
    config.seed = seed;
    const game::ShooterScene shooter(config);

    auto frameAt = [&](double t, double yawDeg, double pitchDeg) {
        scene::FrameDescription f;
        f.camera = shooter.restingCamera();
        f.scene = shooter.snapshot(t);
        if (args.flag("aim-at-target")) {
            const glm::vec3 toTarget = f.scene.objects.front().position - f.camera.eye;
            f.camera.yaw = std::atan2(toTarget.x, -toTarget.z);
            f.camera.pitch = std::asin(toTarget.y / glm::length(toTarget));
        } else {
            f.camera.yaw = static_cast<float>(yawDeg * M_PI / 180.0);
            f.camera.pitch = static_cast<float>(pitchDeg * M_PI / 180.0);
        }
        return f;
    };
    const scene::FrameDescription frame = frameAt(time, yaw, pitch);

    renderer::ContextOptions options;
    options.backend = backend;
    options.width = width;
    options.height = height;
    options.title = "warplab render";
    // --gl window shows the frame: a window with its context; otherwise a headless context.
    const std::unique_ptr<renderer::WindowContext> window =
        backend == renderer::GlBackend::Window ? renderer::createWindow(options) : nullptr;
    const std::unique_ptr<renderer::GlContext> headless = window ? nullptr : renderer::createContext(options);
    const renderer::GlContext& context = window ? static_cast<renderer::GlContext&>(*window) : *headless;
    renderer::ShadingOptions shading;
    shading.supersampling = supersampling;
    renderer::ConventionalRenderer conventional(paths, shading);
    renderer::GBuffer gbuffer(width, height);
    conventional.render(frame, gbuffer);
    renderer::GBufferImages images = renderer::readBack(gbuffer);
    const renderer::GBuffer* onScreen = &gbuffer;
    std::unique_ptr<renderer::DisplayFrame> shown;
    if (!methodName.empty()) {
        // Upconversion: the frame at --time is made by a method from a source rendered at --source-time.
        auto method = renderer::makeMethod(methodName, paths);
        const renderer::GuardBand band = method->info().takesGuardBand
                                             ? renderer::guardBandFor(width, height, guardBand)
                                             : renderer::GuardBand{};
        renderer::SourceFrame previous(width, height, band), next(width, height, band);
        renderer::renderSource(conventional, frameAt(sourceTime, sourceYaw, sourcePitch), previous);
        renderer::UpconversionInput input;
        input.displayTime = time;
        input.camera = frame.camera;
        input.scene = &frame.scene;
        input.previous = &previous;
        if (method->info().needsNext) {
            renderer::renderSource(
                conventional,
                frameAt(args.has("next-time") ? nextTime : sourceTime + 1.0 / method->info().sourceRateHz, yaw, pitch),
                next);
            input.next = &next;
        }
        shown = std::make_unique<renderer::DisplayFrame>(width, height);
        method->produce(input, *shown);
        if (!truthPath.empty()) {
            image::writePng(truthPath, images.colour);
            std::cout << "wrote " << truthPath << " (ground truth at t=" << time << " s)\n";
        }
        // The displayed frame replaces the conventional one in every output below.
        const renderer::DisplayImages display = renderer::readBack(*shown);
        std::cout << methodName << ": PSNR " << image::psnr(display.colour, images.colour) << " dB against ground truth\n";
        if (!errorPath.empty()) {
            // x4: the few-unit errors of a good warp show, a wrong surface saturates.
            image::writePng(errorPath, image::absoluteErrorImage(display.colour, images.colour, 4));
            std::cout << "wrote " << errorPath << " (|error| x4 against ground truth)\n";
        }
        images.colour = display.colour;
        images.ids = display.ids;
        onScreen = &shown->buffer();
    }

    if (window) {
        // The window shows the G-buffer's colour; what we save is the window's own pixels.
        const int dw = window->drawableWidth(), dh = window->drawableHeight();
        renderer::blitToDefaultFramebuffer(*onScreen, dw, dh);
        image::writePng(out, renderer::readDefaultFramebuffer(dw, dh));
        window->swapBuffers();
        const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(show);
        while (std::chrono::steady_clock::now() < until && window->pumpEvents())
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
    } else {
        image::writePng(out, images.colour);
    }
    std::cout << "wrote " << out << " (" << width << "x" << height << ", t=" << time << " s, "
              << context.info().renderer << ")\n";

    const scene::CameraState& cam = frame.camera;
    if (!depthPath.empty()) {
        // The ramp spans the nearest to the farthest geometry in view, not the whole frustum,
        // so the hallway's depth structure is visible; the far plane (sky) stays black.
        const image::ImageF distance = linearDepth(images.depth, cam.nearPlane, cam.farPlane);
        float farthest = cam.nearPlane * 2.0f;
        for (std::size_t i = 0; i < distance.data.size(); ++i)
            if (images.depth.data[i] < 1.0f) farthest = std::max(farthest, distance.data[i]);
        image::writePng(depthPath,
                           image::depthFalseColour(distance, cam.nearPlane, std::min(farthest * 1.001f, cam.farPlane)));
    }
    if (!idsPath.empty()) image::writePng(idsPath, image::idFalseColour(images.ids));
    if (!velocityPath.empty())
        image::writePng(velocityPath,
                           image::velocityFalseColour(images.velocity, static_cast<float>(std::max(speed, 1e-3))));
    if (!rawPrefix.empty()) {
        image::writePfm(rawPrefix + "-depth.pfm", images.depth);
        image::writePfm(rawPrefix + "-ids.pfm", idsAsFloat(images.ids));
        image::writePfm(rawPrefix + "-velocity.pfm", images.velocity);
    }
    return 0;
}

}  // namespace warplab::app
