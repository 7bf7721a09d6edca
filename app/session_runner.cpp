#include "app/session_runner.h"

#include <chrono>
#include <cstring>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "game/bot_player.h"
#include "game/shooter_game.h"
#include "protocol/session_store.h"
#include "protocol/shooter_protocol.h"

#ifndef WARPLAB_VERSION
#define WARPLAB_VERSION "0"
#endif

namespace warplab::app {
namespace {

game::FrameInput toGame(const protocol::InputRecord& r) { return {r.mouseDx, r.mouseDy, r.buttons, r.keys}; }

protocol::InputRecord toRecord(std::int64_t frame, double time, const game::FrameInput& in) {
    protocol::InputRecord r;
    r.frame = frame;
    r.displayTime = time;
    r.mouseDx = in.mouseDx;
    r.mouseDy = in.mouseDy;
    r.buttons = in.buttons;
    r.keys = in.keys;
    return r;
}

// Compares a replayed event with the logged one; "" when identical, else the first field.
std::string firstDifference(const protocol::EventRecord& logged, const protocol::EventRecord& replayed) {
    std::ostringstream out;
    out.precision(17);
    auto text = [&](const char* field, const std::string& a, const std::string& b) {
        if (a != b && out.tellp() == 0) out << "field '" << field << "' logged '" << a << "', replayed '" << b << "'";
    };
    auto num = [&](const char* field, double a, double b) {
        // Bit for bit: replay is exact or it is wrong.
        if (std::memcmp(&a, &b, sizeof a) != 0 && out.tellp() == 0)
            out << "field '" << field << "' logged " << a << ", replayed " << b;
    };
    num("frame", static_cast<double>(logged.frame), static_cast<double>(replayed.frame));
    text("type", logged.type, replayed.type);
    text("phase", logged.phase, replayed.phase);
    num("trial", logged.trial, replayed.trial);
    text("mode", logged.mode, replayed.mode);
    num("difficulty", logged.difficulty, replayed.difficulty);
    num("target_speed", logged.targetSpeed, replayed.targetSpeed);
    num("spawn_time", logged.spawnTime, replayed.spawnTime);
    num("event_time", logged.eventTime, replayed.eventTime);
    num("aim_time", logged.aimTime, replayed.aimTime);
    text("world_outcome", logged.worldOutcome, replayed.worldOutcome);
    text("displayed_outcome", logged.displayedOutcome, replayed.displayedOutcome);
    num("angular_error_deg", logged.angularErrorDeg, replayed.angularErrorDeg);
    text("detail", logged.detailJson, replayed.detailJson);
    return out.str();
}

bool isOutcome(const protocol::EventRecord& e) { return e.type == "shot" || e.type == "timeout"; }

}  // namespace

std::string runHeadless(const HeadlessRun& run, std::ostream& progress) {
    const protocol::ShooterProtocol protocol = protocol::loadShooterProtocol(run.protocolPath);
    const double aspect = static_cast<double>(run.displayWidth) / run.displayHeight;

    // The player: a bot, or the input record of an earlier session.
    std::optional<game::BotPlayer> bot;
    std::vector<protocol::InputRecord> recorded;
    if (run.player == "bot" || run.player.rfind("bot:", 0) == 0) {
        std::uint64_t botSeed = run.seed;
        if (run.player.size() > 4) {
            const std::string digits = run.player.substr(4);
            if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 18)
                throw std::invalid_argument("--player bot:SEED needs a whole number, got '" + digits + "'");
            botSeed = std::stoull(digits);
        }
        bot.emplace(botSeed, protocol);
    } else if (run.player.rfind("replay:", 0) == 0) {
        const auto source = protocol::readSession(run.player.substr(7));
        recorded = source.inputs;
        if (recorded.empty()) throw std::runtime_error("session '" + run.player.substr(7) + "' has no input to replay");
    } else {
        throw std::invalid_argument("unknown player '" + run.player + "' (expected bot, bot:SEED or replay:SESSION)");
    }

    protocol::SessionHeader header;
    header.protocolJson = protocol::toJson(protocol);
    header.seed = run.seed;
    header.participant = run.participant;
    header.appVersion = WARPLAB_VERSION;
    header.glRenderer = "none (headless simulation, nothing rendered)";
    header.refreshHz = protocol.refreshHz;
    header.displayWidth = run.displayWidth;
    header.displayHeight = run.displayHeight;
    header.player = run.player;
    auto writer = protocol::SessionWriter::create(run.resultsDir, header);

    game::ShooterGame game(protocol, run.seed, aspect);
    game::FrameInput input;
    std::size_t next = 0;
    std::int64_t lastReport = 0;
    const auto reportEvery = static_cast<std::int64_t>(60.0 * protocol.refreshHz);
    while (!game.finished()) {
        if (!bot) {
            if (next >= recorded.size()) break;  // the recorded session ended here
            input = toGame(recorded[next++]);
        }
        const game::ShownFrame shown = game.step(input);
        writer.addInput(toRecord(shown.frame, shown.time, input));
        writer.addFrame(game.frameRecord(shown));
        for (auto& e : game.takeEvents()) writer.addEvent(e);
        if (game.atCommitPoint()) writer.commit();
        if (bot) input = bot->next(shown);
        if (shown.frame - lastReport >= reportEvery) {
            lastReport = shown.frame;
            progress << "run: " << static_cast<long long>(shown.time) << " s of display time, phase "
                     << game::phaseName(game.phase()) << "\n";
        }
    }
    if (game.finished()) writer.finish();
    else writer.commit();
    return writer.path();
}

ReplayResult replaySession(const std::string& sessionPath) {
    const auto started = std::chrono::steady_clock::now();
    const protocol::SessionData data = protocol::readSession(sessionPath);
    const protocol::ShooterProtocol protocol = protocol::parseShooterProtocol(data.header.protocolJson, sessionPath);
    const double aspect = static_cast<double>(data.header.displayWidth) / data.header.displayHeight;
    game::ShooterGame game(protocol, data.header.seed, aspect);

    ReplayResult result;
    result.note = data.note;
    for (const auto& e : data.events) result.outcomes += isOutcome(e);
    std::size_t eventIndex = 0;
    for (const auto& in : data.inputs) {
        const game::ShownFrame shown = game.step(toGame(in));
        for (const auto& replayed : game.takeEvents()) {
            if (eventIndex >= data.events.size()) {
                // The store ends before this event was committed: nothing more to check.
                break;
            }
            const auto& logged = data.events[eventIndex];
            const std::string diff = firstDifference(logged, replayed);
            if (!diff.empty() && result.difference.empty()) {
                result.difference = "record " + std::to_string(eventIndex + 1) + " (" + logged.type + " at frame " +
                                    std::to_string(logged.frame) + "): " + diff;
            }
            if (diff.empty() && isOutcome(logged)) ++result.reproduced;
            ++result.events;
            ++eventIndex;
        }
        result.displaySeconds = shown.time;
        if (!result.difference.empty()) break;
    }
    if (result.difference.empty() && eventIndex < data.events.size())
        result.difference = "record " + std::to_string(eventIndex + 1) + " (" + data.events[eventIndex].type +
                            " at frame " + std::to_string(data.events[eventIndex].frame) +
                            ") was logged but the replay never produced it";
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

}  // namespace warplab::app
