// A value the user gave that warplab cannot use: a command-line option, a player spec, a
// frame range, a method or sequence name. The message names the value; the command line
// shows it with a pointer to --help and exits 2 (README "Exit codes"). It lives in the module
// every other one sees, so whichever module finds the bad value can say so in these terms.
#pragma once

#include <stdexcept>

namespace warplab {

class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace warplab
