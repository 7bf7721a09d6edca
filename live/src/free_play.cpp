// Free play: the window loop with nothing recorded, the supervisor's live switching of condition
// and difficulty, and a status line of frame times.
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "free_play_keys.h"
#include "condition/schedule.h"
#include "live/live_session.h"
#include "window_loop.h"

namespace warplab::live {
namespace {

class FreePlayPolicy final : public LoopPolicy {
public:
    FreePlayPolicy(const LiveRun& run, const game::Study& study, const game::DisplaySize& display,
                   std::ostream& progress)
        : condition_(run.freePlayCondition.empty() ? study.conditionNames().front() : run.freePlayCondition),
          level_(run.freePlayLevel),
          game_(study.newFreePlay(run.seed, display, condition_, level_)),
          refreshHz_(study.refreshHz()),
          names_(study.conditions().names()),
          conditions_(study.conditions()),
          progress_(progress) {}

    game::Game& game() override { return *game_; }
    std::string pauseText() const override { return "Free play. Enter resumes, Q ends."; }
    std::string closeText() const override { return "Free play. Enter: keep playing, Q: end it."; }
    void beforeStep(const std::string& keys, std::int64_t frame, game::FrameInput& input) override;
    void stepped(const game::ShownFrame&, const game::FrameInput&) override { game_->takeEvents(); }
    void decorate(const game::ShownFrame& shown, std::int64_t frame, renderer::HudContent& hud) override;
    void presented(const game::ShownFrame&, const FrameTiming& timing) override {
        if (timing.skipped) return;
        late_ += timing.missedVsyncs > 0;
        recentMs_.push_back(timing.frameMs);
        if (recentMs_.size() > static_cast<std::size_t>(refreshHz_)) recentMs_.erase(recentMs_.begin());
    }
    std::string screenshotName(std::int64_t frame) const override { return "free_" + std::to_string(frame); }

    long lateFrames() const { return late_; }

private:
    std::string condition_;
    int level_;
    std::unique_ptr<game::FreePlayGame> game_;
    double refreshHz_;
    std::vector<std::string> names_;  // the presets, then the protocol's own conditions
    condition::ConditionTable conditions_;
    std::ostream& progress_;
    std::vector<double> recentMs_;  // the last second's frame times, for the status line
    long late_ = 0;
    std::string said_;  // why the last key was refused, shown for a while
    std::int64_t saidUntil_ = -1;
};

void FreePlayPolicy::beforeStep(const std::string& keys, std::int64_t frame, game::FrameInput& input) {
    // The supervisor's keys: digits and [ ] pick a condition, U and D the difficulty.
    const double refresh = refreshHz_;
    const FreePlayChoice next =
        applyFreePlayKeys({condition_, level_}, keys, names_,
                          [&](const std::string& condition) { return conditions_.check(condition, refresh).empty(); });
    if (next.condition != condition_ || next.level != level_) {
        try {
            game_->switchTo(next.condition, next.level);
            condition_ = next.condition;
            level_ = next.level;
            progress_ << "free play: " << condition_ << ", level " << level_ << "\n";
        } catch (const std::invalid_argument& e) {
            said_ = e.what();
            saidUntil_ = frame + static_cast<std::int64_t>(2 * refreshHz_);
        }
    }
    input.keys = 0;  // the keys were the supervisor's, not the game's
    input.text.clear();  // ... and so were the letters they typed
}

void FreePlayPolicy::decorate(const game::ShownFrame& shown, std::int64_t frame, renderer::HudContent& hud) {
    std::vector<double> sorted = recentMs_;
    std::sort(sorted.begin(), sorted.end());
    char stats[160];
    std::snprintf(stats, sizeof stats, " | %.1f ms median, %.1f max, %ld late | keys 1-9 [ ] U D Esc",
                  sorted.empty() ? 0.0 : sorted[sorted.size() / 2], sorted.empty() ? 0.0 : sorted.back(), late_);
    hud.status = (frame < saidUntil_ ? said_ : shown.phaseText) + stats;
}

}  // namespace

void runFreePlay(const LiveRun& run, const renderer::DataPaths& paths, std::ostream& progress) {
    WindowLoop loop(run, paths, progress);
    FreePlayPolicy policy(run, loop.study(), loop.display(), progress);
    loop.captureMouse(true);
    loop.run(policy);
    loop.captureMouse(false);
    progress << "free play ended: " << policy.lateFrames() << " late frames\n";
}

}  // namespace warplab::live
