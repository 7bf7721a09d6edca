#include "plan.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "scene/limits.h"

namespace warplab::bench {

BenchPlan makePlan(const BenchOptions& options, const renderer::DataPaths& paths) {
    constexpr int lo = scene::kMinDisplaySize, hi = scene::kMaxImageSize;
    if (options.width < lo || options.height < lo || options.width > hi || options.height > hi)
        throw std::invalid_argument("bench size must be between " + std::to_string(lo) + "x" + std::to_string(lo) +
                                    " and " + std::to_string(hi) + "x" + std::to_string(hi));
    if (options.repeats < 1) throw std::invalid_argument("bench repeats must be at least 1");
    const std::vector<std::string> sequenceNames =
        options.sequences.empty() ? game::sequenceNames() : options.sequences;
    const std::vector<std::string> methodNames = options.methods.empty() ? renderer::methodNames() : options.methods;

    BenchPlan plan;
    game::SequenceConfig sequenceConfig;
    sequenceConfig.aspect = static_cast<double>(options.width) / options.height;
    sequenceConfig.durationScale = options.durationScale;
    sequenceConfig.seed = options.seed;
    for (const auto& name : sequenceNames) plan.sequences.push_back(game::makeSequence(name, sequenceConfig));
    for (const auto& name : methodNames) {
        const std::string unavailable = renderer::methodUnavailable(name);
        if (!unavailable.empty()) {
            plan.skipped.push_back(unavailable);
            continue;
        }
        plan.methods.push_back(renderer::makeMethod(name, paths));
        const renderer::MethodInfo& info = plan.methods.back()->info();
        const double perSource = options.refreshHz / info.sourceRateHz;
        if (std::abs(perSource - std::round(perSource)) > 1e-9 || perSource < 1.0)
            throw std::invalid_argument("method " + name + " renders at a rate that does not divide the display's");
        // A queue delays a frame by whole refreshes, and sources are rendered at display-frame
        // instants: a lag between frames is a wrong setting, not one to round.
        const double lagFrames = info.sourceLagS * options.refreshHz;
        if (!(lagFrames >= 0.0) || std::abs(lagFrames - std::round(lagFrames)) > 1e-6) {
            std::ostringstream message;
            message << "method " << name << " shows its sources " << info.sourceLagS
                    << " s late, which is not a whole number of display frames at " << options.refreshHz << " Hz";
            throw std::invalid_argument(message.str());
        }
    }

    if (plan.methods.empty())
        throw std::invalid_argument("no method named can run in this GL context: " + plan.skipped.front());

    plan.band = renderer::guardBandFor(options.width, options.height, options.guardBand);
    plan.anyBanded = !(plan.band == renderer::GuardBand{}) &&
        std::any_of(plan.methods.begin(), plan.methods.end(), [](const auto& m) { return m->info().takesGuardBand; });
    for (const auto& m : plan.methods)
        if (m->info().usesSourceFlow) plan.flowPeriod = sourcePeriod(options, m->info());
    // Every method of a frame is judged on the same pixels, what the latest lowest-rate source
    // does not show: what an extrapolating method must invent. One that also has the next
    // source (blend, bireproj) may find them there, at the cost of its latency.
    plan.maskRateHz = options.refreshHz;
    for (const auto& m : plan.methods) plan.maskRateHz = std::min(plan.maskRateHz, m->info().sourceRateHz);
    plan.maskPeriod = static_cast<int>(std::lround(options.refreshHz / plan.maskRateHz));

    for (const auto& sequence : plan.sequences) {
        const int frameCount = std::max(1, static_cast<int>(std::floor(sequence->duration() * options.refreshHz)));
        plan.samplesPerSequence.push_back(sampleFrames(frameCount, options.framesPerSequence, 8));
        plan.totalFrames += plan.samplesPerSequence.back().size();
    }
    return plan;
}

int sourcePeriod(const BenchOptions& options, const renderer::MethodInfo& info) {
    return static_cast<int>(std::lround(options.refreshHz / info.sourceRateHz));
}

int sourceLagFrames(const BenchOptions& options, const renderer::MethodInfo& info) {
    return static_cast<int>(std::lround(info.sourceLagS * options.refreshHz));
}

int previousSource(const BenchOptions& options, const renderer::MethodInfo& info, int k) {
    const int period = sourcePeriod(options, info);
    const int shown = k - sourceLagFrames(options, info);
    return shown - ((shown % period) + period) % period;  // rounded down for negative frames too
}

std::vector<int> sampleFrames(int frameCount, int samples, int phases) {
    std::vector<int> frames;
    if (frameCount <= 0) return frames;
    if (samples <= 0 || samples >= frameCount) {
        for (int k = 0; k < frameCount; ++k) frames.push_back(k);
        return frames;
    }
    const int cycles = std::max(1, frameCount / phases);
    for (int j = 0; j < samples; ++j) {
        // Spread over the cycles the sequence has; the phase walks 0, 1, ..., phases-1, 0, ...
        const int cycle = static_cast<int>(static_cast<long long>(j) * cycles / samples);
        const int k = std::min(frameCount - 1, cycle * phases + j % phases);
        if (frames.empty() || frames.back() != k) frames.push_back(k);
    }
    return frames;
}

}  // namespace warplab::bench
