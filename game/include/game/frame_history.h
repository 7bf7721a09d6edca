// What was true at each recent display frame (the camera, the cursor, the world), so a frame
// that depicts an earlier instant -- held, lagged, or one I-frame late -- can be told exactly
// what it shows. Games keep one per thing the conditions look back at.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <stdexcept>

#include "condition/condition.h"

namespace warplab::game {

template <typename T>
class FrameHistory {
public:
    // More than any condition may look back (condition::kMaxLookBackFrames: its lag and two
    // render periods; lag200 at 120 Hz is 24 + 4), with a margin for the frame being made.
    explicit FrameHistory(std::size_t capacity = static_cast<std::size_t>(condition::kMaxLookBackFrames) + 32)
        : capacity_(capacity) {}

    void record(std::int64_t frame, const T& value) {
        if (values_.empty())
            first_ = frame;
        else if (frame != first_ + static_cast<std::int64_t>(values_.size()))
            throw std::logic_error("FrameHistory::record: frames must be recorded one after another");
        values_.push_back(value);
        if (values_.size() > capacity_) {
            values_.pop_front();
            ++first_;
        }
    }
    bool empty() const { return values_.empty(); }
    // The value at `frame`; before the first recorded frame, the first (what the screen
    // showed before anything moved); after the last, the last.
    const T& at(std::int64_t frame) const {
        if (values_.empty()) throw std::logic_error("FrameHistory::at: nothing recorded yet");
        if (frame <= first_) return values_.front();
        const auto offset = static_cast<std::size_t>(frame - first_);
        return offset < values_.size() ? values_[offset] : values_.back();
    }
    void clear() { values_.clear(); }

private:
    std::size_t capacity_;
    std::int64_t first_ = 0;
    std::deque<T> values_;
};

}  // namespace warplab::game
