// Times a GPU pass two ways: wall clock bracketed by glFinish (what a frame really costs,
// driver overhead included) and a GL_TIME_ELAPSED query (the GPU's own account, where the
// driver implements it meaningfully).
#pragma once

#include <memory>

namespace warplab::renderer {

struct PassTime {
    double wallMs = 0.0;
    double gpuMs = 0.0;  // NaN when the driver gives no (plausible) timer result
};

class PassTimer {
public:
    PassTimer();
    ~PassTimer();
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;

    void begin();  // glFinish, then start both clocks
    PassTime end();  // glFinish, stop both clocks

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace warplab::renderer
