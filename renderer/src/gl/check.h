// GL error reporting: user-visible failures become exceptions whose message names what was
// being done, so `warplab` can print one sentence and exit non-zero instead of crashing.
#pragma once

#include <stdexcept>
#include <string>

#include "gl/api.h"

namespace warplab::gl {

class GlError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

const char* errorName(GLenum error);

// Throws GlError naming `what` and every pending GL error; a no-op when there is none.
void checkErrors(const char* what);

}  // namespace warplab::gl
