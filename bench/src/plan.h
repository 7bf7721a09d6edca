// What a bench run does, decided and checked before the first frame: the sequences and methods
// the options name, the display frames sampled from each sequence, and what the chosen methods
// imply for every frame (the guard band, the sources' flow, the rate of the shared masks).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "bench/bench.h"
#include "bench/sequences.h"
#include "renderer/upconvert.h"

namespace warplab::bench {

struct BenchPlan {
    std::vector<std::unique_ptr<game::BenchSequence>> sequences;
    std::vector<std::unique_ptr<renderer::UpconversionMethod>> methods;
    // The methods the GL context cannot run (warp-splat below OpenGL 4.3), each as the one
    // sentence that says why: left out of the run and named in the summary.
    std::vector<std::string> skipped;
    std::vector<std::vector<int>> samplesPerSequence;  // display-frame indices, one list per sequence
    std::size_t totalFrames = 0;  // over all sequences

    // Two kinds of source: plain, and with this band for the methods that take one; anyBanded
    // when some method does and the band is not empty.
    renderer::GuardBand band;
    bool anyBanded = false;
    // Sources carry the backward flow towards the source this many display frames earlier when
    // a method takes it from them (bidirectional reprojection's I-frames, drawn in the same
    // pass); 0 = none does.
    int flowPeriod = 0;
    // The shared masks are those of the latest source at the lowest source rate among the
    // methods (15 Hz for the study's), every maskPeriod display frames.
    double maskRateHz = 0.0;
    int maskPeriod = 1;
};

// Needs a current GL context: methods the context cannot run are skipped (BenchPlan::skipped).
// Throws std::invalid_argument naming the option (size, repeats, an unknown sequence or method,
// no method left that the context can run,
// a method whose source rate does not divide the display's or whose source lag is not a whole
// number of display frames, the guard band).
BenchPlan makePlan(const BenchOptions& options, const renderer::DataPaths& paths);

// Display frames between a method's sources.
int sourcePeriod(const BenchOptions& options, const renderer::MethodInfo& info);
// Display frames a method's sources wait before they are shown (MethodInfo::sourceLagS).
int sourceLagFrames(const BenchOptions& options, const renderer::MethodInfo& info);
// The display frame of the source a method is handed at display frame k: the latest one at or
// before k - lag (sources are rendered at multiples of the period), the next one a period
// later. Negative before the lag has passed: the sequences are defined before t = 0 too, so a
// late method's first frames show what was rendered before the run began, as a queue would.
int previousSource(const BenchOptions& options, const renderer::MethodInfo& info, int k);

}  // namespace warplab::bench
