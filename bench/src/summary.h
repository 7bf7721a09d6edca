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
#include "table/columns.h"

namespace warplab::bench {

// bench.csv's columns, each name beside how its cell is written: its header and every row
// walk this one table.
const std::vector<table::Column<Row>>& csvColumns();

// `path` created for bench.csv; throws std::runtime_error naming it when it cannot be.
std::ofstream openCsv(const std::string& path);
// One row of bench.csv, through csvColumns().
void writeRow(table::CsvFile& csv, const Row& r);

// (shading cost, median wall ms of a conventional frame), one per options.shadingSweep cost, at
// the first sequence's t = 0; leaves the rig's renderer at the run's shading.
using ShadingSweep = std::vector<std::pair<int, double>>;
ShadingSweep timeShadingSweep(Rig& rig, const BenchOptions& options, const BenchPlan& plan);

// summary.md without the plot's note: the run's settings and how loaded the machine looked,
// per method x sequence then per method over all sequences, and the shading sweep.
std::string summaryMarkdown(const BenchOptions& options, const renderer::GlInfo& gl, const BenchPlan& plan,
                            const ConventionalTimes& times, const std::vector<Row>& rows, const ShadingSweep& sweep);

}  // namespace warplab::bench
