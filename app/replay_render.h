// Private to app/: re-rendering a stored session's displayed frames (warplab replay --render).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "renderer/context.h"
#include "renderer/conventional.h"

namespace warplab::app {

struct ReplayRender {
    std::string sessionPath;
    std::string outDir;
    std::int64_t firstFrame = 0;
    std::int64_t lastFrame = 599;   // inclusive
    int width = 0, height = 0;      // 0: the session's display size
};

// Replays the session and writes every displayed frame of the range as DIR/frame_NNNNNNN.png,
// made the way its mode makes it (rendered, held, warped; interpolated frames use a blend until
// the bidirectional renderer exists, and say so). Where a frame was really rendered, the object
// id read back under the reticle is checked against the analytic displayed outcome; prints the
// tally to `out`.
void renderReplay(const ReplayRender& request, const renderer::DataPaths& paths, renderer::GlBackend backend,
                  std::ostream& out);

}  // namespace warplab::app
