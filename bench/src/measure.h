// One display frame measured: the ground truth rendered and timed at its instant, then every
// method's frame made, timed and judged against it -- PSNR, SSIM, the masked errors, the
// correspondence shares, the triangle count.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "bench/bench.h"
#include "bench/ground_truth.h"
#include "plan.h"
#include "renderer/timing.h"
#include "source_cache.h"
#include "stats.h"

namespace warplab::bench {

// The GL objects of a run, made once and reused by every frame.
struct Rig {
    Rig(const BenchOptions& options, const BenchPlan& plan, const renderer::DataPaths& paths);
    // Untimed: the first render of a run pays for shader compilation and first-touch
    // allocations (27 ms against 8 ms later for the same pan frame on llvmpipe).
    void warmUp(const scene::FrameDescription& frame);

    renderer::ShadingOptions shading;  // every conventional frame's, as the options ask
    renderer::ConventionalRenderer conventional;
    renderer::PassTimer timer;
    renderer::SourceFrame truthFrame;
    renderer::DisplayFrame display;
    SourcePool plainPool, bandedPool;
    std::unique_ptr<renderer::SourceFrame> bandedTruth;  // times a banded source at the truth instant
    std::set<const renderer::UpconversionMethod*> warmed;  // methods whose first pass was untimed
};

// The wall-clock times of `repeats` runs of `pass`, each between the timer's glFinish calls.
std::vector<double> timeRepeats(renderer::PassTimer& timer, int repeats, const std::function<void()>& pass);

// One method on one display frame: a line of bench.csv.
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
    // Its shading budget: the share of the display's pixels shaded per displayed frame (a 15 Hz
    // source on a 120 Hz display: 1/8), the way it spends it (budgetFamily), and how old the
    // newest shading behind its pixels is (or, for a method that needs the next source, how long
    // the frame waits for it), mean and 95th percentile over the pixels.
    double budgetShare = kNaN;
    std::string family;
    double ageMeanMs = kNaN, ageP95Ms = kNaN;
    // The pass's stages timed apart (UpconversionMethod::timeStages), each a median over the
    // repeats; empty for methods of one stage.
    std::vector<renderer::StageTime> stages;
};

// The three ways of spending a shading budget the bench compares.
std::string budgetFamily(const renderer::MethodInfo& info);

// The conventional frames' times over the run, one entry per truth frame: what shows another
// process loading the machine, and what the guard band costs.
struct ConventionalTimes {
    std::vector<double> spread;  // slowest / fastest of its repeats
    std::vector<double> frames;  // its median
    std::vector<double> banded;  // a banded source's median at the same instant (when any method takes one)
};

// Display frame k of `sequence`: one row per method of the plan, in the plan's order. Adds the
// truth frame's times to `times`.
std::vector<Row> measureDisplayFrame(Rig& rig, const BenchOptions& options, const BenchPlan& plan,
                                     const game::BenchSequence& sequence, int k, ConventionalTimes& times);

}  // namespace warplab::bench
