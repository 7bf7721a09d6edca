// The equal-budget comparison: methods grouped by how many pixels they shade per displayed frame
// (whole frames less often, a lattice of pixels every frame, adaptive samples every frame), with
// their error against the ideal, what a displayed frame costs them at light and heavy shading,
// and how old the shading they show is.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "measure.h"
#include "plan.h"
#include "summary.h"

namespace warplab::bench {

// Per method that shades part of every frame itself (MethodInfo::shadedShare): its pass's median
// wall ms at each of options.shadingSweep's costs, on the sweep's frame (the first sequence at
// t = 0, after its history frames).
using ShadedSweep = std::map<std::string, std::vector<double>>;
ShadedSweep timeShadedMethods(Rig& rig, const BenchOptions& options, const BenchPlan& plan);

// The table and what it compares, as a section of summary.md.
std::string budgetMarkdown(const BenchOptions& options, const BenchPlan& plan, const std::vector<Row>& rows,
                           const ShadingSweep& sweep, const ShadedSweep& shaded);

}  // namespace warplab::bench
