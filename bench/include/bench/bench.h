// `warplab bench`: every upconversion method against ground truth on scripted sequences,
// speed against error (DESIGN.md "Speed against error", seed 000 section 9).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "renderer/context.h"
#include "renderer/conventional.h"

namespace warplab::bench {

struct BenchOptions {
    int width = 1920;
    int height = 1080;
    double refreshHz = 120.0;  // display rate the methods upconvert to
    std::vector<std::string> sequences;  // empty = all
    std::vector<std::string> methods;  // empty = all
    int framesPerSequence = 16;  // sampled display frames; 0 = every frame
    double durationScale = 1.0;  // shortens (< 1) or lengthens the sequences
    int repeats = 5;  // timed runs of each pass (after an untimed one); the median is reported
    int shadingCost = 0;  // ShadingOptions::shadingCost for every conventional frame
    // Sources of the methods that take one (the warps) are rendered this fraction of the size
    // beyond each side, as a study's warp condition renders them (protocol display.guard_band).
    double guardBand = 0.1;
    // Samples per pixel side for every conventional frame -- truth, sources, brute force -- so
    // that errors measure the method rather than aliasing (protocol display.supersampling).
    int supersampling = 1;
    std::vector<int> shadingSweep{0, 64, 256, 1024};  // costs at which the summary times a conventional frame
    std::string outDir;
    std::uint64_t seed = 1;
};

// `warplab bench --quick`: small and short, the whole table in well under 3 minutes on two
// cores; the other fields as BenchOptions' defaults.
BenchOptions quickBenchOptions();

// Runs the benchmark in the current GL context; writes bench.csv, summary.md,
// speed_vs_error.png and budget_vs_error.png into options.outDir; prints progress to `progress` and the summary to
// `out`. Throws on bad options (naming them) or unwritable output.
void runBench(const BenchOptions& options, const renderer::DataPaths& paths, const renderer::GlInfo& gl,
              std::ostream& out, std::ostream& progress);

// The display frames sampled from a sequence of `frameCount` frames: `samples` of them,
// spread over the sequence and cycling through every phase of the 15 Hz source cycle
// (frame index mod 8 at 120 Hz), so hold/warp are judged at every distance from a source.
std::vector<int> sampleFrames(int frameCount, int samples, int phases);

}  // namespace warplab::bench
