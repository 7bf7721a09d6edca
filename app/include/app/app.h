// warplab as a library: main() only forwards here, so tests can drive the commands.
#pragma once

#include <string>
#include <vector>

namespace warplab::app {

// Runs one command line (without the program name). Returns the process exit status:
// 0 success, 1 runtime failure (bad input file, no GL context, ...), 2 usage error.
int run(const std::vector<std::string>& args);

}  // namespace warplab::app
