#include "condition/stimulus.h"

#include <cmath>
#include <stdexcept>

namespace warplab::condition {

const std::vector<DimensionSpelling>& dimensionSpellings() {
    static const std::vector<DimensionSpelling> list = {
        {"lag_frames", Dimension::LagFrames},
        {"render_hz", Dimension::RenderHz},
        {"frame_time_jitter.sd_ms", Dimension::JitterSdMs},
    };
    return list;
}

std::optional<Dimension> dimensionNamed(const std::string& name) {
    for (const DimensionSpelling& d : dimensionSpellings())
        if (name == d.name) return d.dimension;
    return std::nullopt;
}

const char* dimensionName(Dimension dimension) {
    for (const DimensionSpelling& d : dimensionSpellings())
        if (d.dimension == dimension) return d.name;
    return "";
}

Condition varied(const Condition& reference, Dimension dimension, double level) {
    Condition c = reference;
    const std::string key = dimensionName(dimension);
    if (!std::isfinite(level)) throw std::invalid_argument(key + " must be a finite number");
    switch (dimension) {
        case Dimension::LagFrames:
            if (level != std::floor(level) || level < 0 || level > kMaxLagFrames)
                throw std::invalid_argument(key + " must be a whole number of display frames from 0 to " +
                                            std::to_string(kMaxLagFrames) + ", got " + number(level));
            c.lagFrames = static_cast<int>(level);
            c.lagMs = 0.0;
            break;
        case Dimension::RenderHz:
            if (!(level > 0))
                throw std::invalid_argument(key + " must be a positive number of Hz, got " + number(level));
            c.renderHz = level;
            break;
        case Dimension::JitterSdMs:
            if (!(level >= 0)) throw std::invalid_argument(key + " must be 0 ms or more, got " + number(level));
            c.jitter = level == 0 ? Jitter{} : Jitter{JitterShape::Normal, level, 0.0};
            break;
    }
    c.name = reference.name + "@" + key + "=" + number(level);
    c.description = reference.description + (reference.description.empty() ? "" : ", ") + key + " " + number(level);
    return c;
}

double levelOf(const Condition& c, Dimension dimension, double refreshHz) {
    switch (dimension) {
        case Dimension::LagFrames: return static_cast<double>(lagFramesAt(c, refreshHz));
        case Dimension::RenderHz: return c.renderHz;
        case Dimension::JitterSdMs:
            return c.jitter.shape == JitterShape::Normal || c.jitter.shape == JitterShape::Lognormal ? c.jitter.sdMs
                                                                                                     : 0.0;
    }
    return 0.0;
}

double stimulusOf(Dimension dimension, double referenceLevel, double level) {
    return dimension == Dimension::RenderHz ? referenceLevel - level : level - referenceLevel;
}

const char* dimensionUnits(Dimension dimension) {
    switch (dimension) {
        case Dimension::LagFrames: return "display frames";
        case Dimension::RenderHz: return "Hz";
        case Dimension::JitterSdMs: return "ms";
    }
    return "";
}

}  // namespace warplab::condition
