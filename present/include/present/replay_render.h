// Re-rendering a stored session's displayed frames (warplab replay --render).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "renderer/context.h"
#include "renderer/conventional.h"

namespace warplab::present {

struct ReplayRender {
    std::string sessionPath;
    std::string outDir;
    std::int64_t firstFrame = 0;
    std::int64_t lastFrame = 599;  // inclusive
    int width = 0, height = 0;  // 0: the session's display size
    double progressEveryS = 5.0;  // how often to say how far it got, seconds of wall time
};

struct ReplayRenderResult {
    int written = 0;  // frames written
    int skipped = 0;  // frames of the range the live session skipped (never shown): not written
    int checked = 0;  // frames whose id under the pointer was compared with the analytic model
    int eventsChecked = 0;  // ... of which a logged shot or click, also compared with its displayed outcome
    int nearSilhouette = 0;  // frames not counted: the pointer within a pixel or two of an outline
    int disagreed = 0;  // comparisons that disagreed
    std::vector<std::string> disagreements;  // the first few, one line each
};

// Replays the session and writes every displayed frame of the range as DIR/frame_NNNNNNN.png
// (frames the record marks skipped were never displayed: none is written for them),
// made the way its condition makes it (rendered, held, warped, interpolated) with the HUD over it,
// the photodiode marker included where the session's window drew one (white on the frames it lit).
// On frames whose image is an exact render (rendered or held), the object id read back under
// the reticle or cursor is checked against the game's analytic account of that frame, and on
// frames with a logged shot or click, against the logged displayed outcome. Prints the tally on
// `out`, and on `progress` how far it got: the frames before the range are re-simulated without
// drawing them (a late range of a long session takes a while), said once, then every
// `progressEveryS` seconds of wall time while it works.
ReplayRenderResult renderReplay(const ReplayRender& request, const renderer::DataPaths& paths,
                                renderer::GlBackend backend, std::ostream& out, std::ostream& progress);

}  // namespace warplab::present
