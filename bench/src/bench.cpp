#include "bench/bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "bench/ground_truth.h"
#include "bench/sequences.h"
#include "plot.h"
#include "renderer/timing.h"
#include "renderer/upconvert.h"
#include "scene/limits.h"
#include "stats.h"

namespace warplab::bench {
namespace {

std::vector<glm::vec2> reportedCoordinates(const image::ImageF& correspondence, int channelOffset) {
    std::vector<glm::vec2> out(static_cast<std::size_t>(correspondence.width) * correspondence.height);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = {correspondence.data[4 * i + channelOffset], correspondence.data[4 * i + channelOffset + 1]};
    return out;
}

bool anyFinite(const std::vector<glm::vec2>& v) {
    return std::any_of(v.begin(), v.end(), [](const glm::vec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); });
}

// A conventionally rendered frame with its read-back depth and ids (for the scene's exact
// correspondences), kept while a display frame needs it.
struct RenderedSource {
    std::unique_ptr<renderer::SourceFrame> frame;
    renderer::GBufferImages images;
};

struct BruteForce {
    image::ImageRGBA8 colour;
    double ms = 0.0;
};

// Source frames allocated once and reused: a freshly allocated texture costs first-touch work
// that would otherwise be timed in whichever pass samples it first (a warp-full pass took
// 104-143 ms or 23-32 ms on llvmpipe depending on the source it read).
class SourcePool {
public:
    SourcePool(int width, int height, renderer::GuardBand band) : width_(width), height_(height), band_(band) {}
    std::unique_ptr<renderer::SourceFrame> take() {
        if (free_.empty()) return std::make_unique<renderer::SourceFrame>(width_, height_, band_);
        auto frame = std::move(free_.back());
        free_.pop_back();
        return frame;
    }
    void giveBack(std::unique_ptr<renderer::SourceFrame> frame) { free_.push_back(std::move(frame)); }

private:
    int width_, height_;
    renderer::GuardBand band_;
    std::vector<std::unique_ptr<renderer::SourceFrame>> free_;
};

struct Row {
    std::string sequence, method;
    int frame = 0;
    double time = 0, psnr = kNaN, ssim = kNaN;
    // Over the frame's shared masks (unseenMasks): content no source holds (border) and true
    // disocclusions (occluded), with their pixel counts so the summary weights frames by them.
    double borderMae = kNaN, disoccMae = kNaN;
    std::size_t borderPx = 0, disoccPx = 0;
    CorrespondenceStats corr;
    bool hasCorr = false;
    double passMs = kNaN, gpuMs = kNaN, conventionalMs = kNaN;
    double sourceMs = kNaN;  // one of the method's own source frames (with its guard band)
    double triangles = kNaN;
};

const char* kCsvHeader =
    "sequence,method,frame,time_s,psnr_db,ssim,border_mae,border_px,disocc_mae,disocc_px,corr_all_lt_0p1,corr_all_lt_0p5,corr_all_lt_1,"
    "corr_hit_lt_0p1,corr_hit_lt_0p5,corr_hit_lt_1,pass_ms,gpu_ms,conventional_ms,source_ms,triangles";

void writeRow(std::ostream& csv, const Row& r) {
    auto c = [&](double v) { return r.hasCorr ? field(v) : std::string(); };
    csv << r.sequence << ',' << r.method << ',' << r.frame << ',' << field(r.time, 6) << ',' << field(r.psnr, 3) << ','
        << field(r.ssim, 5) << ',' << field(r.borderMae, 3) << ',' << r.borderPx << ',' << field(r.disoccMae, 3) << ','
        << r.disoccPx << ',' << c(r.corr.allLt0p1) << ',' << c(r.corr.allLt0p5)
        << ',' << c(r.corr.allLt1) << ',' << c(r.corr.hitLt0p1) << ',' << c(r.corr.hitLt0p5) << ','
        << c(r.corr.hitLt1) << ',' << field(r.passMs, 3) << ',' << field(r.gpuMs, 3) << ','
        << field(r.conventionalMs, 3) << ',' << field(r.sourceMs, 3) << ',' << field(r.triangles, 0) << '\n';
}


}  // namespace

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

BenchOptions quickBenchOptions() {
    BenchOptions options;
    options.width = 320;
    options.height = 180;
    options.framesPerSequence = 8;
    options.repeats = 3;
    options.shadingSweep = {0, 256};
    return options;
}

void runBench(const BenchOptions& options, const renderer::DataPaths& paths, const renderer::GlInfo& gl,
              std::ostream& out, std::ostream& progress) {
    namespace fs = std::filesystem;
    constexpr int lo = scene::kMinDisplaySize, hi = scene::kMaxImageSize;
    if (options.width < lo || options.height < lo || options.width > hi || options.height > hi)
        throw std::invalid_argument("bench size must be between " + std::to_string(lo) + "x" + std::to_string(lo) +
                                    " and " + std::to_string(hi) + "x" + std::to_string(hi));
    if (options.repeats < 1) throw std::invalid_argument("bench repeats must be at least 1");
    const std::vector<std::string> sequenceNames =
        options.sequences.empty() ? game::sequenceNames() : options.sequences;
    const std::vector<std::string> methodNames =
        options.methods.empty() ? renderer::methodNames() : options.methods;

    // Everything that can be refused is refused before the first frame.
    game::SequenceConfig sequenceConfig;
    sequenceConfig.aspect = static_cast<double>(options.width) / options.height;
    sequenceConfig.durationScale = options.durationScale;
    sequenceConfig.seed = options.seed;
    std::vector<std::unique_ptr<game::BenchSequence>> sequences;
    for (const auto& name : sequenceNames) sequences.push_back(game::makeSequence(name, sequenceConfig));
    std::vector<std::unique_ptr<renderer::UpconversionMethod>> methods;
    for (const auto& name : methodNames) {
        methods.push_back(renderer::makeMethod(name, paths));
        const double perSource = options.refreshHz / methods.back()->info().sourceRateHz;
        if (std::abs(perSource - std::round(perSource)) > 1e-9 || perSource < 1.0)
            throw std::invalid_argument("method " + name + " renders at a rate that does not divide the display's");
    }
    fs::create_directories(options.outDir);
    const std::string csvPath = options.outDir + "/bench.csv";
    std::ofstream csv(csvPath);
    if (!csv) throw std::runtime_error("cannot write '" + csvPath + "'");
    csv << kCsvHeader << '\n';

    renderer::ShadingOptions shading;
    shading.shadingCost = options.shadingCost;
    shading.supersampling = options.supersampling;
    renderer::ConventionalRenderer conventional(paths, shading);
    renderer::PassTimer timer;
    renderer::SourceFrame truthFrame(options.width, options.height);
    renderer::DisplayFrame display(options.width, options.height);
    // Two kinds of source: plain, and with the guard band for the methods that take one.
    const renderer::GuardBand band = renderer::guardBandFor(options.width, options.height, options.guardBand);
    const bool anyBanded = !(band == renderer::GuardBand{}) &&
                           std::any_of(methods.begin(), methods.end(), [](const auto& m) { return m->info().takesGuardBand; });
    SourcePool plainPool(options.width, options.height, {}), bandedPool(options.width, options.height, band);
    std::unique_ptr<renderer::SourceFrame> bandedTruth;  // times a banded source at the truth instant
    if (anyBanded) bandedTruth = bandedPool.take();

    // Sources carry the backward flow towards the source one period earlier when a method takes
    // it from them (bidirectional reprojection's I-frames, drawn in the same pass); untimed,
    // like the rest of the source render.
    int flowPeriod = 0;
    for (const auto& m : methods)
        if (m->info().usesSourceFlow)
            flowPeriod = static_cast<int>(std::lround(options.refreshHz / m->info().sourceRateHz));
    auto renderSource = [&](SourcePool& pool, const scene::FrameDescription& depicts,
                            const scene::FrameDescription* flowTo) {
        RenderedSource s;
        s.frame = pool.take();
        renderer::renderSource(conventional, depicts, *s.frame, flowTo);
        s.images = renderer::readBack(s.frame->gbuffer);
        return s;
    };

    // Untimed warm-up: the first render of a run pays for shader compilation and first-touch
    // allocations (27 ms against 8 ms later for the same pan frame on llvmpipe).
    conventional.render(sequences.front()->at(0.0), truthFrame.gbuffer);
    renderer::readBack(truthFrame.gbuffer);
    if (bandedTruth) renderer::renderSource(conventional, sequences.front()->at(0.0), *bandedTruth);
    std::set<const renderer::UpconversionMethod*> warmed;  // methods whose first pass was untimed
    std::vector<double> conventionalSpread;  // per truth frame: slowest / fastest of its repeats
    std::vector<double> conventionalFrames;  // per truth frame: its median
    std::vector<double> bandedFrames;        // per truth frame: a banded source's median

    // The shared masks: what the latest source at the lowest source rate among the methods
    // (15 Hz for the study's) does not show when the frame is displayed -- what an extrapolating
    // method must invent. Every method of a frame is judged on the same pixels; one that also
    // has the next source (blend, bireproj) may find them there, at the cost of its latency.
    double maskRateHz = options.refreshHz;
    for (const auto& m : methods) maskRateHz = std::min(maskRateHz, m->info().sourceRateHz);
    const int maskPeriod = static_cast<int>(std::lround(options.refreshHz / maskRateHz));

    std::vector<Row> rows;
    const auto started = std::chrono::steady_clock::now();
    std::size_t totalFrames = 0, doneFrames = 0;
    std::vector<std::vector<int>> samplesPerSequence;
    for (const auto& sequence : sequences) {
        const int frameCount = std::max(1, static_cast<int>(std::floor(sequence->duration() * options.refreshHz)));
        samplesPerSequence.push_back(sampleFrames(frameCount, options.framesPerSequence, 8));
        totalFrames += samplesPerSequence.back().size();
    }

    for (std::size_t si = 0; si < sequences.size(); ++si) {
        const auto& sequence = *sequences[si];
        for (const int k : samplesPerSequence[si]) {
            const double t = k / options.refreshHz;
            const scene::FrameDescription truthDesc = sequence.at(t);

            // Ground truth: a conventional frame at this very instant, timed as the reference cost.
            std::vector<double> conventionalMs;
            for (int r = 0; r < options.repeats; ++r) {
                timer.begin();
                conventional.render(truthDesc, truthFrame.gbuffer);
                conventionalMs.push_back(timer.end().wallMs);
            }
            truthFrame.depicts = truthDesc;
            const renderer::GBufferImages truth = renderer::readBack(truthFrame.gbuffer);
            const double conventionalMedian = median(conventionalMs);
            conventionalFrames.push_back(conventionalMedian);
            conventionalSpread.push_back(*std::max_element(conventionalMs.begin(), conventionalMs.end()) /
                                         *std::min_element(conventionalMs.begin(), conventionalMs.end()));
            // The guard band's cost: the same instant rendered as a banded source.
            double bandedMedian = kNaN;
            if (bandedTruth) {
                std::vector<double> ms;
                for (int r = 0; r < options.repeats; ++r) {
                    timer.begin();
                    renderer::renderSource(conventional, truthDesc, *bandedTruth);
                    ms.push_back(timer.end().wallMs);
                }
                bandedMedian = median(ms);
                bandedFrames.push_back(bandedMedian);
            }

            // Sources by display-frame index and whether they have the guard band.
            using SourceKey = std::pair<int, bool>;
            std::map<SourceKey, RenderedSource> sources;
            std::map<SourceKey, Correspondence> truthCorrespondence;
            auto source = [&](int index, bool banded) -> const RenderedSource& {
                auto it = sources.find({index, banded});
                if (it == sources.end()) {
                    std::optional<scene::FrameDescription> before;
                    if (flowPeriod > 0 && index >= flowPeriod)
                        before = sequence.at((index - flowPeriod) / options.refreshHz);
                    it = sources
                             .emplace(SourceKey{index, banded},
                                      renderSource(banded ? bandedPool : plainPool, sequence.at(index / options.refreshHz),
                                                   before ? &*before : nullptr))
                             .first;
                }
                return it->second;
            };
            auto correspondenceTo = [&](int index, bool banded) -> const Correspondence& {
                auto it = truthCorrespondence.find({index, banded});
                if (it == truthCorrespondence.end()) {
                    const RenderedSource& s = source(index, banded);
                    it = truthCorrespondence
                             .emplace(SourceKey{index, banded},
                                      trueCorrespondence(truthDesc, truth.depth, truth.ids, s.frame->depicts,
                                                         s.images.depth, s.images.ids))
                             .first;
                }
                return it->second;
            };

            // Brute-force motion blur over the display frames [first, last): the mean of
            // `samples` conventional renders spread over it, and their total time (each render's
            // median over the repeats).
            std::map<std::pair<int, int>, BruteForce> bruteForces;
            auto bruteForce = [&](int first, int last, int samples) -> const BruteForce& {
                auto it = bruteForces.find({first, samples});
                if (it != bruteForces.end()) return it->second;
                BruteForce b;
                std::vector<double> sum;
                for (int j = 0; j < samples; ++j) {
                    const double at = (first + (last - first) * (j + 0.5) / samples) / options.refreshHz;
                    const scene::FrameDescription d = sequence.at(at);
                    std::vector<double> ms;
                    for (int r = 0; r < options.repeats; ++r) {
                        timer.begin();
                        conventional.render(d, truthFrame.gbuffer);
                        ms.push_back(timer.end().wallMs);
                    }
                    b.ms += median(ms);
                    const image::ImageRGBA8 colour = renderer::readBack(truthFrame.gbuffer).colour;
                    if (sum.empty()) {
                        sum.assign(colour.pixels.size(), 0.0);
                        b.colour = colour;
                    }
                    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += colour.pixels[i];
                }
                for (std::size_t i = 0; i < sum.size(); ++i)
                    b.colour.pixels[i] = static_cast<std::uint8_t>(std::lround(sum[i] / samples));
                return bruteForces.emplace(std::make_pair(first, samples), std::move(b)).first->second;
            };

            const int maskPrevious = k - k % maskPeriod;
            // Judged on what the displayed field of view's source lacks, with or without a band.
            const UnseenMasks unseen = unseenMasks({&correspondenceTo(maskPrevious, false)});
            const auto count = [](const std::vector<std::uint8_t>& mask) {
                return static_cast<std::size_t>(std::count(mask.begin(), mask.end(), std::uint8_t{1}));
            };

            for (auto& method : methods) {
                const auto& info = method->info();
                const int perSource = static_cast<int>(std::lround(options.refreshHz / info.sourceRateHz));
                const int previous = k - k % perSource;
                const int next = previous + perSource;
                const bool banded = anyBanded && info.takesGuardBand;
                renderer::UpconversionInput input;
                input.displayTime = t;
                input.camera = truthDesc.camera;
                input.previous = source(previous, banded).frame.get();
                if (info.needsNext) input.next = source(next, banded).frame.get();
                input.scene = &truthDesc.scene;

                // Per-interval work (flow fields) and, for methods that start from the previous
                // displayed frame, the interval's earlier frames: made untimed, as a session
                // would have made them before this one.
                method->prepare(input);
                if (info.usesEarlierFrames) {
                    for (int j = previous + 1; j < k; ++j) {
                        renderer::UpconversionInput earlier = input;
                        earlier.displayTime = j / options.refreshHz;
                        const scene::FrameDescription then = sequence.at(earlier.displayTime);
                        earlier.camera = then.camera;
                        earlier.scene = &then.scene;
                        method->produce(earlier, display);
                    }
                }
                // Untimed first pass per method: programs linked, buffers allocated.
                if (warmed.insert(method.get()).second) method->produce(input, display);
                std::vector<double> wall, gpu;
                for (int r = 0; r < options.repeats; ++r) {
                    timer.begin();
                    method->produce(input, display);
                    const auto time = timer.end();
                    wall.push_back(time.wallMs);
                    gpu.push_back(time.gpuMs);
                }
                const renderer::DisplayImages shown = renderer::readBack(display);

                Row row;
                row.sequence = sequence.name();
                row.method = info.name;
                row.frame = k;
                row.time = t;
                if (info.exposureSamples > 0) {
                    // Motion blur: judged against brute force, the mean of as many conventional
                    // renders over the same exposure, whose total time is the reference cost.
                    const BruteForce& reference = bruteForce(previous, next, info.exposureSamples);
                    row.psnr = image::psnr(shown.colour, reference.colour);
                    row.ssim = image::ssimLuminance(shown.colour, reference.colour);
                } else {
                    row.psnr = image::psnr(shown.colour, truth.colour);
                    row.ssim = image::ssimLuminance(shown.colour, truth.colour);
                    row.borderMae = maskedMeanAbsoluteError(shown.colour, truth.colour, unseen.border);
                    row.borderPx = count(unseen.border);
                    row.disoccMae = maskedMeanAbsoluteError(shown.colour, truth.colour, unseen.occluded);
                    row.disoccPx = count(unseen.occluded);
                }
                if (info.reportsCorrespondence) {
                    CorrespondenceAccumulator accumulator;
                    accumulator.add(reportedCoordinates(shown.correspondence, 0), correspondenceTo(previous, banded));
                    const auto intoNext = reportedCoordinates(shown.correspondence, 2);
                    if (info.needsNext && anyFinite(intoNext))
                        accumulator.add(intoNext, correspondenceTo(next, banded));
                    row.corr = accumulator.stats();
                    row.hasCorr = true;
                }
                row.triangles = method->lastTriangleCount();
                row.passMs = median(wall);
                row.gpuMs = median(gpu);
                row.conventionalMs =
                    info.exposureSamples > 0 ? bruteForce(previous, next, info.exposureSamples).ms : conventionalMedian;
                row.sourceMs = banded ? bandedMedian : conventionalMedian;
                writeRow(csv, row);
                rows.push_back(row);
            }
            for (auto& [key, rendered] : sources) (key.second ? bandedPool : plainPool).giveBack(std::move(rendered.frame));
            csv.flush();
            ++doneFrames;
            const double elapsed =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
            progress << "bench: " << sequence.name() << " frame " << k << " (" << doneFrames << "/" << totalFrames
                     << "), " << std::fixed << std::setprecision(0) << elapsed << " s elapsed, ~"
                     << elapsed / doneFrames * (totalFrames - doneFrames) << " s left\n"
                     << std::defaultfloat << std::flush;
        }
    }
    if (!csv) throw std::runtime_error("writing '" + csvPath + "' failed");

    // Where upconversion starts to pay: a conventional frame's cost as shading gets heavier.
    std::vector<std::pair<int, double>> sweep;
    {
        const scene::FrameDescription frame = sequences.front()->at(0.0);
        for (int cost : options.shadingSweep) {
            renderer::ShadingOptions s;
            s.shadingCost = cost;
            conventional.setShading(s);
            std::vector<double> ms;
            for (int r = 0; r < options.repeats; ++r) {
                timer.begin();
                conventional.render(frame, truthFrame.gbuffer);
                ms.push_back(timer.end().wallMs);
            }
            sweep.emplace_back(cost, median(ms));
        }
        conventional.setShading(shading);
    }

    // The summary: per method x sequence, then per method over all sequences.
    std::ostringstream md;
    md << "# warplab bench\n\n"
       << "- GL: " << gl.renderer << " (" << gl.version << ", " << gl.backend << ")\n"
       << "- size: " << options.width << "x" << options.height << ", display " << options.refreshHz << " Hz, "
       << "shading cost " << options.shadingCost << ", " << options.repeats
       << " timed repeats per pass after an untimed one (medians)\n"
       << "- antialiasing: " << (options.supersampling > 1 ? std::to_string(options.supersampling) + "x" +
                                                                    std::to_string(options.supersampling) + " supersampling"
                                                              : std::string("none"))
       << " for every conventional frame, ground truth included\n"
       << "- frames: " << totalFrames << " sampled display frames over " << sequences.size() << " sequences\n"
       << "- masks: border MAE over pixels off-screen in the frame's latest " << maskRateHz
       << " Hz source, disocc MAE over pixels hidden there; the same pixels for every method, weighted by pixel "
          "count over the frames\n";
    // Another process on the machine shows as repeats of one conventional frame that disagree,
    // or, when its load changes slowly, as conventional frames of one size that cost very
    // different amounts over the run (content alone spread them 1.8x, 90th to 10th
    // percentile, in an unloaded quick run; a compile beside it made that 6x).
    const double spread = median(conventionalSpread);
    std::vector<double> sortedFrames = conventionalFrames;
    std::sort(sortedFrames.begin(), sortedFrames.end());
    const auto percentile = [&](double q) {
        return sortedFrames[static_cast<std::size_t>(q * static_cast<double>(sortedFrames.size() - 1))];
    };
    const double runSpread = sortedFrames.empty() ? 1.0 : percentile(0.9) / percentile(0.1);
    if (anyBanded) {
        const double plain = median(conventionalFrames), banded = median(bandedFrames);
        const double pixels = static_cast<double>(options.width + 2 * band.x) * (options.height + 2 * band.y) /
                              (static_cast<double>(options.width) * options.height);
        md << "- guard band: " << options.guardBand * 100 << " % per side (" << band.x << " and " << band.y
           << " px) for the sources of the methods that take one, " << field(pixels, 2)
           << "x the pixels; such a source costs " << field(banded, 3) << " ms against " << field(plain, 3)
           << " ms without (median over the frames, ratio " << field(banded / plain, 2) << ")\n";
    }
    md << "- conventional frames: repeats of one frame median slowest/fastest " << field(spread, 3)
       << "; over the run 90th/10th percentile " << field(runSpread, 3) << "\n";
    if (spread > 1.3 || runSpread > 3.0)
        md << "\n**Warning:** the conventional frame's time varied " << (spread > 1.3 ? "between repeats" : "over the run")
           << " more than content explains: something else is loading this machine, so the times are noisy.\n";
    md << "\n| sequence | method | sources | median pass ms | ratio to conventional | PSNR dB | mean SSIM | border MAE | "
          "disocc MAE | corr all <0.5 px | corr hit <0.5 px | triangles |\n"
          "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    // What a method is given, so methods are compared at equal cost in renders: the rate of its
    // conventional sources, "+ next" when it also waits for the next one (a frame of latency),
    // and how many times the lowest rate's renders it needs.
    const auto sourcesText = [&](const renderer::MethodInfo& info) {
        std::string text = field(info.sourceRateHz, 0) + " Hz";
        if (info.needsNext) text += " + next";
        if (info.sourceRateHz > maskRateHz)
            text += " (" + field(info.sourceRateHz / maskRateHz, 0) + "x the renders)";
        return text;
    };
    auto summarise = [&](const std::string& seq, const renderer::MethodInfo& info) {
        const std::string& method = info.name;
        std::vector<double> pass, conv, psnr, ssim, all05, hit05, triangles;
        double borderSum = 0, disoccSum = 0;
        std::size_t borderPx = 0, disoccPx = 0;
        for (const Row& r : rows) {
            if ((!seq.empty() && r.sequence != seq) || r.method != method) continue;
            pass.push_back(r.passMs);
            conv.push_back(r.conventionalMs);
            psnr.push_back(r.psnr);
            ssim.push_back(r.ssim);
            if (r.borderPx > 0 && !std::isnan(r.borderMae)) borderSum += r.borderMae * r.borderPx, borderPx += r.borderPx;
            if (r.disoccPx > 0 && !std::isnan(r.disoccMae)) disoccSum += r.disoccMae * r.disoccPx, disoccPx += r.disoccPx;
            triangles.push_back(r.triangles);
            if (r.hasCorr) all05.push_back(r.corr.allLt0p5), hit05.push_back(r.corr.hitLt0p5);
        }
        const double p = median(pass), c = median(conv);
        const double combined = psnrOfMeanMse(psnr);
        const std::string psnrText = std::isinf(combined) ? "inf (exact)" : field(combined, 2);
        auto pct = [](double v) { return std::isnan(v) ? std::string("") : field(100.0 * v, 1) + "%"; };
        md << "| " << (seq.empty() ? "**all**" : seq) << " | " << method << " | " << sourcesText(info) << " | "
           << field(p, 3) << " | "
           << field(p / c, 3) << " | " << psnrText << " | " << field(mean(ssim), 4) << " | "
           << field(borderPx > 0 ? borderSum / borderPx : kNaN, 2) << " | "
           << field(disoccPx > 0 ? disoccSum / disoccPx : kNaN, 2)
           << " | " << pct(mean(all05)) << " | " << pct(mean(hit05)) << " | " << field(median(triangles), 0) << " |\n";
    };
    for (const auto& s : sequences)
        for (const auto& m : methods) summarise(s->name(), m->info());
    // Over all sequences, methods of equal source rate together, lowest first.
    std::vector<const renderer::MethodInfo*> byRate;
    for (const auto& m : methods) byRate.push_back(&m->info());
    std::stable_sort(byRate.begin(), byRate.end(), [](const auto* a, const auto* b) {
        return a->sourceRateHz < b->sourceRateHz || (a->sourceRateHz == b->sourceRateHz && !a->needsNext && b->needsNext);
    });
    for (const auto* info : byRate) summarise("", *info);

    md << "\nA 15->120 Hz method renders one conventional frame and makes seven, so per displayed frame it costs "
          "(C + 7M)/8 against C for rendering every frame: it pays whenever its pass M is cheaper than a "
          "conventional frame C.\n\n| shading cost | conventional frame ms (" << sequences.front()->name()
       << ", t = 0) | methods cheaper than it |\n|---:|---:|---|\n";
    for (const auto& [cost, ms] : sweep) {
        std::string cheaper;
        for (const auto& m : methods) {
            std::vector<double> pass;
            for (const Row& r : rows)
                if (r.method == m->info().name) pass.push_back(r.passMs);
            if (median(pass) < ms) cheaper += (cheaper.empty() ? "" : ", ") + m->info().name;
        }
        md << "| " << cost << " | " << field(ms, 3) << " | " << cheaper << " |\n";
    }
    md << "\nColumns of bench.csv: " << kCsvHeader
       << ". Empty = does not apply; psnr_db inf = identical to ground truth. PSNR in the table is that of the "
          "mean squared error over the frames. Ratios divide medians measured in this run.\n";

    const std::string plotNote =
        writePlot(paths, csvPath, options.outDir + "/speed_vs_error.png",
                  gl.renderer + ", " + std::to_string(options.width) + "x" + std::to_string(options.height));
    if (!plotNote.empty()) md << "\nspeed_vs_error.png " << plotNote << "\n";
    const std::string summary = md.str();
    std::ofstream(options.outDir + "/summary.md") << summary;
    out << summary;
}

}  // namespace warplab::bench
