#include "measure.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

namespace warplab::bench {
namespace {

renderer::ShadingOptions shadingFor(const BenchOptions& options) {
    renderer::ShadingOptions shading;
    shading.shadingCost = options.shadingCost;
    shading.supersampling = options.supersampling;
    return shading;
}

std::vector<glm::vec2> reportedCoordinates(const image::ImageF& correspondence, int channelOffset) {
    std::vector<glm::vec2> out(static_cast<std::size_t>(correspondence.width) * correspondence.height);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = {correspondence.data[4 * i + channelOffset], correspondence.data[4 * i + channelOffset + 1]};
    return out;
}

bool anyFinite(const std::vector<glm::vec2>& v) {
    return std::any_of(v.begin(), v.end(), [](const glm::vec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); });
}

std::size_t count(const std::vector<std::uint8_t>& mask) {
    return static_cast<std::size_t>(std::count(mask.begin(), mask.end(), std::uint8_t{1}));
}

// Ground truth: a conventional frame at the displayed instant, timed as the reference cost.
struct Truth {
    scene::FrameDescription desc;
    renderer::GBufferImages images;
    double conventionalMs = kNaN;  // median over the repeats
    double bandedMs = kNaN;  // the same instant rendered as a banded source; NaN without a band
};

Truth renderTruth(Rig& rig, const BenchOptions& options, const scene::FrameDescription& desc,
                  ConventionalTimes& times) {
    Truth truth;
    truth.desc = desc;
    const std::vector<double> conventionalMs =
        timeRepeats(rig.timer, options.repeats, [&] { rig.conventional.render(desc, rig.truthFrame.gbuffer); });
    rig.truthFrame.depicts = desc;
    truth.images = renderer::readBack(rig.truthFrame.gbuffer);
    truth.conventionalMs = median(conventionalMs);
    times.frames.push_back(truth.conventionalMs);
    times.spread.push_back(*std::max_element(conventionalMs.begin(), conventionalMs.end()) /
                           *std::min_element(conventionalMs.begin(), conventionalMs.end()));
    // The guard band's cost: the same instant rendered as a banded source.
    if (rig.bandedTruth) {
        truth.bandedMs = median(timeRepeats(rig.timer, options.repeats,
                                            [&] { renderer::renderSource(rig.conventional, desc, *rig.bandedTruth); }));
        times.banded.push_back(truth.bandedMs);
    }
    return truth;
}

struct BruteForce {
    image::ImageRGBA8 colour;
    double ms = 0.0;
};

// Brute-force motion blur over the display frames [first, last): the mean of `samples`
// conventional renders spread over it, and their total time (each render's median over the
// repeats); made once per display frame however many methods are judged against it.
class BruteForceCache {
public:
    BruteForceCache(Rig& rig, const BenchOptions& options, const game::BenchSequence& sequence)
        : rig_(rig), options_(options), sequence_(sequence) {}

    const BruteForce& get(int first, int last, int samples) {
        auto it = cache_.find({first, samples});
        if (it != cache_.end()) return it->second;
        BruteForce b;
        std::vector<double> sum;
        for (int j = 0; j < samples; ++j) {
            const double at = (first + (last - first) * (j + 0.5) / samples) / options_.refreshHz;
            const scene::FrameDescription d = sequence_.at(at);
            b.ms += median(timeRepeats(rig_.timer, options_.repeats,
                                       [&] { rig_.conventional.render(d, rig_.truthFrame.gbuffer); }));
            const image::ImageRGBA8 colour = renderer::readBack(rig_.truthFrame.gbuffer).colour;
            if (sum.empty()) {
                sum.assign(colour.pixels.size(), 0.0);
                b.colour = colour;
            }
            for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += colour.pixels[i];
        }
        for (std::size_t i = 0; i < sum.size(); ++i)
            b.colour.pixels[i] = static_cast<std::uint8_t>(std::lround(sum[i] / samples));
        return cache_.emplace(std::make_pair(first, samples), std::move(b)).first->second;
    }

private:
    Rig& rig_;
    const BenchOptions& options_;
    const game::BenchSequence& sequence_;
    std::map<std::pair<int, int>, BruteForce> cache_;
};

// What every method of one display frame is made from and judged against.
struct FrameContext {
    const BenchOptions& options;
    const BenchPlan& plan;
    const game::BenchSequence& sequence;
    int k;
    const Truth& truth;
    const UnseenMasks& unseen;
    SourceCache& sources;
    BruteForceCache& bruteForces;
};

struct PassTimes {
    double wallMs = kNaN, gpuMs = kNaN;  // medians over the repeats
    std::vector<renderer::StageTime> stages;  // each stage's median over the repeats
};

// Each stage's median over the repeats, in the method's order of stages.
std::vector<renderer::StageTime> stageMedians(const std::vector<std::vector<renderer::StageTime>>& repeats) {
    std::vector<renderer::StageTime> medians;
    if (repeats.empty()) return medians;
    for (std::size_t i = 0; i < repeats.front().size(); ++i) {
        std::vector<double> ms;
        for (const auto& r : repeats)
            if (i < r.size()) ms.push_back(r[i].wallMs);
        medians.push_back({repeats.front()[i].name, median(ms)});
    }
    return medians;
}

// Makes the method's frame into rig.display, `options.repeats` times timed.
PassTimes timePass(Rig& rig, const BenchOptions& options, renderer::UpconversionMethod& method,
                   const renderer::UpconversionInput& input, int previous, int k, const game::BenchSequence& sequence) {
    // Per-interval work (flow fields) and, for methods that start from the previous
    // displayed frame, the interval's earlier frames: made untimed, as a session
    // would have made them before this one.
    // Methods that build a history over displayed frames: the frames before, likewise.
    method.prepare(input);
    const int first = method.info().usesEarlierFrames ? previous + 1 : k - method.info().historyFrames;
    for (int j = std::max(0, first); j < k; ++j) {
        renderer::UpconversionInput earlier = input;
        earlier.displayTime = j / options.refreshHz;
        const scene::FrameDescription then = sequence.at(earlier.displayTime);
        earlier.camera = then.camera;
        earlier.scene = &then.scene;
        method.produce(earlier, rig.display);
    }
    // Untimed first pass per method: programs linked, buffers allocated.
    if (rig.warmed.insert(&method).second) method.produce(input, rig.display);
    std::vector<double> wall, gpu;
    std::vector<std::vector<renderer::StageTime>> stages;
    // A stage ends with glFinish: on llvmpipe the next stage waits for it anyway; on a GPU it
    // adds a sync or two to the pass time.
    method.timeStages(true);
    for (int r = 0; r < options.repeats; ++r) {
        rig.timer.begin();
        method.produce(input, rig.display);
        const auto time = rig.timer.end();
        wall.push_back(time.wallMs);
        gpu.push_back(time.gpuMs);
        stages.push_back(method.lastStageTimes());
    }
    method.timeStages(false);
    return {median(wall), median(gpu), stageMedians(stages)};
}

Row measureMethod(Rig& rig, const FrameContext& frame, renderer::UpconversionMethod& method) {
    const auto& info = method.info();
    const BenchOptions& options = frame.options;
    const int previous = previousSource(options, info, frame.k);
    const int next = previous + sourcePeriod(options, info);
    const bool banded = frame.plan.anyBanded && info.takesGuardBand;
    renderer::UpconversionInput input;
    input.displayTime = frame.k / options.refreshHz;
    input.camera = frame.truth.desc.camera;
    input.previous = frame.sources.source(previous, banded).frame.get();
    if (info.needsNext) input.next = frame.sources.source(next, banded).frame.get();
    input.scene = &frame.truth.desc.scene;
    input.shading = rig.shading;

    const PassTimes pass = timePass(rig, options, method, input, previous, frame.k, frame.sequence);
    const renderer::DisplayImages shown = renderer::readBack(rig.display);

    Row row;
    row.sequence = frame.sequence.name();
    row.method = info.name;
    row.frame = frame.k;
    row.time = input.displayTime;
    const image::ImageRGBA8& truth = frame.truth.images.colour;
    if (info.exposureSamples > 0) {
        // Motion blur: judged against brute force, the mean of as many conventional
        // renders over the same exposure, whose total time is the reference cost.
        const BruteForce& reference = frame.bruteForces.get(previous, next, info.exposureSamples);
        row.psnr = image::psnr(shown.colour, reference.colour);
        row.ssim = image::ssimLuminance(shown.colour, reference.colour);
    } else {
        row.psnr = image::psnr(shown.colour, truth);
        row.ssim = image::ssimLuminance(shown.colour, truth);
        row.borderMae = maskedMeanAbsoluteError(shown.colour, truth, frame.unseen.border);
        row.borderPx = count(frame.unseen.border);
        row.disoccMae = maskedMeanAbsoluteError(shown.colour, truth, frame.unseen.occluded);
        row.disoccPx = count(frame.unseen.occluded);
    }
    if (info.reportsCorrespondence) {
        CorrespondenceAccumulator accumulator;
        accumulator.add(reportedCoordinates(shown.correspondence, 0), frame.sources.correspondenceTo(previous, banded));
        const auto intoNext = reportedCoordinates(shown.correspondence, 2);
        if (info.needsNext && anyFinite(intoNext))
            accumulator.add(intoNext, frame.sources.correspondenceTo(next, banded));
        row.corr = accumulator.stats();
        row.hasCorr = true;
    }
    row.triangles = method.lastTriangleCount();
    row.passMs = pass.wallMs;
    row.gpuMs = pass.gpuMs;
    row.stages = pass.stages;
    row.conventionalMs = info.exposureSamples > 0 ? frame.bruteForces.get(previous, next, info.exposureSamples).ms
                                                  : frame.truth.conventionalMs;
    row.sourceMs = banded ? frame.truth.bandedMs : frame.truth.conventionalMs;
    row.budgetShare = info.shadedShare > 0.0 ? info.shadedShare : info.sourceRateHz / options.refreshHz;
    row.family = budgetFamily(info);
    if (info.shadedShare > 0.0) {
        std::vector<float> ages = method.lastSampleAges();
        if (ages.empty()) ages.assign(1, 0.0f);
        row.ageMeanMs = 1000.0 * mean(std::vector<double>(ages.begin(), ages.end()));
        std::nth_element(ages.begin(), ages.begin() + static_cast<std::ptrdiff_t>(0.95 * (ages.size() - 1)),
                         ages.end());
        row.ageP95Ms = 1000.0 * ages[static_cast<std::size_t>(0.95 * (ages.size() - 1))];
    } else {
        // Whole frames: every pixel is as old as the source it shows, or waits as long for the next.
        const int newest = info.needsNext ? next : previous;
        row.ageMeanMs = row.ageP95Ms = 1000.0 * std::abs(frame.k - newest) / options.refreshHz;
    }
    return row;
}

}  // namespace

std::string budgetFamily(const renderer::MethodInfo& info) {
    if (info.shadedShare <= 0.0) return "whole frames";
    return info.adaptivePlacement ? "adaptive samples" : "pixel lattice";
}

Rig::Rig(const BenchOptions& options, const BenchPlan& plan, const renderer::DataPaths& paths)
    : shading(shadingFor(options)),
      conventional(paths, shading),
      truthFrame(options.width, options.height),
      display(options.width, options.height),
      plainPool(options.width, options.height, {}),
      bandedPool(options.width, options.height, plan.band) {
    if (plan.anyBanded) bandedTruth = bandedPool.take();
}

void Rig::warmUp(const scene::FrameDescription& frame) {
    conventional.render(frame, truthFrame.gbuffer);
    renderer::readBack(truthFrame.gbuffer);
    if (bandedTruth) renderer::renderSource(conventional, frame, *bandedTruth);
}

std::vector<double> timeRepeats(renderer::PassTimer& timer, int repeats, const std::function<void()>& pass) {
    std::vector<double> ms;
    for (int r = 0; r < repeats; ++r) {
        timer.begin();
        pass();
        ms.push_back(timer.end().wallMs);
    }
    return ms;
}

std::vector<Row> measureDisplayFrame(Rig& rig, const BenchOptions& options, const BenchPlan& plan,
                                     const game::BenchSequence& sequence, int k, ConventionalTimes& times) {
    const Truth truth = renderTruth(rig, options, sequence.at(k / options.refreshHz), times);
    SourceSetting setting;
    setting.conventional = &rig.conventional;
    setting.plainPool = &rig.plainPool;
    setting.bandedPool = &rig.bandedPool;
    setting.sequence = &sequence;
    setting.refreshHz = options.refreshHz;
    setting.flowPeriod = plan.flowPeriod;
    SourceCache sources(setting, truth.desc, truth.images);
    BruteForceCache bruteForces(rig, options, sequence);
    // Judged on what the displayed field of view's source lacks, with or without a band.
    const UnseenMasks unseen = unseenMasks({&sources.correspondenceTo(k - k % plan.maskPeriod, false)});

    const FrameContext frame{options, plan, sequence, k, truth, unseen, sources, bruteForces};
    std::vector<Row> rows;
    for (const auto& method : plan.methods) rows.push_back(measureMethod(rig, frame, *method));
    return rows;
}

}  // namespace warplab::bench
