#include "source_cache.h"

#include <optional>

namespace warplab::bench {

SourceCache::~SourceCache() {
    for (auto& [key, rendered] : sources_)
        (key.second ? setting_.bandedPool : setting_.plainPool)->giveBack(std::move(rendered.frame));
}

const RenderedSource& SourceCache::source(int index, bool banded) {
    auto it = sources_.find({index, banded});
    if (it != sources_.end()) return it->second;
    const game::BenchSequence& sequence = *setting_.sequence;
    std::optional<scene::FrameDescription> before;
    if (setting_.flowPeriod > 0 && index >= setting_.flowPeriod)
        before = sequence.at((index - setting_.flowPeriod) / setting_.refreshHz);
    RenderedSource s;
    s.frame = (banded ? setting_.bandedPool : setting_.plainPool)->take();
    renderer::renderSource(*setting_.conventional, sequence.at(index / setting_.refreshHz), *s.frame,
                           before ? &*before : nullptr);
    s.images = renderer::readBack(s.frame->gbuffer);
    return sources_.emplace(Key{index, banded}, std::move(s)).first->second;
}

const Correspondence& SourceCache::correspondenceTo(int index, bool banded) {
    auto it = correspondences_.find({index, banded});
    if (it != correspondences_.end()) return it->second;
    const RenderedSource& s = source(index, banded);
    return correspondences_
        .emplace(Key{index, banded},
                 trueCorrespondence(display_, displayImages_.depth, displayImages_.ids, s.frame->depicts,
                                    s.images.depth, s.images.ids))
        .first->second;
}

}  // namespace warplab::bench
