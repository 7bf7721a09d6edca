#include "condition/condition.h"

#include "condition/pacing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace warplab::condition {
namespace {

Condition conventional(int rate) {
    Condition c;
    c.name = "conv" + std::to_string(rate);
    c.description = "conventional rendering at " + std::to_string(rate) + " Hz, each frame held until the next";
    c.renderHz = rate;
    return c;
}

// The one table of presets: the nine conditions of the two papers, as parts. Protocols, the
// README's latency table and docs/protocol.md follow it (tests/condition/ checks both).
std::vector<Condition> makePresets() {
    std::vector<Condition> list;
    for (int rate : {15, 30, 60, 120}) list.push_back(conventional(rate));
    for (int lag : {50, 100, 200}) {
        Condition c;
        c.name = "lag" + std::to_string(lag);
        c.description = "conventional 60 Hz, each frame shown " + std::to_string(lag) + " ms after it was rendered";
        c.renderHz = 60;
        c.lagMs = lag;
        list.push_back(c);
    }
    Condition warp;
    warp.name = "warp15to120";
    warp.description = "rendered at 15 Hz, the frames between warped from the latest with the current camera";
    warp.renderHz = 15;
    warp.fill = "warp-sparse8";
    warp.fillHz = 120;
    list.push_back(warp);
    Condition bireproj;
    bireproj.name = "bireproj15to60";
    bireproj.description =
        "I-frames rendered at 15 Hz, B-frames at 60 Hz interpolated between the I-frames before and after";
    bireproj.renderHz = 15;
    bireproj.fill = "bireproj";  // image-based, m = 3, dual and latest-frame initialisation
    bireproj.fillHz = 60;
    list.push_back(bireproj);
    return list;
}

// The shortest text that reads back as the same double: a rate a hair off a divisor must show
// as written ("59.999999999"), where number() would round it to the divisor ("60").
std::string exactNumber(double value) {
    std::ostringstream out;
    for (int precision = 6; precision <= 17; ++precision) {
        out.str("");
        out.precision(precision);
        out << value;
        if (std::stod(out.str()) == value) break;
    }
    return out.str();
}

// "2nd", "3rd", "8th": which display frames a rate that fits the refresh takes.
std::string ordinal(std::int64_t n) {
    const std::int64_t tens = n % 100, ones = n % 10;
    const char* suffix = tens >= 11 && tens <= 13 ? "th"
        : ones == 1                               ? "st"
        : ones == 2                               ? "nd"
        : ones == 3                               ? "rd"
                                                  : "th";
    return std::to_string(n) + suffix;
}

// What is wrong with a condition's frame_time_jitter or hitches, measured against its mean
// render interval; the part is the key within them.
std::optional<Problem> pacingProblem(const Condition& c) {
    const double meanMs = 1000.0 / c.renderHz;
    const std::string mean =
        "the mean render interval (" + number(meanMs) + " ms at render_hz " + number(c.renderHz) + ")";
    const Jitter& j = c.jitter;
    auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (c.frameTimes) {
        if (c.frameTimes->recordedMs.empty()) return Problem{"frame_times", "holds no frame times"};
        if (j.shape != JitterShape::None)
            return Problem{"frame_time_jitter",
                           "is for a steady render_hz; with frame_times the trace gives every render interval "
                           "(leave frame_time_jitter out)"};
    }
    switch (j.shape) {
        case JitterShape::None: break;
        case JitterShape::Normal:
            if (!positive(j.sdMs) || j.sdMs > meanMs / 3.0)
                return Problem{"frame_time_jitter.sd_ms",
                               "is " + number(j.sdMs) +
                                   " ms; a normal jitter's SD must be above 0 and at most a third of " + mean +
                                   ", so intervals stay positive (\"lognormal\" allows wider)"};
            break;
        case JitterShape::Lognormal:
            if (!positive(j.sdMs) || j.sdMs > 2.0 * meanMs)
                return Problem{
                    "frame_time_jitter.sd_ms",
                    "is " + number(j.sdMs) + " ms; a log-normal jitter's SD must be above 0 and at most twice " + mean};
            break;
        case JitterShape::Uniform:
            if (!positive(j.rangeMs) || j.rangeMs >= 2.0 * meanMs)
                return Problem{"frame_time_jitter.range_ms",
                               "is " + number(j.rangeMs) +
                                   " ms; a uniform jitter's range must be above 0 and below twice " + mean +
                                   ", so intervals stay positive"};
            break;
    }
    const Hitches& h = c.hitches;
    if (h.ms == 0.0 && h.everyS == 0.0 && h.ratePerS == 0.0) return std::nullopt;
    if (!positive(h.ms) || h.ms > 10000.0)
        return Problem{"hitches.ms", "is " + number(h.ms) + "; a hitch lasts more than 0 and at most 10000 ms"};
    if ((h.everyS > 0.0) == (h.ratePerS > 0.0))
        return Problem{"hitches", "needs one of every_s (periodic) and rate_per_s (random), not both or neither"};
    if (h.everyS > 0.0 && (!std::isfinite(h.everyS) || h.ms >= 1000.0 * h.everyS))
        return Problem{"hitches.ms",
                       "is " + number(h.ms) + " ms, not shorter than its period (every_s " + number(h.everyS) +
                           " s); a hitch must end before the next is due"};
    if (h.ratePerS > 0.0 && (!std::isfinite(h.ratePerS) || h.ms >= 1000.0 / h.ratePerS))
        return Problem{"hitches.ms",
                       "is " + number(h.ms) + " ms, not shorter than its mean period (1 / rate_per_s = " +
                           number(1000.0 / h.ratePerS) + " ms)"};
    return std::nullopt;
}

}  // namespace

std::string number(double value) {
    std::ostringstream out;
    out.precision(6);
    out << value;
    return out.str();
}

std::optional<std::int64_t> wholeRatio(double total, double part) {
    if (!(part > 0.0) || !std::isfinite(part) || !(total > 0.0) || !std::isfinite(total)) return std::nullopt;
    const auto whole = std::llround(total / part);
    if (whole < 1) return std::nullopt;
    // A few units in the last place: what the division and the product may round by, and no more.
    const double slack = 4.0 * std::numeric_limits<double>::epsilon() * total;
    if (std::abs(part * static_cast<double>(whole) - total) > slack) return std::nullopt;
    return whole;
}

const std::vector<FillSpelling>& fillSpellings() {
    // The warps are the renderer's mesh warps and the splat (tests/present/ checks each is a
    // method that takes a guard band, as a warp's sources need). warp-splat needs OpenGL 4.3;
    // where the context lacks it, the study shows the renderer's fallback (methodFallback).
    static const std::vector<FillSpelling> list = {
        {"hold", Fill::Hold},         {"warp-full", Fill::Warp},    {"warp-nofix", Fill::Warp},
        {"warp-sparse4", Fill::Warp}, {"warp-sparse8", Fill::Warp}, {"warp-sparse16", Fill::Warp},
        {"warp-splat", Fill::Warp},   {"bireproj", Fill::Bireproj}, {"blend", Fill::Blend},
    };
    return list;
}

std::optional<Fill> fillNamed(const std::string& name) {
    for (const auto& s : fillSpellings())
        if (name == s.name) return s.fill;
    return std::nullopt;
}

const std::vector<LateWarp>& lateWarps() {
    static const std::vector<LateWarp> list = {LateWarp::None, LateWarp::Rotation, LateWarp::Depth};
    return list;
}

const char* lateWarpName(LateWarp lateWarp) {
    switch (lateWarp) {
        case LateWarp::None: return "none";
        case LateWarp::Rotation: return "rotation";
        case LateWarp::Depth: return "depth";
    }
    return "?";
}

std::optional<LateWarp> lateWarpNamed(const std::string& name) {
    for (const LateWarp w : lateWarps())
        if (name == lateWarpName(w)) return w;
    return std::nullopt;
}

Fill Condition::fillKind() const {
    const std::optional<Fill> f = fillNamed(fill);
    if (!f) throw std::invalid_argument("condition " + name + ": unknown fill '" + fill + "'");
    return *f;
}

std::string Condition::warpMethod() const {
    if (fillKind() == Fill::Warp) return fill;  // one warp pass, to the late camera where there is one
    switch (lateWarp) {
        case LateWarp::None: return "";
        case LateWarp::Rotation: return kRotationLateWarpMethod;
        case LateWarp::Depth: return kDepthLateWarpMethod;
    }
    return "";
}

std::string Condition::interpolationMethod() const {
    const Fill f = fillKind();
    return f == Fill::Bireproj || f == Fill::Blend ? fill : "";
}

std::string Condition::sourceMethod() const {
    const std::string interpolation = interpolationMethod();
    return interpolation.empty() ? warpMethod() : interpolation;
}

bool Condition::sameParts(const Condition& o) const {
    return renderHz == o.renderHz && lagFrames == o.lagFrames && lagMs == o.lagMs && fill == o.fill &&
        fillHz == o.fillHz && lateWarp == o.lateWarp && jitter == o.jitter && hitches == o.hitches &&
        (frameTimes && o.frameTimes ? *frameTimes == *o.frameTimes : frameTimes == o.frameTimes);
}

const std::vector<JitterShape>& jitterShapes() {
    static const std::vector<JitterShape> list = {JitterShape::Normal, JitterShape::Lognormal, JitterShape::Uniform};
    return list;
}

const char* jitterShapeName(JitterShape shape) {
    switch (shape) {
        case JitterShape::None: return "none";
        case JitterShape::Normal: return "normal";
        case JitterShape::Lognormal: return "lognormal";
        case JitterShape::Uniform: return "uniform";
    }
    return "?";
}

std::optional<JitterShape> jitterShapeNamed(const std::string& name) {
    for (const JitterShape s : jitterShapes())
        if (name == jitterShapeName(s)) return s;
    return std::nullopt;
}

const std::vector<Condition>& presets() {
    static const std::vector<Condition> list = makePresets();
    return list;
}

const Condition* findPreset(const std::string& name) {
    for (const auto& c : presets())
        if (c.name == name) return &c;
    return nullptr;
}

const Condition& preset(const std::string& name) {
    if (const Condition* c = findPreset(name)) return *c;
    return ConditionTable().at(name);  // throws, listing the presets
}

std::vector<std::string> presetNames() { return ConditionTable().names(); }

std::int64_t lagFramesAt(const Condition& c, double refreshHz) {
    if (c.lagFrames) {
        if (*c.lagFrames < 0)
            throw std::invalid_argument("condition " + c.name + ": lag_frames must be at least 0, got " +
                                        std::to_string(*c.lagFrames));
        return *c.lagFrames;
    }
    if (!(c.lagMs >= 0.0) || !std::isfinite(c.lagMs))
        throw std::invalid_argument("condition " + c.name + ": lag_ms must be at least 0, got " + number(c.lagMs));
    const double frames = c.lagMs * refreshHz / 1000.0;
    const auto whole = std::llround(frames);
    if (std::abs(frames - static_cast<double>(whole)) > 1e-9) {
        const auto below = static_cast<std::int64_t>(std::floor(frames));
        auto ms = [&](std::int64_t n) { return number(static_cast<double>(n) * 1000.0 / refreshHz); };
        throw std::invalid_argument("condition " + c.name + ": lag_ms is " + number(c.lagMs) + " ms, which is " +
                                    number(frames) + " frames at " + number(refreshHz) +
                                    " Hz, not a whole number; the nearest that are: " + ms(below) + " ms (" +
                                    std::to_string(below) + " frames) and " + ms(below + 1) + " ms (" +
                                    std::to_string(below + 1) + " frames), or give lag_frames");
    }
    return whole;
}

std::optional<Problem> problem(const Condition& c, double refreshHz) {
    const std::string refresh = number(refreshHz) + " Hz";
    if (!(refreshHz > 0.0) || !std::isfinite(refreshHz))
        return Problem{"", "needs a display refresh that is a positive number of Hz"};
    if (!(c.renderHz > 0.0) || !std::isfinite(c.renderHz))
        return Problem{"render_hz", "must be a positive number of Hz, got " + number(c.renderHz)};
    // A hair off a rate that fits (59.999999999 Hz at 120 Hz) is a typo for it, not a cadence:
    // a display would run it as that rate.
    auto hairOff = [&](const char* part, double rateHz) -> std::optional<Problem> {
        if (wholeRatio(refreshHz, rateHz)) return std::nullopt;
        const auto near = std::llround(refreshHz / rateHz);
        if (near < 1 || std::abs(refreshHz / rateHz - static_cast<double>(near)) >= 1e-6) return std::nullopt;
        const std::string runs = exactNumber(refreshHz / static_cast<double>(near));
        return Problem{part,
                       "is " + exactNumber(rateHz) + " Hz, which a " + refresh + " display can only run as " + runs +
                           " Hz (" + (near == 1 ? std::string("every") : "every " + ordinal(near)) +
                           " display frame); write " + runs};
    };
    // Any render rate up to the refresh runs: one that does not divide it shows the uneven
    // cadence a vsync'd game shows (60 fps on 144 Hz: 2, 3, 2, 3, 2 refreshes).
    const std::optional<std::int64_t> renderPeriod = wholeRatio(refreshHz, c.renderHz);
    if (const auto p = hairOff("render_hz", c.renderHz)) return p;
    if (c.renderHz > refreshHz && c.frameTimes)
        return Problem{c.frameTimes->meanHz ? "frame_times.mean_hz" : "frame_times",
                       "plays at " + number(c.renderHz) + " frames a second, above the refresh (" + refresh +
                           "): a display shows at most one new render per refresh; give frame_times.mean_hz up "
                           "to " +
                           refresh + " to play it slower"};
    if (c.renderHz > refreshHz)
        return Problem{"render_hz",
                       "is " + exactNumber(c.renderHz) + " Hz, above the refresh (" + refresh +
                           "): a display shows at most one new render per refresh; allowed: up to " + refresh};
    if (const auto p = pacingProblem(c)) return p;
    std::int64_t lag = 0;
    try {
        lag = lagFramesAt(c, refreshHz);
    } catch (const std::invalid_argument& e) {
        // The part is named once, by the caller's path: "lag_ms is 60 ms, which is ...", as
        // every other part's reason reads after its path.
        std::string reason = e.what();
        const std::string part = c.lagFrames ? "lag_frames" : "lag_ms";
        for (const std::string& prefix : {"condition " + c.name + ": ", part + " "})
            if (reason.rfind(prefix, 0) == 0) reason.erase(0, prefix.size());
        return Problem{part, reason};
    }
    const std::optional<Fill> fill = fillNamed(c.fill);
    if (!fill) {
        std::string known;
        for (const auto& s : fillSpellings()) known += std::string(known.empty() ? "" : ", ") + s.name;
        return Problem{"fill", "must be one of " + known + ", not \"" + c.fill + "\""};
    }
    // A fill rate the refresh does not divide makes its frames unevenly, each at the first
    // refresh at or after it, as renders are (120 Hz on 144: 1, 1, 1, 1, 2 refreshes apart).
    std::optional<std::int64_t> fillPeriod = 1;
    double fillRate = refreshHz;
    if (c.fillHz) {
        if (*fill == Fill::Hold)
            return Problem{"fill_hz", "is for a fill that makes frames; \"hold\" makes none (leave fill_hz out)"};
        if (const auto p = hairOff("fill_hz", *c.fillHz)) return p;
        fillPeriod = wholeRatio(refreshHz, *c.fillHz);
        if (*c.fillHz > refreshHz)
            return Problem{"fill_hz",
                           "is " + exactNumber(*c.fillHz) + " Hz, above the refresh (" + refresh +
                               "): a display shows at most one new frame per refresh; allowed: up to " + refresh};
        fillRate = *c.fillHz;
    }
    if (*fill != Fill::Hold && renderPeriod && fillPeriod && c.steadyPacing() && *renderPeriod % *fillPeriod != 0)
        return Problem{c.fillHz ? "fill_hz" : "render_hz",
                       "the fill's rate (" + number(fillRate) + " Hz) must be a whole multiple of render_hz (" +
                           number(c.renderHz) + " Hz)"};
    // Renders that do not fall evenly on the fill's frames interleave with them; a fill
    // slower than the renders would make none of its own.
    if (*fill != Fill::Hold && fillRate < c.renderHz)
        return Problem{
            c.fillHz ? "fill_hz" : "render_hz",
            "the fill's rate (" + number(fillRate) + " Hz) must be at least render_hz (" + number(c.renderHz) + " Hz)"};
    if (c.lateWarp != LateWarp::None && (*fill == Fill::Bireproj || *fill == Fill::Blend))
        return Problem{"late_warp",
                       std::string("must be \"none\" with fill \"") + c.fill +
                           "\": a late warp re-projects one frame, and " + c.fill +
                           " shows two (allowed with it: none)"};
    // The longest render interval, in whole frames: what a held render and bidirectional
    // reprojection's wait for the next may look back.
    const std::int64_t longest = renderPeriod && c.steadyPacing()
        ? *renderPeriod
        : static_cast<std::int64_t>(std::ceil(longestRenderIntervalS(c) * refreshHz)) + 1;
    const std::int64_t lookBack = lag + 2 * longest;
    if (lookBack > kMaxLookBackFrames) {
        const char* part = c.lagFrames ? "lag_frames" : "lag_ms";
        if (!c.steadyPacing() && lag < kMaxLookBackFrames / 2)
            part = c.hitches.ms > 0.0 ? "hitches.ms" : (c.frameTimes ? "frame_times" : "frame_time_jitter");
        return Problem{part,
                       "looks back " + std::to_string(lookBack) + " display frames (the lag plus two of the longest " +
                           "render intervals), more than the " + std::to_string(kMaxLookBackFrames) + " a game keeps"};
    }
    return std::nullopt;
}

const Condition* ConditionTable::find(const std::string& name) const {
    // A definition that repeats a preset's parts under its name may stand for it; it is the
    // same condition, so the preset answers.
    if (const Condition* preset = findPreset(name)) return preset;
    for (const auto& c : defined_)
        if (c.name == name) return &c;
    return nullptr;
}

std::vector<std::string> ConditionTable::names() const {
    std::vector<std::string> list;
    for (const auto& c : presets()) list.push_back(c.name);
    for (const auto& c : defined_)
        if (!findPreset(c.name)) list.push_back(c.name);
    return list;
}

const Condition& ConditionTable::at(const std::string& name) const {
    if (const Condition* c = find(name)) return *c;
    std::string known;
    for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown condition '" + name + "' (known: " + known + ")");
}

std::string ConditionTable::check(const std::string& name, double refreshHz) const {
    try {
        const Condition& c = at(name);
        if (const auto p = problem(c, refreshHz))
            return "condition " + name + (p->part.empty() ? " " : ": " + p->part + " ") + p->reason;
        return "";
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
}

bool ConditionTable::operator==(const ConditionTable& o) const {
    if (defined_.size() != o.defined_.size()) return false;
    for (std::size_t i = 0; i < defined_.size(); ++i)
        if (defined_[i].name != o.defined_[i].name || defined_[i].description != o.defined_[i].description ||
            !defined_[i].sameParts(o.defined_[i]))
            return false;
    return true;
}

}  // namespace warplab::condition
