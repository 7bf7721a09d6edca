// speed_vs_error.png, drawn from bench.csv by analysis/plot_bench.py.
#pragma once

#include <string>

#include "renderer/conventional.h"

namespace warplab::bench {

// Empty when the plot was written; otherwise a note for the summary starting "not written: "
// with the reason.
std::string writePlot(const renderer::DataPaths& paths, const std::string& csv, const std::string& png,
                      const std::string& title);

}  // namespace warplab::bench
