// Renderer-private: bidirectional reprojection (seed 000, Yang et al. 2011). Use
// makeMethod("bireproj" | "bireproj-m1".."bireproj-m4" | "bireproj-nodual" | "bireproj-nolatest"
// | "bireproj-noinit").
#pragma once

#include "renderer/upconvert.h"

namespace warplab::renderer {

struct BireprojSettings {
    int iterations = 3;  // m of eq. 5 and 9; the paper uses 3 (1..8)
    float errorThresholdPx = 0.5f;  // epsilon 1 of section 5.2: a search converged below it
    // epsilon 2: two searches found the same surface when their view depths differ by less than
    // this fraction (relative, so it means the same near and far).
    float depthThreshold = 0.02f;
    bool dualInit = true;  // eq. 16-17
    bool latestInit = true;  // eq. 18-19 (from the previous B-frame of the interval)
    int neighbourhood = 1;  // latest-frame initialisation looks at (2n+1)^2 offsets
};

std::unique_ptr<UpconversionMethod> makeBireproj(const DataPaths& paths, const std::string& name,
                                                 const BireprojSettings& settings);

// Motion blur from B-frames (seed 000 section 9, Figure 10): the mean of `samples` B-frames
// spread evenly over the interval between the two I-frames, made by bireproj with `settings`.
std::unique_ptr<UpconversionMethod> makeBireprojBlur(const DataPaths& paths, const std::string& name,
                                                     const BireprojSettings& settings, int samples);

}  // namespace warplab::renderer
