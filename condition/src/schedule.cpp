#include "condition/schedule.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace warplab::condition {
namespace {

// The one table of modes. A new preset is one entry here: protocols, export's
// modes.csv and the analysis take it from this table, and tests/game/test_modes.cpp asks the
// README's latency table and docs/protocol.md to describe it. The nine published presets come
// first, in this order (the test pins it); new ones go after them.
std::vector<ModeSpec> makeModes() {
    std::vector<ModeSpec> modes;
    for (int rate : {15, 30, 60, 120}) {
        ModeSpec m;
        m.id = "conv" + std::to_string(rate);
        m.description = "conventional rendering at " + std::to_string(rate) + " Hz, each frame held until the next";
        m.renderRateHz = rate;
        modes.push_back(m);
    }
    for (int lag : {50, 100, 200}) {
        ModeSpec m;
        m.id = "lag" + std::to_string(lag);
        m.description = "conventional 60 Hz, each frame shown " + std::to_string(lag) + " ms after it was rendered";
        m.renderRateHz = 60;
        m.lagMs = lag;
        modes.push_back(m);
    }
    ModeSpec warp;
    warp.id = "warp15to120";
    warp.description = "rendered at 15 Hz, the frames between warped from the latest with the current camera";
    warp.renderRateHz = 15;
    warp.upconversion = Upconversion::Warp;
    warp.upconvertedRateHz = 120;
    warp.method = "warp-sparse8";
    modes.push_back(warp);
    ModeSpec bireproj;
    bireproj.id = "bireproj15to60";
    bireproj.description =
        "I-frames rendered at 15 Hz, B-frames at 60 Hz interpolated between the I-frames before and after";
    bireproj.renderRateHz = 15;
    bireproj.upconversion = Upconversion::Bidirectional;
    bireproj.upconvertedRateHz = 60;
    bireproj.method = "bireproj";  // image-based, m = 3, dual and latest-frame initialisation
    modes.push_back(bireproj);
    return modes;
}

const std::vector<ModeSpec>& modes() {
    static const std::vector<ModeSpec> list = makeModes();
    return list;
}

// A rate or a duration for a message: "60", "59.94", not "60.000000".
std::string number(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

std::int64_t framesPer(double refreshHz, double rateHz, const std::string& mode) {
    const double ratio = refreshHz / rateHz;
    const auto whole = static_cast<std::int64_t>(std::llround(ratio));
    if (whole < 1 || std::abs(ratio - static_cast<double>(whole)) > 1e-9)
        throw std::invalid_argument("mode " + mode + " needs a display refresh that is a whole multiple of " +
                                    std::to_string(static_cast<int>(rateHz)) + " Hz, not " + number(refreshHz) + " Hz");
    return whole;
}

// Floor division and modulo that stay right for negative frame indices.
std::int64_t floorTo(std::int64_t k, std::int64_t period) {
    const std::int64_t r = ((k % period) + period) % period;
    return k - r;
}

}  // namespace

const char* frameKindName(FrameKind kind) {
    switch (kind) {
        case FrameKind::Rendered: return "rendered";
        case FrameKind::Held: return "held";
        case FrameKind::Warped: return "warped";
        case FrameKind::Interpolated: return "interpolated";
    }
    return "?";
}

const char* upconversionName(Upconversion upconversion) {
    switch (upconversion) {
        case Upconversion::None: return "none";
        case Upconversion::Warp: return "warp";
        case Upconversion::Bidirectional: return "bidirectional";
    }
    return "?";
}

std::vector<std::string> modeIds() {
    std::vector<std::string> ids;
    for (const auto& m : modes()) ids.push_back(m.id);
    return ids;
}

const ModeSpec& modeSpec(const std::string& id) {
    for (const auto& m : modes())
        if (m.id == id) return m;
    std::string known;
    for (const auto& m : modes()) known += (known.empty() ? "" : ", ") + m.id;
    throw std::invalid_argument("unknown mode '" + id + "' (known: " + known + ")");
}

std::string checkMode(const std::string& id, double refreshHz) {
    try {
        ModeSchedule(modeSpec(id), refreshHz);
        return "";
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
}

ModeSchedule::ModeSchedule(const ModeSpec& mode, double refreshHz) : mode_(mode), refreshHz_(refreshHz) {
    if (!(refreshHz > 0.0) || !std::isfinite(refreshHz))
        throw std::invalid_argument("display refresh must be a positive number of Hz");
    renderPeriod_ = framesPer(refreshHz, mode.renderRateHz, mode.id);
    const double lagFrames = mode.lagMs * refreshHz / 1000.0;
    lagFrames_ = std::llround(lagFrames);
    if (std::abs(lagFrames - static_cast<double>(lagFrames_)) > 1e-9)
        throw std::invalid_argument("mode " + mode.id + ": a lag of " + number(mode.lagMs) +
                                    " ms is not a whole number of frames at " + number(refreshHz) + " Hz");
    bPeriod_ =
        mode.upconversion == Upconversion::Bidirectional ? framesPer(refreshHz, mode.upconvertedRateHz, mode.id) : 1;
    if (mode.upconversion == Upconversion::Warp) framesPer(refreshHz, mode.upconvertedRateHz, mode.id);
}

ScheduledFrame ModeSchedule::frame(std::int64_t k) const {
    ScheduledFrame f;
    f.index = k;
    f.displayTime = static_cast<double>(k) / refreshHz_;
    f.rendersNow = floorTo(k, renderPeriod_) == k;
    auto time = [&](std::int64_t frame) { return static_cast<double>(frame) / refreshHz_; };

    switch (mode_.upconversion) {
        case Upconversion::None: {
            // The frame rendered lagFrames_ ago (rounded down to the render cadence) is on screen.
            const std::int64_t shown = floorTo(k - lagFrames_, renderPeriod_);
            f.sourceIndex = shown;
            f.kind = shown == k - lagFrames_ ? FrameKind::Rendered : FrameKind::Held;
            f.cameraTime = f.sceneTime = f.worldSampleTime = time(shown);
            f.samplesInput = f.rendersNow;
            break;
        }
        case Upconversion::Warp: {
            // The latest source, warped to this very instant: the camera is read every frame
            // (view latency) and pixels move by their velocity (scene latency).
            f.sourceIndex = floorTo(k, renderPeriod_);
            f.kind = f.rendersNow ? FrameKind::Rendered : FrameKind::Warped;
            f.cameraTime = f.sceneTime = f.displayTime;
            f.worldSampleTime = time(f.sourceIndex);
            f.samplesInput = true;
            break;
        }
        case Upconversion::Bidirectional: {
            // A B-frame between two I-frames can only be made once the later one exists, so the
            // display runs one I-frame period behind, at the B-frame cadence (seed 000 section 7).
            const std::int64_t depicted = floorTo(k, bPeriod_) - renderPeriod_;
            f.sourceIndex = floorTo(depicted, renderPeriod_);
            const bool onIFrame = f.sourceIndex == depicted;
            f.nextSourceIndex = onIFrame ? -1 : f.sourceIndex + renderPeriod_;
            const bool newFrame = floorTo(k, bPeriod_) == k;
            f.kind = !newFrame ? FrameKind::Held : (onIFrame ? FrameKind::Rendered : FrameKind::Interpolated);
            f.cameraTime = f.sceneTime = time(depicted);
            f.worldSampleTime = time(onIFrame ? f.sourceIndex : f.nextSourceIndex);
            f.samplesInput = newFrame;
            break;
        }
    }
    return f;
}

template <typename Depicted>
double ModeSchedule::firstShowing(double tau, Depicted depicted) const {
    // Display frames are at k / refresh; the first candidate is the first frame at or after tau.
    auto k = static_cast<std::int64_t>(std::ceil(tau * refreshHz_ - 1e-9));
    for (std::int64_t n = 0; n < 1000000; ++n, ++k) {
        const ScheduledFrame f = frame(k);
        if (depicted(f) >= tau - 1e-12) return f.displayTime - tau;
    }
    throw std::logic_error("ModeSchedule: no frame ever shows the step");
}

double ModeSchedule::viewLatency(double tau) const {
    return firstShowing(tau, [](const ScheduledFrame& f) { return f.cameraTime; });
}
double ModeSchedule::sceneLatency(double tau) const {
    return firstShowing(tau, [](const ScheduledFrame& f) { return f.worldSampleTime; });
}

}  // namespace warplab::condition
