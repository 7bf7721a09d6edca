// Renderer-private: timing a method's stages apart for the bench (UpconversionMethod::timeStages).
#pragma once

#include <chrono>
#include <vector>

#include "gl/api.h"
#include "renderer/upconvert.h"

namespace warplab::renderer {

// Times the stages of one produce() when the bench asks: each ends with glFinish, so its time
// is its own and not the next one's.
class StageClock {
public:
    void enable(bool on) { on_ = on; }
    void start() {
        times_.clear();
        if (!on_) return;
        glFinish();
        last_ = std::chrono::steady_clock::now();
    }
    void done(const char* stage) {
        if (!on_) return;
        glFinish();
        const auto now = std::chrono::steady_clock::now();
        times_.push_back({stage, std::chrono::duration<double, std::milli>(now - last_).count()});
        last_ = now;
    }
    const std::vector<StageTime>& times() const { return times_; }

private:
    bool on_ = false;
    std::chrono::steady_clock::time_point last_;
    std::vector<StageTime> times_;
};

}  // namespace warplab::renderer
