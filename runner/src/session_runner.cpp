#include "runner/session_runner.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "game/registry.h"
#include "session/session_store.h"
#include "rerun.h"
#include "runner/resume.h"

#ifndef WARPLAB_VERSION
#define WARPLAB_VERSION "0"
#endif

namespace warplab::runner {

session::InputRecord toRecord(std::int64_t frame, double time, const game::FrameInput& in) {
    session::InputRecord r;
    r.frame = frame;
    r.displayTime = time;
    r.mouseDx = in.mouseDx;
    r.mouseDy = in.mouseDy;
    r.buttons = in.buttons;
    r.keys = in.keys;
    r.text = in.text;
    return r;
}

namespace {

// The seed after "NAME:" in a player spec, or `fallback` for the bare name.
std::uint64_t playerSeed(const std::string& player, std::size_t nameLength, std::uint64_t fallback) {
    if (player.size() < nameLength) return fallback;  // the bare name; "bot:" needs its seed
    const std::string name = player.substr(0, nameLength - 1);
    const std::string digits = player.substr(nameLength);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 18)
        throw std::invalid_argument("--player " + name + ":SEED needs a whole number, got '" + digits + "'");
    return std::stoull(digits);
}

bool isBot(const std::string& player) { return player == "bot" || player.rfind("bot:", 0) == 0; }
bool isReplay(const std::string& player) { return player.rfind("replay:", 0) == 0; }

std::string unknownPlayer(const std::string& player) {
    return "unknown player '" + player + "' (expected bot, bot:SEED, sim, sim:SEED or replay:SESSION)";
}

}  // namespace

bool isSimulatedParticipant(const std::string& player) { return player == "sim" || player.rfind("sim:", 0) == 0; }

std::string replaySource(const std::string& player) { return isReplay(player) ? player.substr(7) : ""; }

void checkPlayer(const std::string& player) {
    if (isBot(player) || isSimulatedParticipant(player))
        playerSeed(player, 4, 0);
    else if (isReplay(player) && replaySource(player).empty())
        throw std::invalid_argument("--player replay:SESSION needs the SESSION file whose input to play");
    else if (player != "human" && !isReplay(player))
        throw std::invalid_argument(unknownPlayer(player));
}

std::unique_ptr<game::Player> makePlayer(const std::string& player, std::uint64_t sessionSeed, const game::Study& study,
                                         const game::DisplaySize& display, const game::SeeingPlayerMaker& seeing) {
    if (isBot(player)) return study.newBot(playerSeed(player, 4, sessionSeed), display);
    if (isSimulatedParticipant(player)) {
        const std::uint64_t seed = playerSeed(player, 4, sessionSeed);
        if (!seeing)
            throw std::invalid_argument("--player " + player +
                                        " (the simulated participant) runs headless only: add --headless");
        return seeing(seed, study, display);
    }
    if (isReplay(player)) {
        auto source = session::readSession(replaySource(player));
        if (source.inputs.empty())
            throw std::runtime_error("session '" + replaySource(player) + "' has no input to replay");
        return std::make_unique<game::RecordedPlayer>(std::move(source.inputs));
    }
    throw std::invalid_argument(unknownPlayer(player));
}

std::unique_ptr<game::Study> loadRunStudy(const std::string& protocolPath, const std::string& protocolText) {
    return protocolText.empty() ? game::loadStudy(protocolPath) : game::parseStudy(protocolText, protocolPath);
}

session::SessionHeader sessionHeader(const game::Study& study, const std::string& participant, std::uint64_t seed,
                                     const std::string& player, const game::DisplaySize& display) {
    session::SessionHeader header;
    header.protocolJson = study.protocolJson();
    header.seed = seed;
    header.participant = participant;
    header.appVersion = WARPLAB_VERSION;
    header.glRenderer = "none (headless simulation, nothing rendered)";
    header.photonMarker = protocol::nameOf(protocol::PhotonMarker::Off);  // no window draws one
    header.refreshHz = study.refreshHz();
    header.displayWidth = display.width;
    header.displayHeight = display.height;
    header.player = player;
    return header;
}

SessionCommits::SessionCommits(session::SessionWriter& writer, double refreshHz, std::ostream& progress)
    : writer_(writer),
      progress_(progress),
      maxFrames_(std::max<std::int64_t>(1, static_cast<std::int64_t>(kMaxSecondsBetweenCommits * refreshHz))),
      retryFrames_(std::max<std::int64_t>(1, static_cast<std::int64_t>(refreshHz))) {}

void SessionCommits::afterFrame(std::int64_t frame, bool commitPoint) {
    const bool due = commitPoint || frame - lastCommit_ >= maxFrames_ ||
        (writer_.heldCommits() > 0 && frame - lastTry_ >= retryFrames_);
    if (!due) return;
    if (commitPoint || frame - lastCommit_ >= maxFrames_) lastCommit_ = frame;
    lastTry_ = frame;
    writer_.commit();
    tell();
}

std::string SessionCommits::waitingText() const {
    if (writer_.heldCommits() == 0) return "";
    std::ostringstream text;
    text << "Another program holds the write lock on the session file: " << writer_.heldCommits()
         << " commit(s) wait in memory (" << static_cast<long>(writer_.heldForSeconds())
         << " s). Close it (a DB browser, or sqlite3 without -readonly).";
    return text.str();
}

void SessionCommits::tell() {
    for (const std::string& notice : writer_.takeNotices()) progress_ << "warning: " << notice << "\n";
    const bool held = writer_.heldCommits() > 0;
    if (held && !waiting_)
        progress_ << "warning: another program holds the write lock on " << writer_.path()
                  << " (a DB browser, or sqlite3 without -readonly?); the session goes on and keeps "
                     "its commits in memory until the lock is free: a crash meanwhile would lose them\n";
    if (!held && waiting_) progress_ << "note: " << writer_.path() << " is written again; no commit was lost\n";
    waiting_ = held;
}

void SessionCommits::end(bool completed, const std::function<void(const std::string&)>& show) {
    const auto waiting = [&](double seconds, session::SessionWriter::WaitingFor what) {
        const std::string held = std::to_string(static_cast<long>(seconds)) + " s";
        const std::string line = what == session::SessionWriter::WaitingFor::WriteLock
            ? "Saving the session: another program has held the write lock on " + writer_.path() + " for " + held +
                ". Close it (a DB browser, or sqlite3 without -readonly)."
            : "Finishing the session: another program (export, replay, a DB browser) has been reading " +
                writer_.path() + " for " + held +
                ", which keeps its last commits out of the file; if it goes on, the session is written again whole.";
        if (show) show(line);
        if (static_cast<long>(seconds) % 5 == 1) progress_ << "waiting: " << line << "\n";
    };
    if (completed) {
        writer_.finish(waiting);
    } else {
        writer_.close(waiting);
    }
    tell();
}

std::string runHeadless(const HeadlessRun& run, std::ostream& progress) {
    // A resumed session plays the interrupted one's protocol, seed and display, whatever the run says.
    std::optional<ResumePoint> resume;
    if (!run.resumeFrom.empty()) {
        resume = findResumePoint(run.resumeFrom);
        progress << resumeSummary(*resume) << "\n";
    }
    const session::SessionHeader* was = resume ? &resume->stored.header : nullptr;
    const auto study =
        was ? game::parseStudy(was->protocolJson, run.resumeFrom) : loadRunStudy(run.protocolPath, run.protocolText);
    const game::DisplaySize display = was ? game::DisplaySize{was->displayWidth, was->displayHeight}
                                          : game::DisplaySize{run.displayWidth, run.displayHeight};
    const std::uint64_t seed = was ? was->seed : run.seed;
    const auto player = makePlayer(run.player, seed, *study, display, run.seeingPlayer);

    session::SessionHeader header = sessionHeader(*study, run.participant, seed, run.player, display);
    header.planId = run.planId;
    if (resume) header = resumedHeader(*resume, header);
    // A player that sees drew the frames it saw: its inputs are reproducible on the same GL.
    if (const std::string drawn = player->perceivedWith(); !drawn.empty()) header.glRenderer = drawn;
    header.playerModel = player->model();
    auto writer = session::SessionWriter::create(run.resultsDir, header,
                                                 resume ? keptRows(*resume) : session::SessionWriter::FirstCommit{});

    const auto game = study->newGame(seed, display);
    SessionCommits commits(writer, study->refreshHz(), progress);
    game::FrameInput input = player->first();
    // The kept frames, shown to the player as they were: it stands where it stood then.
    if (resume) replayKeptFrames(*resume, *game, [&](const game::ShownFrame& shown) { input = player->next(shown); });
    std::int64_t lastReport = 0;
    const auto reportEvery = static_cast<std::int64_t>(60.0 * study->refreshHz());
    while (!game->finished() && player->hasMore()) {
        const game::ShownFrame shown = game->step(input);
        writer.addInput(toRecord(shown.frame, shown.time, input));
        writer.addFrame(game->frameRecord(shown));
        for (auto& e : game->takeEvents()) writer.addEvent(e);
        commits.afterFrame(shown.frame, game->atCommitPoint());
        input = player->next(shown);
        if (shown.frame - lastReport >= reportEvery) {
            lastReport = shown.frame;
            progress << "run: " << static_cast<long long>(shown.time) << " s of display time, phase " << game->phase()
                     << "\n";
        }
    }
    commits.end(game->finished());
    return writer.path();
}

int replayExitCode(const ReplayResult& result) {
    if (!result.difference.empty()) return kReplayDiffers;
    if (result.damaged) return kReplayDamaged;
    if (!result.completed) return kReplayIncomplete;
    return kReplayReproduced;
}

ReplayResult replaySession(const std::string& sessionPath) {
    const auto started = std::chrono::steady_clock::now();
    const session::SessionData data = session::readSession(sessionPath);
    const auto study = game::parseStudy(data.header.protocolJson, sessionPath);
    const auto game = study->newGame(data.header.seed, {data.header.displayWidth, data.header.displayHeight});
    const Rerun r = rerun(data, *game);

    ReplayResult result;
    result.note = data.note;
    result.completed = data.completed;
    result.damaged = data.damaged;
    result.outcomes = r.outcomes;
    result.reproduced = r.reproduced;
    result.events = r.events;
    result.difference = r.difference;
    result.frames = r.frames;
    result.displaySeconds = r.displaySeconds;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return result;
}

}  // namespace warplab::runner
