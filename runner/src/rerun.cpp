#include "rerun.h"

#include <nlohmann/json.hpp>

#include "session/records.h"

namespace warplab::runner {
namespace {

// The event without the details that describe the rendering (Game::renderDetailKeys), which
// replay does not redo: such sessions still replay, and export still reports the details.
session::EventRecord withoutRenderNotes(session::EventRecord event, const std::vector<std::string>& keys) {
    bool present = false;
    for (const std::string& key : keys)
        present = present || event.detailJson.find('"' + key + '"') != std::string::npos;
    if (!present) return event;
    auto detail = nlohmann::json::parse(event.detailJson, nullptr, false);
    if (!detail.is_object()) return event;
    for (const std::string& key : keys) detail.erase(key);
    event.detailJson = detail.dump();
    return event;
}

}  // namespace

Rerun rerun(const session::SessionData& data, game::Game& game,
            const std::function<void(std::size_t, const game::ShownFrame&, std::size_t)>& stepped) {
    Rerun result;
    const std::vector<std::string> renderKeys = game.renderDetailKeys();
    for (const auto& e : data.events) result.outcomes += game.isOutcome(e);
    std::size_t eventIndex = 0;
    for (std::size_t i = 0; i < data.inputs.size(); ++i) {
        const session::InputRecord& in = data.inputs[i];
        if (game::resumedBefore(data.header, in.frame)) game.resumeHere();
        const game::ShownFrame shown = game.step({in.mouseDx, in.mouseDy, in.buttons, in.keys, in.text});
        for (const auto& replayed : game.takeEvents()) {
            if (eventIndex >= data.events.size()) {
                // The store ends before this event was committed: nothing more to check.
                break;
            }
            const std::string diff =
                session::firstDifference(withoutRenderNotes(data.events[eventIndex], renderKeys), replayed);
            const auto& logged = data.events[eventIndex];
            if (!diff.empty() && result.difference.empty()) {
                result.difference = "record " + std::to_string(eventIndex + 1) + " (" + logged.type + " at frame " +
                    std::to_string(logged.frame) + "): " + diff;
            }
            if (diff.empty() && game.isOutcome(logged)) ++result.reproduced;
            ++result.events;
            ++eventIndex;
        }
        result.displaySeconds = shown.time;
        ++result.frames;
        if (stepped) stepped(i, shown, eventIndex);
        if (!result.difference.empty()) break;
    }
    if (result.difference.empty() && eventIndex < data.events.size())
        result.difference = "record " + std::to_string(eventIndex + 1) + " (" + data.events[eventIndex].type +
            " at frame " + std::to_string(data.events[eventIndex].frame) +
            ") was logged but the replay never produced it";
    return result;
}

}  // namespace warplab::runner
