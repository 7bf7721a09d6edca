// The source frames the methods of one display frame read, each rendered once per source
// instant and kind (plain or with the guard band) however many methods read it, with the
// scene's exact correspondence from the displayed frame into it.
#pragma once

#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "bench/ground_truth.h"
#include "bench/sequences.h"
#include "renderer/conventional.h"
#include "renderer/upconvert.h"

namespace warplab::bench {

// Source frames allocated once and reused: a freshly allocated texture costs first-touch work
// that would otherwise be timed in whichever pass samples it first (a warp-full pass took
// 104-143 ms or 23-32 ms on llvmpipe depending on the source it read).
class SourcePool {
public:
    SourcePool(int width, int height, renderer::GuardBand band) : width_(width), height_(height), band_(band) {}
    std::unique_ptr<renderer::SourceFrame> take() {
        if (free_.empty()) return std::make_unique<renderer::SourceFrame>(width_, height_, band_);
        auto frame = std::move(free_.back());
        free_.pop_back();
        return frame;
    }
    void giveBack(std::unique_ptr<renderer::SourceFrame> frame) { free_.push_back(std::move(frame)); }

private:
    int width_, height_;
    renderer::GuardBand band_;
    std::vector<std::unique_ptr<renderer::SourceFrame>> free_;
};

// A conventionally rendered frame with its read-back depth and ids (for the scene's exact
// correspondences), kept while a display frame needs it.
struct RenderedSource {
    std::unique_ptr<renderer::SourceFrame> frame;
    renderer::GBufferImages images;
};

// What the cache needs to render a source: untimed, like the rest of a source's render.
struct SourceSetting {
    renderer::ConventionalRenderer* conventional = nullptr;
    SourcePool* plainPool = nullptr;
    SourcePool* bandedPool = nullptr;
    const game::BenchSequence* sequence = nullptr;
    double refreshHz = 120.0;
    int flowPeriod = 0;  // BenchPlan::flowPeriod
};

// The sources of one display frame, by display-frame index and whether they have the guard
// band, rendered on first use; their frames go back to the pools when the cache goes.
class SourceCache {
public:
    // `display` and `displayImages`: the ground truth of the displayed instant, which
    // correspondenceTo maps from. Both must outlive the cache.
    SourceCache(const SourceSetting& setting, const scene::FrameDescription& display,
                const renderer::GBufferImages& displayImages)
        : setting_(setting), display_(display), displayImages_(displayImages) {}
    ~SourceCache();
    SourceCache(const SourceCache&) = delete;
    SourceCache& operator=(const SourceCache&) = delete;

    const RenderedSource& source(int index, bool banded);
    const Correspondence& correspondenceTo(int index, bool banded);

private:
    using Key = std::pair<int, bool>;
    SourceSetting setting_;
    const scene::FrameDescription& display_;
    const renderer::GBufferImages& displayImages_;
    std::map<Key, RenderedSource> sources_;
    std::map<Key, Correspondence> correspondences_;
};

}  // namespace warplab::bench
