// speed_vs_error.png, drawn from bench.csv by analysis/plot_bench.py.
#pragma once

#include <string>

#include "renderer/conventional.h"

namespace warplab::bench {

// Writes speed against error to `png` and error at equal shading budgets to `budgetPng`
// (samplesPerShare: shaded samples per second at a budget share of 1, width x height x display
// rate). Empty when both were written; otherwise a note for the summary starting "not written: "
// with the reason.
std::string writePlot(const renderer::DataPaths& paths, const std::string& csv, const std::string& png,
                      const std::string& title, const std::string& budgetPng, double samplesPerShare);

}  // namespace warplab::bench
