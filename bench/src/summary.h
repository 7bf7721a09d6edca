// What a run reports: bench.csv's rows, the shading sweep (where upconversion starts to pay),
// and summary.md.
#pragma once

#include <fstream>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench.h"
#include "measure.h"
#include "plan.h"

namespace warplab::bench {

extern const char* const kCsvHeader;

// `path` created with the header line; throws std::runtime_error naming it when it cannot be.
std::ofstream openCsv(const std::string& path);
void writeRow(std::ostream& csv, const Row& r);

// (shading cost, median wall ms of a conventional frame), one per options.shadingSweep cost, at
// the first sequence's t = 0; leaves the rig's renderer at the run's shading.
using ShadingSweep = std::vector<std::pair<int, double>>;
ShadingSweep timeShadingSweep(Rig& rig, const BenchOptions& options, const BenchPlan& plan);

// summary.md without the plot's note: the run's settings and how loaded the machine looked,
// per method x sequence then per method over all sequences, and the shading sweep.
std::string summaryMarkdown(const BenchOptions& options, const renderer::GlInfo& gl, const BenchPlan& plan,
                            const ConventionalTimes& times, const std::vector<Row>& rows, const ShadingSweep& sweep);

}  // namespace warplab::bench
