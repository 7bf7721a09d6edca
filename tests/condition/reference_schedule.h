// The frame schedule as it was before render instants became data (every render_hz dividing
// the refresh), kept verbatim as the oracle that the presets and every shipped protocol expand
// to exactly the schedules their sessions were recorded with, frame by frame.
#pragma once

#include <cstdint>

#include "condition/schedule.h"

namespace warplab::condition::reference {

inline std::int64_t floorTo(std::int64_t k, std::int64_t period) {
    const std::int64_t r = ((k % period) + period) % period;
    return k - r;
}

class Schedule {
public:
    Schedule(const Condition& c, double refreshHz) : condition_(c), refreshHz_(refreshHz), fill_(c.fillKind()) {
        renderPeriod_ = std::llround(refreshHz / c.renderHz);
        lagFrames_ = lagFramesAt(c, refreshHz);
        fillPeriod_ = fill_ == Fill::Hold ? renderPeriod_ : (c.fillHz ? std::llround(refreshHz / *c.fillHz) : 1);
    }

    ScheduledFrame produced(std::int64_t j) const {
        ScheduledFrame f;
        f.rendersNow = floorTo(j, renderPeriod_) == j;
        auto time = [&](std::int64_t frame) { return static_cast<double>(frame) / refreshHz_; };
        switch (fill_) {
            case Fill::Hold: {
                f.sourceIndex = floorTo(j, renderPeriod_);
                f.made = f.sourceIndex == j ? FrameKind::Rendered : FrameKind::Held;
                f.cameraTime = f.sceneTime = f.worldSampleTime = time(f.sourceIndex);
                f.samplesInput = f.rendersNow;
                break;
            }
            case Fill::Warp: {
                const std::int64_t made = floorTo(j, fillPeriod_);
                f.sourceIndex = floorTo(j, renderPeriod_);
                f.made = j == f.sourceIndex ? FrameKind::Rendered
                                            : (made == f.sourceIndex ? FrameKind::Held : FrameKind::Warped);
                f.cameraTime = f.sceneTime = time(made);
                f.worldSampleTime = time(f.sourceIndex);
                f.samplesInput = made == j;
                break;
            }
            case Fill::Bireproj:
            case Fill::Blend: {
                const std::int64_t depicted = floorTo(j, fillPeriod_) - renderPeriod_;
                f.sourceIndex = floorTo(depicted, renderPeriod_);
                const bool onRender = f.sourceIndex == depicted;
                f.nextSourceIndex = onRender ? -1 : f.sourceIndex + renderPeriod_;
                const bool newFrame = floorTo(j, fillPeriod_) == j;
                f.made = onRender ? (newFrame ? FrameKind::Rendered : FrameKind::Held) : FrameKind::Interpolated;
                f.sceneTime = time(depicted);
                if (fill_ == Fill::Bireproj) {
                    f.cameraTime = f.sceneTime;
                    f.worldSampleTime = time(onRender ? f.sourceIndex : f.nextSourceIndex);
                } else {
                    const bool later = !onRender && 2 * (depicted - f.sourceIndex) >= renderPeriod_;
                    f.cameraTime = f.worldSampleTime = time(later ? f.nextSourceIndex : f.sourceIndex);
                }
                f.samplesInput = newFrame;
                break;
            }
        }
        f.kind = floorTo(j, fillPeriod_) == j ? f.made : FrameKind::Held;
        return f;
    }

    ScheduledFrame frame(std::int64_t k) const {
        ScheduledFrame f = produced(k - lagFrames_);
        const ScheduledFrame now = lagFrames_ == 0 ? f : produced(k);
        f.index = k;
        f.displayTime = static_cast<double>(k) / refreshHz_;
        f.rendersNow = now.rendersNow;
        f.samplesInput = now.samplesInput;
        if (condition_.lateWarp != LateWarp::None) {
            f.samplesInput = true;
            if (f.cameraTime != f.displayTime ||
                (condition_.lateWarp == LateWarp::Depth && f.sceneTime != f.displayTime))
                f.kind = f.made = FrameKind::Warped;
            f.cameraTime = f.displayTime;
            if (condition_.lateWarp == LateWarp::Depth) f.sceneTime = f.displayTime;
        }
        return f;
    }

private:
    Condition condition_;
    double refreshHz_;
    Fill fill_;
    std::int64_t renderPeriod_ = 1, lagFrames_ = 0, fillPeriod_ = 1;
};

// The first frame in [from, to] where the schedule differs from the reference, in words; ""
// when none does. Every field is compared exactly: the instants are the same doubles.
inline std::string firstDifference(const Condition& c, double refreshHz, std::int64_t from, std::int64_t to) {
    const ConditionSchedule now(c, refreshHz);
    const Schedule before(c, refreshHz);
    for (std::int64_t k = from; k <= to; ++k) {
        const ScheduledFrame a = now.frame(k), b = before.frame(k);
        if (a.index != b.index || a.displayTime != b.displayTime || a.kind != b.kind || a.made != b.made ||
            a.cameraTime != b.cameraTime || a.sceneTime != b.sceneTime || a.worldSampleTime != b.worldSampleTime ||
            a.rendersNow != b.rendersNow || a.samplesInput != b.samplesInput || a.sourceIndex != b.sourceIndex ||
            a.nextSourceIndex != b.nextSourceIndex)
            return c.name + " at " + std::to_string(refreshHz) + " Hz differs at frame " + std::to_string(k);
    }
    return "";
}

}  // namespace warplab::condition::reference
