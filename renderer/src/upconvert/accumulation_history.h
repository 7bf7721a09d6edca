// Renderer-private: the bookkeeping of a method that builds its picture over consecutive
// displayed frames (spatio-temporal upsampling, adaptive frameless sampling) into two buffers,
// one written per frame while the other holds the frame before.
#pragma once

#include <glm/glm.hpp>

namespace warplab::renderer {

class AccumulationHistory {
public:
    // A history is reprojected from the frame before only; a gap longer than this (a cut, or a
    // bench that samples frames far apart) starts it again, so that a frame's result depends
    // only on the frames since the last gap.
    static constexpr double kMaxFrameGapS = 0.1;
    // A sample reprojected from the frame before shows the same surface when its view depth is
    // within this share of the point's (scene-assisted reprojection's test, with the object id).
    static constexpr float kSameSurfaceDepth = 0.01f;

    // Call once per displayed frame made, with its instant and camera. A repeat of the last
    // frame (the bench times a pass several times) changes nothing: it reads the history its
    // first run read and writes the same buffer.
    void advance(double time, const glm::mat4& viewProjection) {
        if (haveLast_ && time == lastTime_) {
            repeat_ = true;
            return;
        }
        repeat_ = false;
        const bool follows = haveLast_ && time > lastTime_ && time - lastTime_ <= kMaxFrameGapS;
        follows_ = follows;
        dt_ = follows ? time - lastTime_ : 0.0;
        previousViewProjection_ = viewProjection_;
        frameIndex_ = follows ? frameIndex_ + 1 : 0;
        if (!follows) origin_ = time;
        written_ = 1 - written_;
        lastTime_ = time;
        viewProjection_ = viewProjection;
        haveLast_ = true;
    }
    // Forget every frame (the buffers were made anew).
    void reset() { haveLast_ = false; }

    int written() const { return written_; }  // the buffer this frame writes: 0 or 1
    int previous() const { return 1 - written_; }  // the one holding the frame before
    bool follows() const { return follows_; }  // the frame before is in previous()
    bool repeat() const { return repeat_; }
    double dt() const { return dt_; }  // since the frame before; 0 when none
    long frameIndex() const { return frameIndex_; }  // frames since the last gap
    double time() const { return lastTime_; }
    double origin() const { return origin_; }  // the first frame's instant since the last gap
    const glm::mat4& viewProjection() const { return viewProjection_; }
    const glm::mat4& previousViewProjection() const { return previousViewProjection_; }

private:
    bool haveLast_ = false, follows_ = false, repeat_ = false;
    int written_ = 0;
    double lastTime_ = 0.0, dt_ = 0.0, origin_ = 0.0;
    long frameIndex_ = 0;
    glm::mat4 viewProjection_{1.0f}, previousViewProjection_{1.0f};
};

}  // namespace warplab::renderer
