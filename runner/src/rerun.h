// Playing a stored session's input again, each event the game makes compared with the logged
// one in turn: what replay reports and what resuming a session checks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "game/game.h"
#include "session/session_store.h"

namespace warplab::runner {

struct Rerun {
    std::size_t outcomes = 0;  // scored outcomes logged
    std::size_t reproduced = 0;  // ... and replayed identically
    std::size_t events = 0;  // events compared
    std::string difference;  // the first difference, "" when none
    std::int64_t frames = 0;  // input rows played
    double displaySeconds = 0.0;  // display time of the last frame played
};

// Steps `game` with data.inputs in order, calling stepped(input index, shown, events compared
// so far) after each frame. Stops after the frame of the first difference; an event logged
// that the replay never made is one too.
Rerun rerun(const session::SessionData& data, game::Game& game,
            const std::function<void(std::size_t, const game::ShownFrame&, std::size_t)>& stepped = {});

}  // namespace warplab::runner
