// Renderer-private: extrapolation by iterative search. Use makeMethod("warp-search").
#pragma once

#include "renderer/upconvert.h"

namespace warplab::renderer {

struct WarpSearchSettings {
    int iterations = 3;  // m of seed 000 eq. 5 (1..8)
    float errorThresholdPx = 0.5f;  // a search converged below this screen-space error
    // Neighbourhood starts (see shaders/warp_search.frag): rings of 8 flow samples around each
    // pixel, the outermost at ringRadius times the image height, each inner one at half the
    // radius of the one outside it. 0 rings = only the starts p and p - F(p), which cannot find
    // a surface that moved onto p over one that stays (a target's leading edge). Quick bench
    // (320x180, llvmpipe, all sequences): 0 rings 28.73 dB in 10.5 ms, 1 ring 29.14 dB in
    // 17.2 ms, 2 rings 29.25 dB in ~29 ms; the falling spheres 33.5 dB without, 37.6 dB with.
    // At 1920x1080 on llvmpipe the ring's scattered fetches cost more: pass time 0.63x
    // warp-sparse8's with 0 rings, 2.0x with 1 (pan and track, where it changes nothing).
    int rings = 1;
    float ringRadius = 0.04f;
};

std::unique_ptr<UpconversionMethod> makeWarpSearch(const DataPaths& paths, const std::string& name,
                                                   const WarpSearchSettings& settings);

}  // namespace warplab::renderer
