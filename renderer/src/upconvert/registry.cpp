// The one list of upconversion methods. A new method registers here and is then available to
// the bench (--methods) and, through its name, to the study conditions.
#include <cmath>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "gbuffer_gl.h"
#include "renderer/upconvert.h"
#include "upconvert/bireproj.h"
#include "upconvert/frameless.h"
#include "upconvert/rotation.h"
#include "upconvert/scene_assisted.h"
#include "upconvert/simple_methods.h"
#include "upconvert/spatiotemporal.h"
#include "upconvert/warp.h"
#include "upconvert/warp_search.h"
#include "upconvert/warp_splat.h"
#include "gl/api.h"
#include "scene/camera.h"
#include "scene/limits.h"

namespace warplab::renderer {
namespace {

// `make` is handed the entry's name, so that a method named by its settings is named once.
using Name = const std::string&;
struct Entry {
    const char* name;
    std::function<std::unique_ptr<UpconversionMethod>(const DataPaths&, Name)> make;
    bool needsCompute = false;  // OpenGL 4.3 compute shaders
    const char* fallback = "";  // what a study shows instead where the context cannot run it
};

WarpSettings sparse(int patchSize) {
    WarpSettings s;
    s.patchSize = patchSize;
    return s;
}

// Motion blur from B-frames: ten per I-frame interval, as seed 000's Figure 10.
constexpr int kBlurSamplesPerInterval = 10;

BireprojSettings bireproj(int iterations, bool dual, bool latest) {
    BireprojSettings s;
    s.iterations = iterations;
    s.dualInit = dual;
    s.latestInit = latest;
    return s;
}

// The lagged frame late warp is meant to rescue (Kim et al., HPG 2020): rendered at 60 Hz and
// shown five frames (83.3 ms) later, the delay of a deep render queue.
constexpr double kLateRateHz = 60.0;
constexpr double kLateLagS = 5.0 / kLateRateHz;

// A method shown a queued, late source: `inner` makes the frame from whatever source it is
// handed, and the lag only changes which one that is (the bench's choice, MethodInfo::sourceLagS),
// so the late variants are the very passes of hold, rotation and warp, measured beside them.
class LateSource final : public UpconversionMethod {
public:
    LateSource(std::unique_ptr<UpconversionMethod> inner, Name name, const std::string& description)
        : inner_(std::move(inner)), info_(inner_->info()) {
        info_.name = name;
        info_.description = description;
        info_.sourceRateHz = kLateRateHz;
        info_.sourceLagS = kLateLagS;
    }
    const MethodInfo& info() const override { return info_; }
    void produce(const UpconversionInput& input, DisplayFrame& out) override {
        // Checked here too, so that a wrong source is reported under this method's name.
        if (input.previous == nullptr) throw std::invalid_argument(info_.name + ": no source frame");
        checkSourceSize(*input.previous, out, info_);
        inner_->produce(input, out);
    }
    void prepare(const UpconversionInput& input) override { inner_->prepare(input); }
    double lastTriangleCount() override { return inner_->lastTriangleCount(); }

private:
    std::unique_ptr<UpconversionMethod> inner_;
    MethodInfo info_;
};

std::unique_ptr<UpconversionMethod> late(std::unique_ptr<UpconversionMethod> inner, Name name,
                                         const std::string& what) {
    return std::make_unique<LateSource>(std::move(inner), name,
                                        what + ", from 60 Hz frames with 5 frames (83.3 ms) of queue delay");
}

const std::vector<Entry>& registry() {
    static const std::vector<Entry> entries = {
        {"hold15", [](const DataPaths& p, Name) { return makeHold(p, 15.0); }},
        {"hold30", [](const DataPaths& p, Name) { return makeHold(p, 30.0); }},
        {"hold60", [](const DataPaths& p, Name) { return makeHold(p, 60.0); }},
        {"hold120", [](const DataPaths& p, Name) { return makeHold(p, 120.0); }},
        {"blend", [](const DataPaths& p, Name) { return makeBlend(p); }},
        {"warp-full", [](const DataPaths& p, Name name) { return makeWarp(p, name, {}); }},
        {"warp-nofix",
         [](const DataPaths& p, Name name) {
             WarpSettings s;
             s.disocclusionFix = false;
             return makeWarp(p, name, s);
         }},
        {"warp-sparse4", [](const DataPaths& p, Name name) { return makeWarp(p, name, sparse(4)); }},
        {"warp-sparse8", [](const DataPaths& p, Name name) { return makeWarp(p, name, sparse(8)); }},
        {"warp-sparse16", [](const DataPaths& p, Name name) { return makeWarp(p, name, sparse(16)); }},
        {"warp-search", [](const DataPaths& p, Name name) { return makeWarpSearch(p, name, {}); }},
        {"warp-splat", [](const DataPaths& p, Name name) { return makeWarpSplat(p, name, {}); }, true, "warp-sparse8"},
        {"bireproj", [](const DataPaths& p, Name name) { return makeBireproj(p, name, {}); }},
        {"bireproj-m1", [](const DataPaths& p, Name name) { return makeBireproj(p, name, bireproj(1, true, true)); }},
        {"bireproj-m2", [](const DataPaths& p, Name name) { return makeBireproj(p, name, bireproj(2, true, true)); }},
        {"bireproj-m4", [](const DataPaths& p, Name name) { return makeBireproj(p, name, bireproj(4, true, true)); }},
        {"bireproj-nodual",
         [](const DataPaths& p, Name name) { return makeBireproj(p, name, bireproj(3, false, true)); }},
        {"bireproj-nolatest",
         [](const DataPaths& p, Name name) { return makeBireproj(p, name, bireproj(3, true, false)); }},
        {"bireproj-noinit",
         [](const DataPaths& p, Name name) { return makeBireproj(p, name, bireproj(3, false, false)); }},
        {"scene-assisted", [](const DataPaths& p, Name) { return makeSceneAssisted(p); }},
        {"bireproj-blur",
         [](const DataPaths& p, Name name) { return makeBireprojBlur(p, name, {}, kBlurSamplesPerInterval); }},
        {"rotation", [](const DataPaths& p, Name) { return makeRotation(p); }},
        {"late-hold",
         [](const DataPaths& p, Name name) {
             return late(makeHold(p, kLateRateHz), name, "the lagged frame held, no late warp");
         }},
        {"late-rotation",
         [](const DataPaths& p, Name name) {
             return late(makeRotation(p), name, "late warp by camera rotation to the displayed camera, depth ignored");
         }},
        {"late-depth",
         [](const DataPaths& p, Name name) {
             return late(makeWarp(p, name, sparse(8)), name,
                         "late warp with depth and velocities (warp-sparse8) to the displayed instant");
         }},
        // Equal shading budgets spent in space and time (seed 001): a quarter or an eighth of
        // the pixels shaded every displayed frame.
        {"stu-4",
         [](const DataPaths& p, Name name) {
             return makeSpatioTemporal(p, name, {2, 2});
         }},
        {"stu-8",
         [](const DataPaths& p, Name name) {
             return makeSpatioTemporal(p, name, {4, 2});
         }},
        // The same eighth placed where colour varies (seed 002).
        {"frameless-8", [](const DataPaths& p, Name name) { return makeFrameless(p, name, 8); }},
    };
    return entries;
}

// Shortest text of a limit for a message: 0.5, not 0.500000.
std::string formatted(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

const Entry& entryNamed(const std::string& name) {
    for (const auto& e : registry())
        if (name == e.name) return e;
    std::string known;
    for (const auto& e : registry()) known += std::string(known.empty() ? "" : ", ") + e.name;
    throw std::invalid_argument("unknown method '" + name + "' (known: " + known + ")");
}

}  // namespace

std::vector<std::string> methodNames() {
    std::vector<std::string> names;
    for (const auto& e : registry()) names.emplace_back(e.name);
    return names;
}

void requireMethod(const std::string& name) { entryNamed(name); }

std::unique_ptr<UpconversionMethod> makeMethod(const std::string& name, const DataPaths& paths) {
    const Entry& e = entryNamed(name);
    const std::string why = methodUnavailable(name);
    if (!why.empty()) throw std::runtime_error(why);
    return e.make(paths, e.name);
}

std::string methodUnavailable(const std::string& name) {
    const Entry& e = entryNamed(name);
    std::string why;
    if (e.needsCompute && !gl::hasCompute(&why)) return name + " needs OpenGL 4.3 compute shaders; " + why;
    return "";
}

std::string methodFallback(const std::string& name) { return entryNamed(name).fallback; }

GuardBand guardBandFor(int width, int height, double fraction) {
    if (!(fraction >= 0.0 && fraction <= scene::kMaxGuardBand))
        throw std::invalid_argument("guard band " + std::to_string(fraction) + " is outside 0.." +
                                    formatted(scene::kMaxGuardBand) + " of the displayed size");
    return {static_cast<int>(std::lround(fraction * width)), static_cast<int>(std::lround(fraction * height))};
}

void renderSource(ConventionalRenderer& renderer, const scene::FrameDescription& frame, SourceFrame& source,
                  const scene::FrameDescription* flowTo) {
    static std::uint64_t renders = 0;  // GL work is single-threaded: one context per process
    source.depicts = frame;
    const int displayedHeight = source.gbuffer.height() - 2 * source.band.y;
    if (source.band.y > 0) source.depicts.camera = scene::widenedByRows(frame.camera, displayedHeight, source.band.y);
    if (flowTo != nullptr)
        renderer.render(source.depicts, source.gbuffer, *flowTo);
    else
        renderer.render(source.depicts, source.gbuffer);
    source.serial = ++renders;
}

void checkSourceSize(const SourceFrame& source, const DisplayFrame& out, const MethodInfo& info) {
    const GuardBand band = source.band;
    if (!info.acceptsGuardBand && !(band == GuardBand{}))
        throw std::invalid_argument(info.name + " does not take sources with a guard band");
    if (source.gbuffer.width() != out.width() + 2 * band.x || source.gbuffer.height() != out.height() + 2 * band.y)
        throw std::invalid_argument(info.name + ": source and display sizes differ");
}

DisplayImages readShown(const SourceFrame& source) {
    if (!(source.band == GuardBand{}))
        throw std::invalid_argument("readShown: a source with a guard band shows only its inside");
    const auto& g = source.gbuffer.impl();
    return {readColourAttachment(g), readIdAttachment(g), image::ImageF{}};
}

DisplayImages readBack(const DisplayFrame& frame, bool correspondence) {
    const auto& g = frame.buffer().impl();
    return {readColourAttachment(g), readIdAttachment(g),
            correspondence ? readVectorAttachment(g, 4) : image::ImageF{}};
}

}  // namespace warplab::renderer
