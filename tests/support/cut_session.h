// A session as a kill leaves it, for the tests of resuming: the whole session's first
// `keptEvents` events, and its inputs and frames up to the last of them, committed but never
// finished.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "session/session_store.h"

namespace warplab::testing_sessions {

inline std::string cutSession(const session::SessionData& whole, std::size_t keptEvents, const std::string& dir) {
    const std::int64_t lastFrame = whole.events.at(keptEvents - 1).frame;
    auto writer = session::SessionWriter::create(dir, whole.header);
    for (const auto& in : whole.inputs)
        if (in.frame <= lastFrame) writer.addInput(in);
    for (const auto& frame : whole.frames)
        if (frame.frame <= lastFrame) writer.addFrame(frame);
    for (std::size_t i = 0; i < keptEvents; ++i) writer.addEvent(whole.events[i]);
    writer.commit();  // not finished: an interrupted session
    return writer.path();
}

}  // namespace warplab::testing_sessions
